#pragma once
/// \file
/// Reads the labelled real residual cases (tests/data/screening_cases, made by
/// examples/screening_cases/hbos-screening-cases; format in docs/screening_cases.md) into one
/// hbos::Matchesd per frame pair plus the labels and evidence columns. Test support, not part of
/// the library: header-only, standard library + Eigen + hbos/screening.hpp.
///
/// A scene folder holds `pairs.csv` (one row per frame pair: frames, rough-pose information) and
/// `pair_NN.csv` (one row per match, with the residual under each rough pose). A case is a scene
/// read under one rough pose (`CasePose`): the manifest `cases.json` lists them. Every malformed
/// file, line or field throws hbos::InvalidArgument naming the file, line, column and value.

#include <hbos/screening.hpp>

#include <Eigen/Core>
#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace hbos_test {

/// The pose the predictions of a case are made with.
enum class CasePose {
  Ransac,       ///< cv::solvePnPRansac on the pair's matches (the front end's rough pose)
  PerturbedGt,  ///< the reference pose moved by 0.2 deg / 3 mm about / along random axes
  Reference,    ///< the reference pose itself (ground truth refined on the static matches)
};

/// `ransac`, `pgt`, `reference` (the manifest's spelling); throws on anything else.
[[nodiscard]] inline CasePose parse_case_pose(const std::string& name) {
  if (name == "ransac") return CasePose::Ransac;
  if (name == "pgt") return CasePose::PerturbedGt;
  if (name == "reference") return CasePose::Reference;
  throw hbos::InvalidArgument("unknown rough pose '" + name + "' (ransac, pgt, reference)");
}

/// One frame pair: the matches as a screen sees them, and per match the labels and evidence.
/// Index i of every vector is match i of `matches`.
struct CasePair {
  std::string file;  ///< path of the pair's CSV, for messages
  /// predicted / observed [px, undistorted], sigma = 1.2^octave, on_dynamic_mask = on_mask (when
  /// loaded with flag_on_mask; otherwise false)
  hbos::Matchesd matches;
  std::vector<std::uint8_t> dynamic;  ///< 1 = either keypoint on a composited person (exact label)
  std::vector<std::uint8_t> gross;    ///< 1 = static, residual under ground truth > 3 sigma
  std::vector<std::uint8_t> on_mask;  ///< 1 = observed keypoint within 15 px of the (degraded) mask
  std::vector<int> octave;            ///< of the observed keypoint
  std::vector<int> track_id;          ///< chain of the previous keypoint over the case; -1 = none
  std::vector<double> depth_m;        ///< [m] at the observed keypoint, 0 = none
  std::vector<double> prev_depth_m;   ///< [m] at the previous keypoint (> 0)
  /// [px] to the nearest masked pixel; -1 = the scene has no mask; +inf = it has one, but this
  /// frame's is empty (a missed detection)
  std::vector<double> mask_distance_px;
  Eigen::Matrix2Xd reference_residual;  ///< [px] observed - prediction under the reference pose

  int prev_frame = 0;      ///< sequence index of the previous frame
  int cur_frame = 0;       ///< sequence index of the current frame
  bool ransac_ok = false;  ///< RANSAC succeeded (else its constant-velocity fallback was used)
  int ransac_inliers = 0;  ///< of RANSAC's 1 px consensus
  double rough_rotation_error_deg = 0.0;    ///< the case's rough pose vs the reference [deg]
  double rough_translation_error_mm = 0.0;  ///< the case's rough pose vs the reference [mm]

  [[nodiscard]] Eigen::Index size() const { return matches.size(); }
  /// |r_i| / sigma_i under the rough pose [px/sigma].
  [[nodiscard]] double whitened_residual(Eigen::Index i) const {
    return matches.residual(i).norm() / matches.sigma(i);
  }
};

/// One case: a scene folder read under one rough pose.
struct ScreeningCase {
  std::string name;  ///< the scene folder's name
  CasePose pose = CasePose::Ransac;
  std::vector<CasePair> pairs;

  /// No match of any pair is dynamic (the static sequence).
  [[nodiscard]] bool is_static() const {
    for (const CasePair& p : pairs)
      for (const std::uint8_t d : p.dynamic)
        if (d != 0) return false;
    return true;
  }
};

