// Tests of examples/hbos_score/score_options.hpp and column_selector.hpp: option values,
// combinations, and their translation into model parameters.

#include "column_selector.hpp"
#include "score_options.hpp"

#include <catch2/catch.hpp>
#include <string>
#include <variant>

using namespace hbos::cli;

TEST_CASE("bins option values", "[options]") {
  CHECK(parse_bins("10").rule == hbos::BinCountRule::Fixed);
  CHECK(parse_bins("10").count == 10);
  CHECK(parse_bins("1").count == 1);
  CHECK(parse_bins("65536").count == 65536);
  CHECK(parse_bins("sqrt").rule == hbos::BinCountRule::Sqrt);
  CHECK(parse_bins("sturges").rule == hbos::BinCountRule::Sturges);
  CHECK(parse_bins("scott").rule == hbos::BinCountRule::Scott);
  CHECK(parse_bins("fd").rule == hbos::BinCountRule::FreedmanDiaconis);
  CHECK(parse_bins("birge").rule == hbos::BinCountRule::BirgeRozenblac);
  CHECK(parse_bins("auto").rule == hbos::BinCountRule::BirgeRozenblac);
  for (const char* bad : {"0", "-3", "65537", "", "10x", "1.5", "Sturges", "sqrt "}) {
    INFO(bad);
    REQUIRE_THROWS_WITH(parse_bins(bad), Catch::Contains("is neither a bin count in [1, 65536]"));
  }
  for (const char* text : {"7", "sqrt", "sturges", "scott", "fd", "birge"})
    CHECK(to_string(parse_bins(text)) == text);
}

TEST_CASE("threshold option values", "[options]") {
  CHECK(std::get<hbos::AdaptiveRange>(parse_threshold("adaptive")).range_alpha == 0.7);
  CHECK(std::get<hbos::AdaptiveRange>(parse_threshold("adaptive:0.25")).range_alpha == 0.25);
  CHECK(std::get<hbos::Contamination>(parse_threshold("contamination")).contamination == 0.1);
  CHECK(std::get<hbos::Contamination>(parse_threshold("contamination:0.5")).contamination == 0.5);
  CHECK(std::get<hbos::MedianMad>(parse_threshold("mad")).k == 3.0);
  CHECK(std::get<hbos::MedianMad>(parse_threshold("mad:2.5")).k == 2.5);
  CHECK(std::get<hbos::FixedThreshold>(parse_threshold("fixed:-1.5")).value == -1.5);
  for (const char* text : {"adaptive:0.7", "contamination:0.05", "mad:3", "fixed:12.5"}) {
    CHECK(to_string(parse_threshold(text)) == text);
  }
  REQUIRE_THROWS_WITH(parse_threshold("adaptive:1"),
                      Catch::Contains("range_alpha must lie in (0, 1)"));
  REQUIRE_THROWS_WITH(parse_threshold("adaptive:0"),
                      Catch::Contains("range_alpha must lie in (0, 1)"));
  REQUIRE_THROWS_WITH(parse_threshold("contamination:0.6"),
                      Catch::Contains("contamination must lie in (0, 0.5]"));
  REQUIRE_THROWS_WITH(parse_threshold("contamination:0"),
                      Catch::Contains("contamination must lie in (0, 0.5]"));
  REQUIRE_THROWS_WITH(parse_threshold("mad:-1"), Catch::Contains("k must be > 0"));
  REQUIRE_THROWS_WITH(parse_threshold("fixed"), Catch::Contains("fixed needs a value"));
  REQUIRE_THROWS_WITH(parse_threshold("fixed:nan"), Catch::Contains("not a finite number"));
  REQUIRE_THROWS_WITH(parse_threshold("fixed:"), Catch::Contains("not a finite number"));
  REQUIRE_THROWS_WITH(parse_threshold("median:3"), Catch::Contains("\"median:3\": unknown rule"));
  REQUIRE_THROWS_WITH(parse_threshold(""), Catch::Contains("unknown rule"));
}

TEST_CASE("column selectors", "[options]") {
  const std::vector<std::string> names{"a", "3", "last", "b"};
  CHECK(select_column("a", names) == 0);
  CHECK(select_column("3", names) == 1);     // a name wins over an index
  CHECK(select_column("last", names) == 2);  // and over the keyword
  CHECK(select_column("0", names) == 0);
  CHECK(select_column("2", names) == 2);
  CHECK(select_column("last", std::vector<std::string>{"a", "b"}) == 1);
  REQUIRE_THROWS_WITH(select_column("4", names), Catch::Contains("no column is named \"4\""));
  REQUIRE_THROWS_WITH(select_column("-1", names), Catch::Contains("no column is named \"-1\""));
  REQUIRE_THROWS_WITH(select_column("", names), Catch::Contains("no column is named \"\""));

  CHECK(split_list("a, b ,3") == std::vector<std::string>{"a", "b", "3"});
  CHECK(split_list("x") == std::vector<std::string>{"x"});
  REQUIRE_THROWS_WITH(split_list("a,,b"), Catch::Contains("empty item"));
  REQUIRE_THROWS_WITH(split_list("a,"), Catch::Contains("empty item"));
  REQUIRE_THROWS_WITH(split_list(""), Catch::Contains("empty item"));
}

