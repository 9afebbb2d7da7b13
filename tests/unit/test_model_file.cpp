// Tests of hbos/model_file.hpp (and Histogram::parts/from_parts, Hbos::from_histograms): a saved
// and loaded model scores bit for bit like the original under every mode, binning, tail and
// periodic spec; damaged files are refused with the line and field named; saving is atomic.

#include <hbos/model_file.hpp>
#include <hbos/pyod/model_file.hpp>

#include "../support/mixed_features.hpp"

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

namespace {

using hbos::test::mixed_features;
using hbos::test::same_bits;

template <class Scalar>
using Matrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;

/// Data to score: the training rows, shifted copies reaching outside the fitted range.
template <class Scalar>
Matrix<Scalar> make_queries(const Matrix<Scalar>& train) {
  Matrix<Scalar> q(3 * train.rows(), train.cols());
  q << train, (train.array() * Scalar(1.3)).matrix(), (train.array() - Scalar(2.5)).matrix();
  return q;
}

/// Every spec the format has to carry: named, so a failure says which one.
std::vector<std::pair<std::string, hbos::HbosParams>> all_modes() {
  std::vector<std::pair<std::string, hbos::HbosParams>> modes;
  modes.emplace_back("default (5 bins x 5 shifts)", hbos::HbosParams{});
  hbos::HbosParams p;
  p.feature.binning.shifts = 1;
  p.feature.binning.bins = 10;
  modes.emplace_back("classic static 10", p);
  using Rule = hbos::BinCountRule;
  for (const auto& [name, rule] :
       std::vector<std::pair<std::string, Rule>>{{"sqrt", Rule::Sqrt},
                                                 {"sturges", Rule::Sturges},
                                                 {"scott", Rule::Scott},
                                                 {"freedman-diaconis", Rule::FreedmanDiaconis},
                                                 {"birge-rozenblac", Rule::BirgeRozenblac}}) {
    p = {};
    p.feature.binning.rule = rule;
    modes.emplace_back("equal width, " + name, p);
    p.feature.binning.method = hbos::BinningMethod::EqualFrequency;
    modes.emplace_back("equal frequency, " + name, p);
  }
  p = {};
  p.feature.binning.method = hbos::BinningMethod::EqualFrequency;
  p.feature.binning.bins = 7;
  modes.emplace_back("equal frequency, 7", p);
  p = {};
  p.feature.binning.method = hbos::BinningMethod::FixedWidth;
  p.feature.binning.width = 0.25;
  p.feature.binning.origin = 0.1;
  p.feature.binning.shifts = 3;
  modes.emplace_back("fixed width 0.25 x 3 shifts", p);
  p = {};
  p.feature.tail = hbos::Tail::Upper;
  modes.emplace_back("upper tail", p);
  p.feature.tail = hbos::Tail::Lower;
  p.scoring.empty_bin_count = 0.25;
  p.scoring.range_tolerance = 1.5;
  modes.emplace_back("lower tail, other scoring options", p);
  // Per-feature specs: a tail, a fixed width, dynamic bins and an angle (periodic ASH).
  p = {};
  p.features.resize(4);
  p.features[0].tail = hbos::Tail::Upper;
  p.features[1].binning.method = hbos::BinningMethod::FixedWidth;
  p.features[1].binning.width = 0.5;
  p.features[2].binning.method = hbos::BinningMethod::EqualFrequency;
  p.features[3] = hbos::angle_feature(12);
  p.features[3].binning.shifts = 3;
  modes.emplace_back("per-feature specs with a periodic feature", p);
  p.features[3] = hbos::angle_feature(8);
  p.features[3].binning.method = hbos::BinningMethod::FixedWidth;
  p.features[3].binning.width = 0.7;
  modes.emplace_back("periodic fixed width", p);
  return modes;
}

template <class Scalar>
void check_round_trip(const Matrix<Scalar>& x, const hbos::HbosParams& params) {
  const auto model = hbos::Hbos<Scalar>::fit(x, params);
  const std::string text = hbos::to_model_text(model);
  const auto loaded = hbos::hbos_from_model_text<Scalar>(text);
  const Matrix<Scalar> q = make_queries(x);
  CHECK(same_bits(model.score(q), loaded.score(q)));
  CHECK(same_bits(model.contributions(q), loaded.contributions(q)));
  CHECK(loaded.n_samples() == model.n_samples());
  CHECK(loaded.params().features.size() == model.params().features.size());
  for (Eigen::Index j = 0; j < model.n_features(); ++j) {
    CHECK(loaded.histogram(j).bin_contributions() == model.histogram(j).bin_contributions());
    CHECK(loaded.histogram(j).cap() == model.histogram(j).cap());
    CHECK(loaded.histogram(j).mode() == model.histogram(j).mode());
  }
  // Writing the loaded model gives the same text: nothing is lost or re-rounded.
  CHECK(hbos::to_model_text(loaded) == text);
  // Version 1 (the layout older releases read) round-trips too, and loads to the same scores.
  const std::string v1 = hbos::to_model_text(model, 1);
  const auto loaded_v1 = hbos::hbos_from_model_text<Scalar>(v1);
  CHECK(same_bits(model.score(q), loaded_v1.score(q)));
  CHECK(hbos::to_model_text(loaded_v1, 1) == v1);
  // Re-saved as version 2, a version 1 model lists its edges (the width they were placed with
  // is not in version 1) and still scores the same.
  const auto again = hbos::hbos_from_model_text<Scalar>(hbos::to_model_text(loaded_v1));
  CHECK(same_bits(model.score(q), again.score(q)));
}

/// The feature-at-a-time writer writes save_model's file, and the reader gives back the
/// histograms load_hbos holds: scoring feature by feature gives the same bits.
template <class Scalar>
void check_streamed(const Matrix<Scalar>& x, const hbos::HbosParams& params,
                    const std::string& path) {
  const auto model = hbos::Hbos<Scalar>::fit(x, params);
  {
    hbos::ModelFileWriter<Scalar> writer(path, params, x.cols(), x.rows());
    for (Eigen::Index j = 0; j < x.cols(); ++j) writer.add(model.histogram(j));
    writer.commit();
  }
  std::ifstream in(path, std::ios::binary);
  const std::string written((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  CHECK(written == hbos::to_model_text(model));
  const Matrix<Scalar> q = make_queries(x);
  for (const int version : {2, 1}) {
    if (version == 1) hbos::save_model(model, path, 1);
    hbos::ModelFileReader<Scalar> reader(path);
    CHECK(reader.version() == version);
    CHECK(reader.n_features() == x.cols());
    CHECK(reader.n_samples() == x.rows());
    Eigen::Matrix<Scalar, Eigen::Dynamic, 1> scores(q.rows());
    for (Eigen::Index j = 0; j < q.cols(); ++j) {
      const hbos::Histogram<Scalar> h = reader.next();
      CHECK(h.bin_contributions() == model.histogram(j).bin_contributions());
      const Eigen::Matrix<Scalar, Eigen::Dynamic, 1> column = q.col(j);
      h.contributions_into(hbos::detail::ColumnView<Scalar>{column.data(), column.size(), 1},
                           scores.data(), j > 0, j);
    }
    CHECK_NOTHROW(reader.finish());
    CHECK(same_bits(scores, model.score(q)));
  }
  std::filesystem::remove(path);
}

std::string temp_path(const std::string& name, const std::string& folder = "hbos_test_model_file") {
  const auto dir = std::filesystem::temp_directory_path() / folder;
  std::filesystem::create_directories(dir);
  return (dir / name).string();
}

/// The PyOD-mode tests' files: a folder of their own, since the test above counts the files in
/// its folder and ctest may run the tests at the same time.
std::string pyod_temp_path(const std::string& name) {
  return temp_path(name, "hbos_test_pyod_model_file");
}

/// The text of a small fitted model, to damage: version 1 unless `version` says 2.
std::string sample_text(int version = 1) {
  hbos::HbosParams p;
  p.feature.binning.shifts = 1;
  p.feature.binning.bins = 3;
  return hbos::to_model_text(hbos::Hbosd::fit(mixed_features<double>(5, 50).leftCols(2), p),
                             version);
}

/// `text` with the line starting with `key` replaced by `replacement`.
std::string replace_line(const std::string& text, const std::string& key,
                         const std::string& replacement) {
  const std::size_t at = text.find("\n" + key + " ");
  REQUIRE(at != std::string::npos);
  const std::size_t end = text.find('\n', at + 1);
  return text.substr(0, at + 1) + replacement + text.substr(end);
}

/// Loading `text` fails with a message containing every one of `parts`.
void check_refused(const std::string& text, const std::vector<std::string>& parts) {
  try {
    (void)hbos::hbos_from_model_text<double>(text, "m.txt");
    FAIL("accepted a damaged model file");
  } catch (const hbos::InvalidArgument& e) {
    const std::string what = e.what();
    for (const auto& part : parts) {
      INFO(what);
      CHECK(what.find(part) != std::string::npos);
    }
  }
}

}  // namespace

TEST_CASE("a loaded model scores bit for bit like the saved one, every mode", "[model_file]") {
  for (const auto& [name, params] : all_modes()) {
    SECTION(name) {
      for (std::uint32_t seed = 1; seed <= 3; ++seed) {
        check_round_trip(mixed_features<double>(seed, 300 + 71 * seed), params);
        check_round_trip(mixed_features<float>(seed, 300 + 71 * seed), params);
      }
      check_streamed(mixed_features<double>(4, 250), params, temp_path("streamed.hbos"));
      check_streamed(mixed_features<float>(4, 250), params, temp_path("streamed.hbos"));
    }
  }
}

TEST_CASE("a constant feature and a single row round-trip", "[model_file]") {
  Eigen::MatrixXd x(40, 2);
  x.col(0).setConstant(3.5);
  x.col(1).setLinSpaced(40, -1.0, 1.0);
  check_round_trip<double>(x, {});
  hbos::HbosParams dynamic;
  dynamic.feature.binning.method = hbos::BinningMethod::EqualFrequency;
  check_round_trip<double>(x, dynamic);
  check_round_trip<double>(x.topRows(1), {});
  // A range that overflows a double is binned in scaled form (EdgeLayout::scale != 1).
  for (Eigen::Index i = 0; i < x.rows(); ++i) {
    const double t = static_cast<double>(i * i) / 1521.0;
    x(i, 0) = 1.7e308 * t - 1.5e308 * (1.0 - t);
  }
  const auto extreme = hbos::Hbosd::fit(x);
  REQUIRE(extreme.histogram(0).parts().scale != 1.0);
  const auto loaded = hbos::hbos_from_model_text<double>(hbos::to_model_text(extreme));
  CHECK(same_bits(loaded.score(x), extreme.score(x)));
  CHECK(hbos::to_model_text(loaded) == hbos::to_model_text(extreme));
}

TEST_CASE("save_model writes atomically and load_hbos reads it back", "[model_file]") {
  const Eigen::MatrixXd x = mixed_features<double>(9, 500);
  const auto model = hbos::Hbosd::fit(x);
  const std::string path = temp_path("model.hbos");
  std::filesystem::remove(path);
  hbos::save_model(model, path);
  // Replacing an existing file leaves only the new one, and no temporary file behind.
  const auto other = hbos::Hbosd::fit(x.topRows(100));
  hbos::save_model(other, path);
  // Only this file and its temporaries (`model.hbos.tmp...`) count: other tests write into the
  // same folder, and ctest may run them at the same time.
  std::size_t files = 0;
  for (const auto& entry :
       std::filesystem::directory_iterator(std::filesystem::path(path).parent_path())) {
    files += entry.path().filename().string().rfind("model.hbos", 0) == 0 ? 1U : 0U;
  }
  CHECK(files == 1);
  const auto loaded = hbos::load_hbos<double>(path);
  CHECK(same_bits(loaded.score(x), other.score(x)));
  const hbos::ModelFileInfo info = hbos::read_model_info(path);
  CHECK(info.version == hbos::kModelFileVersion);
  CHECK(info.kind == "hbos");
  CHECK(info.scalar == "double");
  CHECK_THROWS_WITH(hbos::load_hbos<float>(path),
                    Catch::Contains("load it with load_hbos<double>"));
  CHECK_THROWS_WITH(hbos::load_hbos<double>(temp_path("missing.hbos")),
                    Catch::Contains("cannot open model file"));
  CHECK_THROWS_WITH(hbos::save_model(model, temp_path("no/such/dir/m.hbos")),
                    Catch::Contains("m.hbos"));
  std::filesystem::remove(path);
}

TEST_CASE("damaged model files are refused naming the line and the field", "[model_file]") {
  const std::string text = sample_text();
  REQUIRE_NOTHROW(hbos::hbos_from_model_text<double>(text));
  check_refused("", {"m.txt", "hbos-model-file", "truncated"});
  check_refused("not a model\n", {"line 1", "hbos-model-file"});
  check_refused(replace_line("x\n" + text.substr(text.find('\n') + 1), "kind", "kind hbos"),
                {"line 1"});
  std::string v3 = text;
  v3.replace(0, v3.find('\n'), "hbos-model-file 3");
  check_refused(v3, {"line 1", "unsupported format version 3"});
  check_refused(replace_line(text, "kind", "kind pyod"), {"load_pyod_hbos"});
  check_refused(replace_line(text, "scalar", "scalar half"), {"line 3", "'half'"});
  check_refused(text.substr(0, text.size() / 2), {"m.txt"});
  check_refused(text + "extra\n", {"unexpected content", "extra"});
  check_refused(replace_line(text, "n_features", "n_features 0"), {"line 4", "n_features"});
  check_refused(replace_line(text, "n_samples", "n_samples 49"), {"counts 50", "49"});
  check_refused(replace_line(text, "hist.lo", "hist.lo nan"), {"hist.lo", "not finite"});
  check_refused(replace_line(text, "hist.lo", "hist.lo inf"), {"hist.lo", "not finite"});
  check_refused(replace_line(text, "hist.lo", "hist.lo 1.5x"), {"hist.lo", "'1.5x'"});
  check_refused(replace_line(text, "hist.lo", "hist.low 1"), {"expected a line starting with"});
  check_refused(replace_line(text, "hist.lo", "hist.lo 1e400"), {"out of range"});
  check_refused(replace_line(text, "hist.edges", "hist.edges 4 0 2 1 3"),
                {"feature 0", "not ascending"});
  check_refused(replace_line(text, "hist.edges", "hist.edges 3 0 1 2"), {"edges has 3 values"});
  check_refused(replace_line(text, "hist.edges", "hist.edges 5 0 1 2"), {"declares 5 values"});
  check_refused(replace_line(text, "hist.counts", "hist.counts 3 60 -5 -5"),
                {"feature 0", "counts[1] is negative"});
  check_refused(replace_line(text, "hist.inv_width", "hist.inv_width 1e30"),
                {"feature 0", "inv_width"});
  check_refused(replace_line(text, "hist.shifts", "hist.shifts 2"), {"shifts"});
  check_refused(replace_line(text, "hist.tail", "hist.tail sideways"), {"'sideways'", "both"});
  check_refused(replace_line(text, "spec.bins", "spec.bins 0"), {"spec", "bin count must be >= 1"});
  check_refused(replace_line(text, "spec.periodic", "spec.periodic 2"), {"not 0 or 1"});
  check_refused(replace_line(text, "scoring.empty_bin_count", "scoring.empty_bin_count 2"),
                {"line 7", "empty_bin_count"});
  check_refused(replace_line(text, "feature", "feature 1"), {"expected feature 0"});
}

TEST_CASE("version 2 stores a feature on one line, uniform edges as their width", "[model_file]") {
  const Eigen::MatrixXd x = mixed_features<double>(6, 400);
  const std::string v2 = hbos::to_model_text(hbos::Hbosd::fit(x));
  const std::string v1 = hbos::to_model_text(hbos::Hbosd::fit(x), 1);
  CHECK(v2.rfind("hbos-model-file 2\n", 0) == 0);
  // Every feature of the default spec is uniform: one `f ... u <width> ...` line each.
  std::size_t lines = 0, uniform = 0;
  for (std::size_t at = v2.find("\nf "); at != std::string::npos; at = v2.find("\nf ", at + 1)) {
    ++lines;
    const std::string line = v2.substr(at + 1, v2.find('\n', at + 1) - at - 1);
    if (line.find(" u ") != std::string::npos) ++uniform;
  }
  CHECK(lines == static_cast<std::size_t>(x.cols()));
  CHECK(uniform == lines);
  CHECK(v2.size() * 2 < v1.size());
  // Irregular bins list their edges.
  hbos::HbosParams ef;
  ef.feature.binning.method = hbos::BinningMethod::EqualFrequency;
  const std::string listed = hbos::to_model_text(hbos::Hbosd::fit(x, ef));
  CHECK(listed.find(" e ") != std::string::npos);
  CHECK(listed.find(" u ") == std::string::npos);
}

TEST_CASE("damaged version 2 model files are refused naming the line and the field",
          "[model_file]") {
  const std::string text = sample_text(2);
  REQUIRE_NOTHROW(hbos::hbos_from_model_text<double>(text));
  const std::size_t f = text.find("\nf ") + 1;
  const std::string line = text.substr(f, text.find('\n', f) - f);
  // The first feature line's tokens, to damage one at a time.
  std::vector<std::string> t;
  for (std::size_t i = 0; i < line.size();) {
    const std::size_t end = std::min(line.find(' ', i), line.size());
    t.push_back(line.substr(i, end - i));
    i = end + 1;
  }
  REQUIRE(t.size() == 13);  // f, 6 numbers, 3 bins, u, the width, 3 counts
  REQUIRE(t[8] == "u");
  auto with = [&](std::size_t i, const std::string& token) {
    std::vector<std::string> u = t;
    u[i] = token;
    std::string joined;
    for (const auto& s : u) joined += (joined.empty() ? "" : " ") + s;
    return text.substr(0, f) + joined + text.substr(f + line.size());
  };
  const std::string before = text.substr(0, f);
  const std::string feature_line =
      "line " + std::to_string(std::count(before.begin(), before.end(), '\n') + 1);
  // Truncated: no final `end`, cut in the middle of a line, missing the last feature.
  check_refused(text.substr(0, text.rfind("end\n")), {"m.txt", "'end'", "truncated"});
  check_refused(text.substr(0, f + line.size() / 2), {"m.txt"});
  check_refused(text.substr(0, text.rfind("\nf ") + 1) + "end\n",
                {"expected a line starting with 'f'"});
  check_refused(text + "f 1\n", {"unexpected content"});
  check_refused(with(1, "nan"), {feature_line, "(f.lo)", "not finite"});
  check_refused(with(2, "inf"), {"(f.hi)", "not finite"});
  check_refused(with(9, "nan"), {"(f.fine)", "not finite"});
  check_refused(with(9, "0.5"), {"(f.fine)", "does not match inv_width"});
  check_refused(with(9, "0"), {"(f.fine)", "does not match"});
  check_refused(with(7, "4"), {feature_line, "expected 13 values for 4 bins, got 12"});
  check_refused(with(7, "0"), {"(f.bins)", "outside [1"});
  check_refused(with(7, "-3"), {"(f.bins)", "outside [1"});
  check_refused(with(8, "x"), {"edge form 'x'"});
  check_refused(with(10, "-1"), {"feature 0", "negative"});
  check_refused(with(10, "1000"), {"feature 0", "counts 1", "the model 50"});
  // Counts whose sum overflows a signed 64-bit integer: an error, not undefined behaviour
  // (the sanitizer build checks the latter).
  check_refused(with(10, "9223372036854775807"), {"feature 0", "the model 50"});
  check_refused(with(10, "1.5"), {"(f.counts)", "not a whole number"});
  check_refused(with(3, "1e30"), {"(f.fine)", "does not match inv_width 1e+30"});
  check_refused(with(4, "1"), {"feature 0", "period"});
  // Listed edges: the form of irregular bins, checked as version 1's edges are.
  std::vector<std::string> e = {t[0], t[1], t[2], t[3], t[4], t[5], t[6], t[7], "e"};
  auto listed = [&](const std::vector<std::string>& edges) {
    std::string joined;
    for (const auto& s : e) joined += (joined.empty() ? "" : " ") + s;
    for (const auto& s : edges) joined += " " + s;
    for (std::size_t i = 10; i < t.size(); ++i) joined += " " + t[i];
    return text.substr(0, f) + joined + text.substr(f + line.size());
  };
  const double lo = std::stod(t[1]), hi = std::stod(t[2]);
  const double w = (hi - lo) / 3;
  auto num = [](double v) {
    std::ostringstream o;
    o.precision(17);
    o << v;
    return o.str();
  };
  REQUIRE_NOTHROW(
      hbos::hbos_from_model_text<double>(listed({t[1], num(lo + w), num(lo + 2 * w), t[2]})));
  check_refused(listed({t[1], "nan", num(lo + 2 * w), t[2]}), {"(f.edges)", "not finite"});
  check_refused(listed({t[1], num(lo + 2 * w), num(lo + w), t[2]}),
                {"feature 0 (from " + feature_line + ")", "not ascending"});
  check_refused(listed({t[1], num(lo + w), t[2]}), {"expected 15 values for 3 bins, got 14"});
  check_refused(listed({num(lo - 1), num(lo + w), num(lo + 2 * w), t[2]}),
                {"feature 0", "edges run from"});
  // Per-feature specs: one `spec` line before each feature line.
  hbos::HbosParams p;
  p.features.resize(2);
  p.features[1].binning.method = hbos::BinningMethod::EqualFrequency;
  const std::string per =
      hbos::to_model_text(hbos::Hbosd::fit(mixed_features<double>(5, 50).leftCols(2), p));
  REQUIRE_NOTHROW(hbos::hbos_from_model_text<double>(per));
  check_refused(replace_line(per, "spec", "spec equal_width fixed 5"), {"(spec)", "expected 11"});
  std::string swapped = per;
  const std::size_t second = swapped.find("\nspec ", swapped.find("\nspec ") + 1);
  swapped.replace(swapped.find("equal_frequency", second), 15, "equal_width");
  check_refused(swapped, {"m.txt"});
}

TEST_CASE("Hbos::from_histograms refuses histograms that disagree with the spec", "[model_file]") {
  const Eigen::MatrixXd x = mixed_features<double>(3, 200);
  const auto model = hbos::Hbosd::fit(x);
  std::vector<hbos::Histogram<double>> histograms;
  for (Eigen::Index j = 0; j < model.n_features(); ++j) histograms.push_back(model.histogram(j));
  CHECK_NOTHROW(hbos::Hbosd::from_histograms(histograms, model.params(), 200));
  CHECK_THROWS_WITH(hbos::Hbosd::from_histograms(histograms, model.params(), 199),
                    Catch::Contains("counts 200 samples"));
  hbos::HbosParams plain;
  plain.feature.binning.shifts = 1;
  CHECK_THROWS_WITH(hbos::Hbosd::from_histograms(histograms, plain, 200),
                    Catch::Contains("shifts"));
  CHECK_THROWS_WITH(hbos::Hbosd::from_histograms({}, model.params(), 200),
                    Catch::Contains("at least one feature"));
}

// ---- the PyOD mode (hbos/pyod/model_file.hpp) ----------------------------------------------

namespace {

const std::string kPyodDir = std::string(HBOS_TEST_DATA_DIR) + "/hbos_pyod/";

Eigen::MatrixXd read_csv(const std::string& path) {
  std::ifstream in(path);
  REQUIRE(in.good());
  std::vector<std::vector<double>> rows;
  std::string line;
  while (std::getline(in, line)) {
    std::vector<double> row;
    std::size_t start = 0;
    while (start <= line.size()) {
      const std::size_t end = std::min(line.find(',', start), line.size());
      row.push_back(std::stod(line.substr(start, end - start)));
      start = end + 1;
    }
    rows.push_back(row);
  }
  Eigen::MatrixXd x(static_cast<Eigen::Index>(rows.size()),
                    static_cast<Eigen::Index>(rows.front().size()));
  for (Eigen::Index i = 0; i < x.rows(); ++i)
    for (Eigen::Index j = 0; j < x.cols(); ++j)
      x(i, j) = rows[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)];
  return x;
}

template <class Scalar>
void check_pyod_round_trip(const Eigen::MatrixXd& x, const Eigen::MatrixXd& x_test,
                           const hbos::PyodParams& params) {
  const Matrix<Scalar> xs = x.cast<Scalar>();
  const Matrix<Scalar> ts = x_test.cast<Scalar>();
  const auto model = hbos::PyodHbos<Scalar>::fit(xs, params);
  const std::string text = hbos::to_model_text(model);
  const auto loaded = hbos::pyod_hbos_from_model_text<Scalar>(text);
  CHECK(same_bits(model.decision_function(ts), loaded.decision_function(ts)));
  CHECK(same_bits(model.decision_scores(), loaded.decision_scores()));
  CHECK(model.threshold() == loaded.threshold());
  CHECK(model.labels() == loaded.labels());
  CHECK(model.predict(ts) == loaded.predict(ts));
  for (Eigen::Index j = 0; j < model.n_features(); ++j) {
    CHECK(model.densities(j) == loaded.densities(j));
    CHECK(model.bin_edges(j) == loaded.bin_edges(j));
  }
  CHECK(hbos::to_model_text(loaded) == text);
  // Version 1 (the layout older releases read and wrote) round-trips to the same model too.
  const std::string v1 = hbos::to_model_text(model, 1);
  CHECK(v1.rfind("hbos-model-file 1\n", 0) == 0);
  const auto loaded_v1 = hbos::pyod_hbos_from_model_text<Scalar>(v1);
  CHECK(same_bits(model.decision_function(ts), loaded_v1.decision_function(ts)));
  CHECK(hbos::to_model_text(loaded_v1, 1) == v1);
  CHECK(hbos::to_model_text(loaded_v1) == text);
}

/// The feature-at-a-time writer fits and writes save_model's file, and the reader gives back the
/// features load_pyod_hbos holds: scoring feature by feature gives decision_function's bits,
/// from files of both versions. The columns are given strided (a row-major copy) and contiguous.
template <class Scalar>
void check_pyod_streamed(const Matrix<Scalar>& x, const Matrix<Scalar>& x_test,
                         const hbos::PyodParams& params, const std::string& path) {
  const auto model = hbos::PyodHbos<Scalar>::fit(x, params);
  const Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> rows = x;
  for (const bool strided : {true, false}) {
    hbos::PyodModelFileWriter<Scalar> writer(path, params, x.cols(), x.rows());
    for (Eigen::Index j = 0; j < x.cols(); ++j) {
      if (strided) {
        writer.add(rows.data() + j, rows.cols());
      } else {
        writer.add(x.col(j));
      }
    }
    writer.commit();
    std::ifstream in(path, std::ios::binary);
    const std::string written((std::istreambuf_iterator<char>(in)),
                              std::istreambuf_iterator<char>());
    CHECK(written == hbos::to_model_text(model));
  }
  const auto expected = model.decision_function(x_test);
  for (const int version : {2, 1}) {
    if (version == 1) hbos::save_model(model, path, 1);
    hbos::PyodModelFileReader<Scalar> reader(path);
    CHECK(reader.version() == version);
    CHECK(reader.n_features() == x.cols());
    CHECK(reader.n_samples() == x.rows());
    hbos::PyodFeatureScores<Scalar> scores(x_test.cols(), x_test.rows());
    for (Eigen::Index j = 0; j < x_test.cols(); ++j) {
      const hbos::PyodFeatureModel<Scalar> f = reader.next();
      CHECK(f.bin_edges() == model.bin_edges(j));
      CHECK(f.densities() == model.densities(j));
      scores.add(f, x_test.col(j).data(), 1);
    }
    CHECK_NOTHROW(reader.finish());
    CHECK(reader.threshold() == model.threshold());
    CHECK(same_bits(scores.scores(), expected));
  }
  std::filesystem::remove(path);
}

}  // namespace

TEST_CASE("a loaded PyOD-mode model scores bit for bit like the saved one", "[model_file][pyod]") {
  for (const std::string name : {"cardio", "glass", "lympho", "pima", "vertebral", "wbc"}) {
    const Eigen::MatrixXd x = read_csv(kPyodDir + name + "/X.csv");
    const Eigen::MatrixXd x_test = read_csv(kPyodDir + name + "/X_test.csv");
    hbos::PyodParams p;
    for (const auto& [bins, alpha, tol] : std::vector<std::tuple<int, double, double>>{
             {10, 0.1, 0.5}, {5, 0.1, 0.5}, {20, 0.01, 0.2}, {0, 0.1, 0.5}}) {
      p.auto_bins = bins == 0;
      p.n_bins = bins == 0 ? 10 : bins;
      p.alpha = alpha;
      p.tol = tol;
      INFO(name << " n_bins " << bins);
      check_pyod_round_trip<double>(x, x_test, p);
      check_pyod_round_trip<float>(x, x_test, p);
    }
  }
}

TEST_CASE("numpy's pairwise sum fed one term at a time gives the same bits", "[model_file][pyod]") {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> mantissa(-1.0, 1.0);
  std::uniform_int_distribution<int> exponent(-30, 30);
  for (const Eigen::Index d :
       {1, 2, 7, 8, 9, 15, 16, 17, 127, 128, 129, 130, 136, 255, 256, 257, 1000, 1031, 4099}) {
    const Eigen::Index rows = 3;
    std::vector<double> terms(static_cast<std::size_t>(d * rows));  // term k of row i at k*rows+i
    for (double& t : terms) t = std::ldexp(mantissa(rng), exponent(rng));
    hbos::detail::PairwiseRowSums sums(d, rows);
    for (Eigen::Index k = 0; k < d; ++k) sums.add(terms.data() + k * rows);
    for (Eigen::Index i = 0; i < rows; ++i) {
      const double expected = hbos::detail::numpy_pairwise_sum(terms.data() + i, d, rows);
      INFO("d = " << d << ", row " << i);
      const double got = sums.sum(i);
      CHECK(std::memcmp(&got, &expected, sizeof(double)) == 0);
    }
    CHECK_THROWS_WITH(sums.add(terms.data()), Catch::Contains("all"));
  }
  hbos::detail::PairwiseRowSums partial(10, 2);
  const double two[2] = {1.0, 2.0};
  partial.add(two);
  CHECK_THROWS_WITH(partial.sum(0), Catch::Contains("1 of 10 terms"));
}

TEST_CASE("a PyOD-mode model written and read one feature at a time is the whole model's",
          "[model_file][pyod]") {
  const std::string path = pyod_temp_path("streamed.pyod");
  for (const std::string name : {"cardio", "vertebral"}) {
    const Eigen::MatrixXd x = read_csv(kPyodDir + name + "/X.csv");
    const Eigen::MatrixXd x_test = read_csv(kPyodDir + name + "/X_test.csv");
    hbos::PyodParams p;
    for (const auto& [bins, alpha, tol] : std::vector<std::tuple<int, double, double>>{
             {10, 0.1, 0.5}, {5, 0.1, 0.5}, {20, 0.01, 0.2}, {0, 0.1, 0.5}}) {
      p.auto_bins = bins == 0;
      p.n_bins = bins == 0 ? 10 : bins;
      p.alpha = alpha;
      p.tol = tol;
      INFO(name << " n_bins " << bins);
      check_pyod_streamed<double>(x, x_test, p, path);
      check_pyod_streamed<float>(x.cast<float>(), x_test.cast<float>(), p, path);
    }
  }
  // Wide: 6 rows of 700 features (numpy's sum splits the features in halves of multiples of 8),
  // mixed shapes, constant features among them; more bins than PyOD's grid stores (2^16 + 1).
  Eigen::MatrixXd wide(6, 700);
  for (Eigen::Index j = 0; j < wide.cols(); ++j)
    wide.col(j) = mixed_features<double>(static_cast<std::uint32_t>(j), 6, true).col(j % 5);
  const Matrix<double> wide_test = make_queries(Matrix<double>(wide));
  hbos::PyodParams p;
  check_pyod_streamed<double>(wide, wide_test, p, path);
  check_pyod_streamed<float>(wide.cast<float>(), wide_test.cast<float>(), p, path);
  p.auto_bins = true;
  check_pyod_streamed<double>(wide, wide_test, p, path);
  p.auto_bins = false;
  p.n_bins = 65537;
  check_pyod_streamed<double>(wide.leftCols(9), wide_test.leftCols(9), p, path);
}

TEST_CASE("the PyOD-mode writer is atomic and refuses bad columns naming X(i, j)",
          "[model_file][pyod]") {
  const std::string path = pyod_temp_path("atomic.pyod");
  { std::ofstream(path) << "previous\n"; }
  Eigen::MatrixXd x = mixed_features<double>(3, 40);
  x(7, 2) = std::numeric_limits<double>::quiet_NaN();
  {
    hbos::PyodModelFileWriter<double> writer(path, {}, x.cols(), x.rows());
    writer.add(x.col(0));
    writer.add(x.col(1));
    CHECK_THROWS_WITH(writer.add(x.col(2)), Catch::Contains("X(7, 2) is not finite"));
    CHECK_THROWS_WITH(writer.commit(), Catch::Contains("2 of 4 terms"));
  }  // destroyed without commit: the old file stays, no temporary file is left
  std::ifstream in(path);
  std::string first;
  std::getline(in, first);
  CHECK(first == "previous");
  std::size_t files = 0;
  for (const auto& entry :
       std::filesystem::directory_iterator(std::filesystem::path(path).parent_path())) {
    files += entry.path().filename().string().find("atomic.pyod") != std::string::npos ? 1U : 0U;
  }
  CHECK(files == 1);
  hbos::PyodModelFileWriter<double> writer(path, {}, 1, x.rows());
  writer.add(x.col(0));
  CHECK_THROWS_WITH(writer.add(x.col(1)), Catch::Contains("all 1 terms"));
  CHECK_THROWS_WITH(writer.add(Eigen::VectorXd::Zero(3)), Catch::Contains("40 values expected"));
  std::filesystem::remove(path);
}

TEST_CASE("a loaded PyOD-mode model still reproduces PyOD's test scores", "[model_file][pyod]") {
  const Eigen::MatrixXd x = read_csv(kPyodDir + "cardio/X.csv");
  const Eigen::MatrixXd x_test = read_csv(kPyodDir + "cardio/X_test.csv");
  const Eigen::MatrixXd expected = read_csv(kPyodDir + "cardio/test_scores_nb10_a0.1_tol0.5.csv");
  const std::string path = temp_path("cardio.pyod");
  hbos::save_model(hbos::PyodHbosd::fit(x), path);
  CHECK(hbos::read_model_info(path).kind == "pyod");
  const auto loaded = hbos::load_pyod_hbos<double>(path);
  const Eigen::VectorXd scores = loaded.decision_function(x_test);
  CHECK(same_bits(scores, Eigen::VectorXd(expected.col(0))));
  CHECK_THROWS_WITH(hbos::load_hbos<double>(path), Catch::Contains("load it with load_pyod_hbos"));
  std::filesystem::remove(path);
}

TEST_CASE("damaged PyOD-mode model files are refused naming the line and the field",
          "[model_file][pyod]") {
  // Version 1 (still read): its block of lines per feature.
  const std::string text =
      hbos::to_model_text(hbos::PyodHbosd::fit(mixed_features<double>(2, 60)), 1);
  REQUIRE_NOTHROW(hbos::pyod_hbos_from_model_text<double>(text));
  auto refused = [](const std::string& damaged, const std::vector<std::string>& parts) {
    try {
      (void)hbos::pyod_hbos_from_model_text<double>(damaged, "p.txt");
      FAIL("accepted a damaged model file");
    } catch (const hbos::InvalidArgument& e) {
      const std::string what = e.what();
      for (const auto& part : parts) {
        INFO(what);
        CHECK(what.find(part) != std::string::npos);
      }
    }
  };
  refused(replace_line(text, "n_bins", "n_bins 2"), {"line 6", "n_bins must be > 2"});
  refused(replace_line(text, "alpha", "alpha 1.5"), {"alpha must lie"});
  refused(replace_line(text, "threshold", "threshold 99"), {"line 10", "threshold", "percentile"});
  refused(replace_line(text, "edges", "edges 3 0 1 2"), {"line 13", "counts for 3 edges"});
  const std::size_t edges_at = text.find("\nedges 11 ") + 10;
  std::string shifted = text;
  shifted.insert(edges_at, "-");  // a different first edge: not numpy's edges any more
  refused(shifted, {"feature 0", "numpy's edges"});
  refused(replace_line(text, "counts", "counts 10 59 0 0 0 0 0 0 0 0 0"),
          {"feature 0", "add up to 59"});
  refused(replace_line(text, "counts", "counts 10 58 -1 3 0 0 0 0 0 0 0"), {"counts[1] = -1"});
  refused(text.substr(0, text.size() - 30), {"p.txt"});
  const std::size_t scores_at = text.find("\ndecision_scores 60\n") + 20;
  std::string bad_score = text;
  bad_score.insert(scores_at, "x");
  refused(bad_score, {"decision_scores", "not a number"});
}

TEST_CASE("damaged version 2 PyOD-mode model files are refused naming the line and the field",
          "[model_file][pyod]") {
  const auto model = hbos::PyodHbosd::fit(mixed_features<double>(2, 60));
  const std::string text = hbos::to_model_text(model);
  REQUIRE(text.rfind("hbos-model-file 2\nkind pyod\n", 0) == 0);
  REQUIRE_NOTHROW(hbos::pyod_hbos_from_model_text<double>(text));
  const std::string path = pyod_temp_path("damaged_v2.pyod");
  // Both loaders, whole and one feature at a time, refuse with the same message.
  auto refused = [&](const std::string& damaged, const std::vector<std::string>& parts) {
    std::vector<std::string> messages;
    INFO(damaged.substr(0, 400));
    try {
      (void)hbos::pyod_hbos_from_model_text<double>(damaged, "model file '" + path + "'");
      FAIL("load accepted a damaged model file");
    } catch (const hbos::InvalidArgument& e) {
      messages.emplace_back(e.what());
    }
    { std::ofstream(path, std::ios::binary) << damaged; }
    try {
      hbos::PyodModelFileReader<double> reader(path);
      for (Eigen::Index j = 0; j < reader.n_features(); ++j) (void)reader.next();
      reader.finish();
      FAIL("the reader accepted a damaged model file");
    } catch (const hbos::InvalidArgument& e) {
      messages.emplace_back(e.what());
    }
    REQUIRE(messages.size() == 2);
    CHECK(messages[0] == messages[1]);
    for (const auto& part : parts) {
      INFO(messages[0]);
      CHECK(messages[0].find(part) != std::string::npos);
    }
  };
  // Line 10 is feature 0: f <B> <e_0> <e_B> <counts>; its tokens changed one at a time.
  const std::size_t f0 = text.find("\nf ") + 1;
  const std::string line10 = text.substr(f0, text.find('\n', f0) - f0);
  auto with_line10 = [&](const std::string& replacement) {
    return text.substr(0, f0) + replacement + text.substr(f0 + line10.size());
  };
  std::vector<std::string> tokens;
  {
    std::istringstream split(line10.substr(2));
    for (std::string t; split >> t;) tokens.push_back(t);
  }
  REQUIRE(tokens.size() == 13);
  auto changed = [&](std::size_t i, const std::string& value) {
    std::string line = "f";
    for (std::size_t k = 0; k < tokens.size(); ++k) line += " " + (k == i ? value : tokens[k]);
    return with_line10(line);
  };
  refused(with_line10("f 0 1 2 3"), {"line 10 (f.bins)", "bin count 0"});
  refused(with_line10("f 10 1 2"), {"line 10 (f)", "expected at least 4 values, got 3"});
  refused(with_line10("f 10 1 2 3"), {"line 10 (f)", "expected 13 values for 10 bins, got 4"});
  refused(changed(0, "9"), {"line 10 (f)", "expected 12 values for 9 bins, got 13"});
  refused(changed(1, "1x"), {"line 10 (f.lo)", "'1x' is not a number"});
  refused(changed(2, tokens[1]), {"line 10 (f.hi)", "is empty"});
  std::string overflowing = "f 10 -1e308 1e308";
  for (std::size_t k = 3; k < tokens.size(); ++k) overflowing += " " + tokens[k];
  refused(with_line10(overflowing), {"line 10 (f.hi)", "feature 0", "overflows a double"});
  refused(changed(3, std::to_string(std::stoll(tokens[3]) - 1)),
          {"line 10 (f)", "feature 0", "add up to 59"});
  refused(changed(4, "-1"), {"line 10 (f)", "counts[1] = -1"});
  refused(changed(12, "nan"), {"line 10 (f.counts)", "'nan' is not a whole number"});
  refused(replace_line(text, "n_bins", "n_bins 2"), {"line 6 (n_bins)", "n_bins must be > 2"});
  // The threshold comes last in version 2.
  const std::size_t last = text.find("\nthreshold ");
  REQUIRE(last != std::string::npos);
  const auto threshold_line = static_cast<std::size_t>(std::count(
                                  text.begin(), text.begin() + static_cast<long>(last) + 1, '\n')) +
                              1;
  refused(replace_line(text, "threshold", "threshold 99"),
          {"line " + std::to_string(threshold_line) + " (threshold)", "percentile"});
  refused(replace_line(text, "decision_scores", "decision_scores 59"),
          {"(decision_scores)", "59 scores for n_samples = 60"});
  refused(text.substr(0, last + 1), {"ends after line", "'threshold' was expected"});
  refused(text + "f 1 0 1 60\n", {"(end of file)", "unexpected content"});
  refused("hbos-model-file 3" + text.substr(text.find('\n')),
          {"line 1 (hbos-model-file)", "unsupported format version 3"});
  std::filesystem::remove(path);
}

TEST_CASE("a PyOD-mode file's header cannot make the loader allocate beyond the file",
          "[model_file][pyod]") {
  // n_samples of a billion, backed by two scores: refused at the short score list, after
  // features whose counts are checked in O(bins) (rebuilding one value per sample would
  // have allocated gigabytes first; tests/fuzz/corpus/fuzz_model_file/pyod_v2_huge_* is the
  // input the fuzzer found).
  const std::string huge =
      "hbos-model-file 2\nkind pyod\nscalar float\nn_features 2\nn_samples 1000000000\n"
      "n_bins 4\nalpha 0.1\ntol 0.5\ncontamination 0.1\n"
      "f 4 -2 2 250000000 250000000 250000000 250000000\n"
      "f 4 -25 33 250000000 250000000 250000000 250000000\n"
      "decision_scores 1000000000\n5.24\n3.79\nend\n";
  try {
    (void)hbos::pyod_hbos_from_model_text<float>(huge, "h.txt");
    FAIL("accepted a file with two of a billion scores");
  } catch (const hbos::InvalidArgument& e) {
    const std::string what = e.what();
    INFO(what);
    CHECK(what.find("h.txt, line 15 (decision_scores)") != std::string::npos);
  }
}

TEST_CASE("PyOD-mode counts that no training values could give are refused", "[model_file][pyod]") {
  // A float feature whose range [1, 1 + 1e-7] is narrower than a float's spacing at 1: every
  // training value is the float 1, counted in bin 0. Counts in later bins cannot come from
  // any float data, for the whole loader and for the one-feature reader alike.
  auto text_with = [](const std::string& feature) {
    return "hbos-model-file 2\nkind pyod\nscalar float\nn_features 1\nn_samples 40\n"
           "n_bins 4\nalpha 0.1\ntol 0.5\ncontamination 0.1\n" +
           feature + "\ndecision_scores 40\n";
  };
  auto message = [](const std::string& text) {
    try {
      (void)hbos::pyod_hbos_from_model_text<float>(text, "c.txt");
    } catch (const hbos::InvalidArgument& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  // All in bin 0: the features load, so the file fails later, at its missing scores.
  CHECK(message(text_with("f 4 1 1.0000001 40 0 0 0")).find("decision_scores") !=
        std::string::npos);
  const std::string refused = message(text_with("f 4 1 1.0000001 30 10 0 0"));
  INFO(refused);
  CHECK(refused.find("c.txt, line 10 (f): feature 0: the counts do not match the edges") !=
        std::string::npos);
  CHECK(refused.find("edges[1] is not counted in bin 1") != std::string::npos);
  // The same edges in double hold a value of each bin: accepted there.
  std::string as_double = text_with("f 4 1 1.0000001 30 10 0 0");
  as_double.replace(as_double.find("scalar float"), 12, "scalar double");
  std::string double_message = "accepted";
  try {
    (void)hbos::pyod_hbos_from_model_text<double>(as_double, "c.txt");
  } catch (const hbos::InvalidArgument& e) {
    double_message = e.what();
  }
  INFO(double_message);
  // Past the counts: refused only at the scores the text leaves out.
  CHECK(double_message.find("counts do not match") == std::string::npos);
  CHECK(double_message.find("'decision_scores'") != std::string::npos);
}