namespace cases_detail {

inline const char* const kPairHeader =
    "ransac_du,ransac_dv,pgt_du,pgt_dv,reference_du,reference_dv,observed_u,observed_v,"
    "octave,depth_m,prev_depth_m,mask_distance_px,on_mask,dynamic,gross,track_id";
inline const char* const kPairsHeader =
    "pair,prev_frame,cur_frame,prev_stamp,cur_stamp,matches,dynamic,gross,ransac_ok,"
    "ransac_inliers,ransac_rotation_error_deg,ransac_translation_error_mm,"
    "pgt_rotation_error_deg,pgt_translation_error_mm,gt_rotation_error_deg,"
    "gt_translation_error_mm,reference_matches";

/// Splits a header into its column names.
inline std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> out;
  std::string field;
  std::istringstream in(line);
  while (std::getline(in, field, ',')) out.push_back(field);
  if (!line.empty() && line.back() == ',') out.emplace_back();
  return out;
}

/// Reads the comma-separated fields of one CSV line into numbers, naming file:line and column on
/// any error (wrong count, not a number, not finite).
class LineReader {
 public:
  LineReader(const std::string& file, int line, const std::string& text,
             const std::vector<std::string>& columns)
      : file_(file), line_(line), columns_(columns) {
    const char* p = text.c_str();
    const char* end = p + text.size();
    while (true) {
      const char* comma = std::find(p, end, ',');
      fields_.emplace_back(p, comma);
      if (comma == end) break;
      p = comma + 1;
    }
    hbos::detail::require(fields_.size() == columns_.size(), file_, ":", line_, ": expected ",
                          columns_.size(), " fields, got ", fields_.size());
  }
  [[nodiscard]] double real(std::size_t k) const {
    const double v = number(k);
    hbos::detail::require(std::isfinite(v), file_, ":", line_, ": column '", columns_[k],
                          "' is not a finite number: '", fields_[k], "'");
    return v;
  }
  /// A number that may be `inf`.
  [[nodiscard]] double number(std::size_t k) const {
    const std::string& f = fields_[k];
    errno = 0;
    char* stop = nullptr;
    const double v = std::strtod(f.c_str(), &stop);
    hbos::detail::require(!f.empty() && stop == f.c_str() + f.size() && errno == 0 &&
                              !std::isnan(v) && v != -HUGE_VAL,
                          file_, ":", line_, ": column '", columns_[k], "' is not a number: '", f,
                          "'");
    return v;
  }
  [[nodiscard]] int integer(std::size_t k, int lo, int hi) const {
    const double v = real(k);
    hbos::detail::require(v == std::floor(v) && v >= lo && v <= hi, file_, ":", line_, ": column '",
                          columns_[k], "' must be an integer in [", lo, ", ", hi, "], got '",
                          fields_[k], "'");
    return static_cast<int>(v);
  }
  [[nodiscard]] std::uint8_t flag(std::size_t k) const {
    return static_cast<std::uint8_t>(integer(k, 0, 1));
  }

 private:
  std::string file_;
  int line_;
  const std::vector<std::string>& columns_;
  std::vector<std::string> fields_;
};

/// Opens `path` and checks that its first line is `header`.
inline std::ifstream open_csv(const std::string& path, const char* header,
                              std::vector<std::string>& columns) {
  std::ifstream in(path);
  hbos::detail::require(in.good(), "cannot open '", path, "'");
  std::string first;
  std::getline(in, first);
  hbos::detail::require(first == header, path, ":1: unexpected header '", first, "', expected '",
                        header, "'");
  columns = split(first);
  return in;
}

/// Passes the depth and mask distance to Matches when it takes them (Matches::set_depth and
/// set_mask_distance, the screen's evidence); with a Matches that has no such setters, nothing.
/// The predicted point's depth in the current camera is approximated by the previous keypoint's
/// depth (one frame apart: ~1 cm at 30 Hz). A mask distance of -1 (no mask) stays unset.
template <class M>
auto set_evidence(M& m, Eigen::Index i, double prev_depth, double distance, int)
    -> decltype(m.set_depth(i, prev_depth), m.set_mask_distance(i, distance), void()) {
  m.set_depth(i, prev_depth);
  if (distance >= 0.0) m.set_mask_distance(i, distance);
}
template <class M>
void set_evidence(M&, Eigen::Index, double, double, long) {}

