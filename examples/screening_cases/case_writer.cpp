#include "case_writer.hpp"

#include "common/atomic_file.hpp"

#include <fmt/format.h>

#include <cmath>
#include <filesystem>

namespace hbos::cases {

namespace {

// x rounded to `decimals`, with -0 printed as 0, so equal values always give equal bytes.
std::string fixed(double x, int decimals) {
  const double scale = std::pow(10.0, decimals);
  double r = std::round(x * scale) / scale;
  if (r == 0.0) r = 0.0;
  return fmt::format("{:.{}f}", r, decimals);
}

// -1 = the scene has no mask; inf = it has one, but not in this frame (a missed detection).
std::string mask_distance(double d) {
  if (std::isinf(d)) return "inf";
  return d < 0.0 ? std::string("-1") : fixed(d, 1);
}

std::string pair_csv(const PairRecord& pair) {
  std::string out = pair_csv_header();
  out += '\n';
  for (const MatchRow& m : pair.rows) {
    out += fmt::format(
        "{},{},{},{},{},{},{},{},{},{},{},{},{:d},{:d},{:d},{}\n",
        fixed(m.observed.x() - m.ransac.x(), 2), fixed(m.observed.y() - m.ransac.y(), 2),
        fixed(m.observed.x() - m.perturbed.x(), 2), fixed(m.observed.y() - m.perturbed.y(), 2),
        fixed(m.observed.x() - m.reference.x(), 2), fixed(m.observed.y() - m.reference.y(), 2),
        fixed(m.observed.x(), 2), fixed(m.observed.y(), 2), m.octave, fixed(m.depth_m, 3),
        fixed(m.prev_depth_m, 3), mask_distance(m.mask_distance_px), static_cast<int>(m.on_mask),
        static_cast<int>(m.dynamic), static_cast<int>(m.gross), m.track_id);
  }
  return out;
}

int count(const PairRecord& pair, bool MatchRow::*field) {
  int n = 0;
  for (const MatchRow& m : pair.rows) n += (m.*field) ? 1 : 0;
  return n;
}

}  // namespace

const char* pair_csv_header() {
  return "ransac_du,ransac_dv,pgt_du,pgt_dv,reference_du,reference_dv,observed_u,observed_v,"
         "octave,depth_m,prev_depth_m,mask_distance_px,on_mask,dynamic,gross,track_id";
}

const char* pairs_csv_header() {
  return "pair,prev_frame,cur_frame,prev_stamp,cur_stamp,matches,dynamic,gross,ransac_ok,"
         "ransac_inliers,ransac_rotation_error_deg,ransac_translation_error_mm,"
         "pgt_rotation_error_deg,pgt_translation_error_mm,gt_rotation_error_deg,"
         "gt_translation_error_mm,reference_matches";
}

nlohmann::ordered_json write_case(const std::string& folder, const CaseSpec& spec,
                                  const std::vector<PairRecord>& pairs) {
  namespace fs = std::filesystem;
  fs::create_directories(folder);
  nlohmann::ordered_json entry;
  entry["name"] = spec.name;
  entry["dir"] = spec.name;
  nlohmann::ordered_json people = nlohmann::ordered_json::array();
  for (const PersonMotion& p : spec.people) {
    people.push_back(
        {{"person", std::string(1, p.person)},
         {"scale", p.scale},
         {"depth_m", p.depth_m},
         {"start_px", {p.start_px.x(), p.start_px.y()}},
         {"velocity_m_s", {p.velocity_m_s.x(), p.velocity_m_s.y(), p.velocity_m_s.z()}},
         {"speed_m_s", std::stod(fixed(p.velocity_m_s.norm(), 3))}});
  }
  entry["people"] = people;
  entry["speed"] = spec.speed;
  entry["mask"] = to_string(spec.mask);
  if (spec.mask == MaskKind::kDegraded) {
    entry["degradation"] = {{"erosion_px", spec.degradation.erosion_px},
                            {"unmasked_lower", spec.degradation.unmasked_lower},
                            {"missing_every", spec.degradation.missing_every}};
  }
  entry["seed"] = spec.seed;
  entry["perturbation"] = {{"rotation_deg", spec.perturb_deg},
                           {"translation_mm", spec.perturb_m * 1000.0}};
  entry["reverse"] = spec.reverse;

  std::string table = pairs_csv_header();
  table += '\n';
  nlohmann::ordered_json pair_list = nlohmann::ordered_json::array();
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    const PairRecord& p = pairs[k];
    const std::string file = fmt::format("pair_{:02d}.csv", k);
    hbos::examples::write_file_atomically(fs::path(folder) / file, pair_csv(p));
    const int dynamic = count(p, &MatchRow::dynamic), gross = count(p, &MatchRow::gross);
    table += fmt::format(
        "{},{},{},{:.6f},{:.6f},{},{},{},{:d},{},{},{},{},{},{},{},{}\n", k, p.prev_frame,
        p.cur_frame, p.prev_stamp, p.cur_stamp, p.rows.size(), dynamic, gross,
        static_cast<int>(p.ransac_ok), p.ransac_inliers, fixed(p.ransac_rotation_error_deg, 4),
        fixed(p.ransac_translation_error_m * 1000.0, 3), fixed(p.perturbed_rotation_error_deg, 4),
        fixed(p.perturbed_translation_error_m * 1000.0, 3), fixed(p.gt_rotation_error_deg, 4),
        fixed(p.gt_translation_error_m * 1000.0, 3), p.reference_matches);
    const auto pose = [](double deg, double m) {
      return nlohmann::ordered_json{{"rotation_error_deg", std::stod(fixed(deg, 4))},
                                    {"translation_error_mm", std::stod(fixed(m * 1000.0, 3))}};
    };
    nlohmann::ordered_json ransac = pose(p.ransac_rotation_error_deg, p.ransac_translation_error_m);
    ransac["ok"] = p.ransac_ok;
    ransac["inliers"] = p.ransac_inliers;
    pair_list.push_back(
        {{"file", file},
         {"prev_frame", p.prev_frame},
         {"cur_frame", p.cur_frame},
         {"matches", p.rows.size()},
         {"dynamic", dynamic},
         {"gross", gross},
         {"ransac", ransac},
         {"pgt", pose(p.perturbed_rotation_error_deg, p.perturbed_translation_error_m)},
         {"gt_vs_reference", pose(p.gt_rotation_error_deg, p.gt_translation_error_m)},
         {"reference_matches", p.reference_matches}});
  }
  hbos::examples::write_file_atomically(fs::path(folder) / "pairs.csv", table);
  entry["pairs"] = pair_list;
  return entry;
}

}  // namespace hbos::cases