TEST_CASE("option combinations", "[options]") {
  ScoreOptions o;
  CHECK_NOTHROW(check_combinations(o));

  SECTION("options of the other mode") {
    o.mode = Mode::Pyod;
    CHECK_NOTHROW(check_combinations(o));
    o.shifts = 3;
    REQUIRE_THROWS_WITH(check_combinations(o),
                        Catch::Contains("--shifts is not available with --mode pyod"));
    o.shifts.reset();
    o.bins = BinsChoice{hbos::BinCountRule::Sturges, 0};
    REQUIRE_THROWS_WITH(check_combinations(o), Catch::Contains("--bins sturges is not available"));
    o.bins = BinsChoice{hbos::BinCountRule::Fixed, 2};
    REQUIRE_THROWS_WITH(check_combinations(o), Catch::Contains("--bins must be > 2"));
    o.bins = BinsChoice{hbos::BinCountRule::BirgeRozenblac, 0};
    CHECK_NOTHROW(check_combinations(o));
    o.alpha = 1.0;
    REQUIRE_THROWS_WITH(check_combinations(o), Catch::Contains("--alpha must lie in (0, 1)"));
    o.alpha = 0.5;
    o.periodic_columns = {"a"};
    REQUIRE_THROWS_WITH(check_combinations(o),
                        Catch::Contains("--periodic-columns is not available"));
  }
  SECTION("PyOD's options in the default mode") {
    o.tol = 0.3;
    REQUIRE_THROWS_WITH(check_combinations(o), Catch::Contains("--tol belongs to --mode pyod"));
  }
  SECTION("fixed-width binning needs a width, and only it takes one") {
    o.binning = hbos::BinningMethod::FixedWidth;
    REQUIRE_THROWS_WITH(check_combinations(o), Catch::Contains("needs --width"));
    o.width = 0.5;
    CHECK_NOTHROW(check_combinations(o));
    o.bins = BinsChoice{hbos::BinCountRule::Fixed, 4};
    REQUIRE_THROWS_WITH(check_combinations(o), Catch::Contains("--bins does not apply"));
    o.bins.reset();
    o.width = -1.0;
    REQUIRE_THROWS_WITH(check_combinations(o), Catch::Contains("--width must be > 0"));
    o.binning = hbos::BinningMethod::EqualWidth;
    o.width = 1.0;
    REQUIRE_THROWS_WITH(check_combinations(o),
                        Catch::Contains("--width applies to --binning fixed-width only"));
  }
  SECTION("equal-frequency has no shifts and no circle") {
    o.binning = hbos::BinningMethod::EqualFrequency;
    o.shifts = 2;
    REQUIRE_THROWS_WITH(check_combinations(o), Catch::Contains("--shifts applies to equal-width"));
    o.shifts.reset();
    o.periodic_columns = {"a"};
    REQUIRE_THROWS_WITH(check_combinations(o), Catch::Contains("not defined on a circle"));
  }
  SECTION("periods need periodic columns") {
    o.period = 360.0;
    REQUIRE_THROWS_WITH(check_combinations(o), Catch::Contains("need --periodic-columns"));
    o.periodic_columns = {"a"};
    CHECK_NOTHROW(check_combinations(o));
    o.period = 0.0;
    REQUIRE_THROWS_WITH(check_combinations(o), Catch::Contains("--period must be > 0"));
  }
  SECTION("shifts must be positive") {
    o.shifts = 0;
    REQUIRE_THROWS_WITH(check_combinations(o), Catch::Contains("--shifts must be >= 1"));
  }
}

TEST_CASE("options become model parameters", "[options]") {
  CsvOptions csv;
  csv.label_column = "label";
  const CsvTable table = parse_csv("a,label,deg,b\n1,0,10,2\n3,1,350,4\n", "t.csv", csv);

  ScoreOptions o;
  const hbos::HbosParams defaults = make_params(o, table);
  CHECK(defaults.features.empty());
  CHECK(defaults.feature.binning.bins == hbos::default_feature().binning.bins);
  CHECK(defaults.feature.binning.shifts == hbos::default_feature().binning.shifts);

  o.bins = BinsChoice{hbos::BinCountRule::Fixed, 12};
  o.shifts = 1;
  o.tail = hbos::Tail::Upper;
  o.periodic_columns = {"deg"};
  o.period_start = 0.0;
  o.period = 360.0;
  const hbos::HbosParams p = make_params(o, table);
  REQUIRE(p.features.size() == 3);  // a, deg, b: the label is not a feature
  CHECK_FALSE(p.features[0].periodic);
  CHECK(p.features[0].tail == hbos::Tail::Upper);
  CHECK(p.features[0].binning.bins == 12);
  CHECK(p.features[1].periodic);
  CHECK(p.features[1].tail == hbos::Tail::Both);  // a circle has no upper tail
  CHECK(p.features[1].period == 360.0);
  CHECK(p.features[1].period_start == 0.0);
  CHECK(p.features[1].binning.shifts == 1);
  CHECK_FALSE(p.features[2].periodic);

  o.periodic_columns = {"2"};  // a 0-based index of the file's columns: deg
  CHECK(make_params(o, table).features[1].periodic);
  o.periodic_columns = {"label"};
  REQUIRE_THROWS_WITH(make_params(o, table), Catch::Contains("\"label\" is the label column"));
  o.periodic_columns = {"c"};
  REQUIRE_THROWS_WITH(make_params(o, table),
                      Catch::Contains("--periodic-columns: no column is named \"c\""));

  ScoreOptions pyod;
  pyod.mode = Mode::Pyod;
  CHECK(make_pyod_params(pyod).n_bins == 10);
  CHECK_FALSE(make_pyod_params(pyod).auto_bins);
  pyod.bins = BinsChoice{hbos::BinCountRule::BirgeRozenblac, 0};
  pyod.alpha = 0.01;
  pyod.tol = 0.2;
  pyod.threshold = hbos::Contamination{0.05};
  const hbos::PyodParams pp = make_pyod_params(pyod);
  CHECK(pp.auto_bins);
  CHECK(pp.alpha == 0.01);
  CHECK(pp.tol == 0.2);
  CHECK(pp.contamination == 0.05);
}