inline void read_pair_rows(CasePair& pair, CasePose pose, bool flag_on_mask) {
  std::vector<std::string> columns;
  std::ifstream in = open_csv(pair.file, kPairHeader, columns);
  std::vector<double> reference;
  std::string text;
  int line = 1;
  pair.matches.clear();
  // The residual columns of the chosen pose: observed - predicted [px].
  const std::size_t du = pose == CasePose::Ransac ? 0 : pose == CasePose::PerturbedGt ? 2 : 4;
  while (std::getline(in, text)) {
    ++line;
    if (text.empty()) continue;
    const LineReader r(pair.file, line, text, columns);
    const Eigen::Vector2d observed(r.real(6), r.real(7));
    const Eigen::Vector2d predicted = observed - Eigen::Vector2d(r.real(du), r.real(du + 1));
    const int octave = r.integer(8, 0, 64);
    const double depth = r.real(9), prev_depth = r.real(10), distance = r.number(11);
    hbos::detail::require(depth >= 0.0 && prev_depth > 0.0 && distance >= -1.0, pair.file, ":",
                          line, ": depths must be >= 0 (previous > 0) and mask distance >= -1");
    const std::uint8_t on_mask = r.flag(12);
    pair.matches.add(predicted, observed, hbos::sigma_from_octave(octave),
                     flag_on_mask && on_mask != 0);
    set_evidence(pair.matches, pair.matches.size() - 1, prev_depth, distance, 0);
    pair.octave.push_back(octave);
    pair.depth_m.push_back(depth);
    pair.prev_depth_m.push_back(prev_depth);
    pair.mask_distance_px.push_back(distance);
    pair.on_mask.push_back(on_mask);
    pair.dynamic.push_back(r.flag(13));
    pair.gross.push_back(r.flag(14));
    pair.track_id.push_back(r.integer(15, -1, 1 << 30));
    reference.push_back(r.real(4));
    reference.push_back(r.real(5));
  }
  pair.reference_residual =
      Eigen::Map<const Eigen::Matrix2Xd>(reference.data(), 2, pair.matches.size());
}

}  // namespace cases_detail

/// Loads the scene in `folder` with the predictions of `pose`. With `flag_on_mask`, on_mask
/// becomes the matches' dynamic-mask prior (hbos::ScreenConfig::flagged decides what a screen
/// does with it).
[[nodiscard]] inline ScreeningCase load_screening_case(const std::string& folder, CasePose pose,
                                                       bool flag_on_mask = true) {
  namespace fs = std::filesystem;
  ScreeningCase c;
  c.name = fs::path(folder).filename().string();
  c.pose = pose;
  const std::string table = (fs::path(folder) / "pairs.csv").string();
  std::vector<std::string> columns;
  std::ifstream in = cases_detail::open_csv(table, cases_detail::kPairsHeader, columns);
  std::string text;
  int line = 1;
  while (std::getline(in, text)) {
    ++line;
    if (text.empty()) continue;
    const cases_detail::LineReader r(table, line, text, columns);
    CasePair p;
    const int index = r.integer(0, 0, 9999);
    hbos::detail::require(index == static_cast<int>(c.pairs.size()), table, ":", line,
                          ": pairs must be numbered 0, 1, ... in order, got ", index);
    char name[32];
    std::snprintf(name, sizeof name, "pair_%02d.csv", index);
    p.file = (fs::path(folder) / name).string();
    p.prev_frame = r.integer(1, 0, 1 << 30);
    p.cur_frame = r.integer(2, 0, 1 << 30);
    const int n = r.integer(5, 0, 1 << 30), dynamic = r.integer(6, 0, n),
              gross = r.integer(7, 0, n);
    p.ransac_ok = r.flag(8) != 0;
    p.ransac_inliers = r.integer(9, 0, 1 << 30);
    const std::size_t error = pose == CasePose::Ransac        ? 10
                              : pose == CasePose::PerturbedGt ? 12
                                                              : 0;
    p.rough_rotation_error_deg = error == 0 ? 0.0 : r.real(error);
    p.rough_translation_error_mm = error == 0 ? 0.0 : r.real(error + 1);
    cases_detail::read_pair_rows(p, pose, flag_on_mask);
    long long d = 0, g = 0;
    for (Eigen::Index i = 0; i < p.size(); ++i) {
      d += p.dynamic[static_cast<std::size_t>(i)];
      g += p.gross[static_cast<std::size_t>(i)];
    }
    hbos::detail::require(p.size() == n && d == dynamic && g == gross, p.file, ": has ", p.size(),
                          " matches, ", d, " dynamic, ", g, " gross; ", table, ":", line, " says ",
                          n, ", ", dynamic, ", ", gross);
    c.pairs.push_back(std::move(p));
  }
  hbos::detail::require(!c.pairs.empty(), table, ": lists no pair");
  return c;
}

/// The scene folders under `root` (sub-folders with a pairs.csv), sorted by name.
[[nodiscard]] inline std::vector<std::string> list_case_folders(const std::string& root) {
  namespace fs = std::filesystem;
  hbos::detail::require(fs::is_directory(root), "cases folder '", root, "' does not exist");
  std::vector<std::string> out;
  for (const auto& entry : fs::directory_iterator(root))
    if (entry.is_directory() && fs::is_regular_file(entry.path() / "pairs.csv"))
      out.push_back(entry.path().string());
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace hbos_test
