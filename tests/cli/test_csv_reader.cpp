// Tests of examples/hbos_score/csv_reader.hpp: the accepted format, header detection, the label
// column, and the exact position and wording of every error.

#include "csv_reader.hpp"

#include <catch2/catch.hpp>
#include <cmath>
#include <string>

using hbos::cli::CsvError;
using hbos::cli::CsvOptions;
using hbos::cli::CsvTable;
using hbos::cli::HeaderMode;
using hbos::cli::parse_csv;

namespace {

CsvTable parse(const std::string& text, CsvOptions options = {}) {
  return parse_csv(text, "t.csv", options);
}

CsvOptions with_label(const std::string& column) {
  CsvOptions options;
  options.label_column = column;
  return options;
}

/// Parses `text`, expecting a CsvError at `line`:`column` whose message contains `fragment`.
void require_error(const std::string& text, std::size_t line, std::size_t column,
                   const std::string& fragment, CsvOptions options = {}) {
  INFO("input: " << text);
  try {
    static_cast<void>(parse(text, options));
    FAIL("no error");
  } catch (const CsvError& e) {
    CHECK(e.source() == "t.csv");
    CHECK(e.line() == line);
    CHECK(e.column() == column);
    CHECK_THAT(e.message(), Catch::Contains(fragment));
    CHECK(std::string(e.what()) ==
          "t.csv:" + std::to_string(line) + ":" + std::to_string(column) + ": " + e.message());
  }
}

}  // namespace

TEST_CASE("a header and numbers give a column-major matrix", "[csv]") {
  const CsvTable t = parse("x,y\n1,2\n3,4.5\n-6e2,.25\n");
  CHECK(t.has_header);
  CHECK(t.column_names == std::vector<std::string>{"x", "y"});
  REQUIRE(t.features.rows() == 3);
  REQUIRE(t.features.cols() == 2);
  CHECK(t.features(0, 0) == 1.0);
  CHECK(t.features(1, 1) == 4.5);
  CHECK(t.features(2, 0) == -600.0);
  CHECK(t.features(2, 1) == 0.25);
  // Column-major: the first column is contiguous.
  CHECK(t.features.data()[1] == 3.0);
  CHECK(t.row_lines == std::vector<std::size_t>{2, 3, 4});
  CHECK(t.feature_name(1) == "y");
  CHECK(t.labels.size() == 0);
  CHECK_FALSE(t.label_column.has_value());
}

TEST_CASE("values read back exactly as strtod reads them", "[csv]") {
  const CsvTable t = parse("0.1,1e-05,148.0,+2.5,4.9e-324,1e-400,-0\n", {});
  CHECK_FALSE(t.has_header);
  CHECK(t.features(0, 0) == 0.1);
  CHECK(t.features(0, 1) == 1e-05);
  CHECK(t.features(0, 2) == 148.0);
  CHECK(t.features(0, 3) == 2.5);
  CHECK(t.features(0, 4) == 4.9e-324);  // the smallest subnormal
  CHECK(t.features(0, 5) == 0.0);       // underflow reads as zero, as strtod does
  CHECK(std::signbit(t.features(0, 6)));
}

TEST_CASE("line ends, a missing final line break, trailing blank lines and a BOM", "[csv]") {
  const std::string expected = "a,b\n1,2\n3,4\n";
  for (const std::string& text :
       {expected, std::string("a,b\r\n1,2\r\n3,4\r\n"), std::string("a,b\n1,2\n3,4"),
        std::string("a,b\r\n1,2\r\n3,4"), std::string("a,b\n1,2\n3,4\n\n  \n\r\n"),
        std::string("\xEF\xBB\xBF") + expected}) {
    INFO(text);
    const CsvTable t = parse(text);
    CHECK(t.column_names == std::vector<std::string>{"a", "b"});
    REQUIRE(t.features.rows() == 2);
    CHECK(t.features(1, 0) == 3.0);
    CHECK(t.features(1, 1) == 4.0);
  }
}

TEST_CASE("blanks around cells and quoted cells", "[csv]") {
  const CsvTable t = parse(" \"first, name\" ,\"say \"\"hi\"\"\",  c\n 1 ,\t\"2\"\t, 3\n");
  CHECK(t.column_names == std::vector<std::string>{"first, name", "say \"hi\"", "c"});
  CHECK(t.features(0, 0) == 1.0);
  CHECK(t.features(0, 1) == 2.0);  // a quoted number is a number
  CHECK(t.features(0, 2) == 3.0);
}

TEST_CASE("header detection", "[csv]") {
  SECTION("a non-numeric cell makes a header, and empty names get x<j>") {
    const CsvTable t = parse(",b,2\n1,2,3\n");
    CHECK(t.has_header);
    CHECK(t.column_names == std::vector<std::string>{"x0", "b", "2"});
    // The numeric-looking name is reported so that the tool can warn.
    CHECK(t.numeric_header_cells == std::vector<std::size_t>{3});
  }
  SECTION("an all-numeric first line is data") {
    const CsvTable t = parse("0,1,2\n3,4,5\n");
    CHECK_FALSE(t.has_header);
    CHECK(t.features.rows() == 2);
    CHECK(t.column_names == std::vector<std::string>{"x0", "x1", "x2"});
    CHECK(t.numeric_header_cells.empty());
  }
  SECTION("a quoted numeric name makes a header") { CHECK(parse("\"0\",\"1\"\n3,4\n").has_header); }
  SECTION("forced header") {
    CsvOptions options;
    options.header = HeaderMode::Present;
    const CsvTable t = parse("0,1\n3,4\n", options);
    CHECK(t.has_header);
    CHECK(t.column_names == std::vector<std::string>{"0", "1"});
    CHECK(t.features.rows() == 1);
  }
  SECTION("forced no header: a name is then a bad number") {
    CsvOptions options;
    options.header = HeaderMode::Absent;
    require_error("a,b\n1,2\n", 1, 1, "\"a\" is not a number (field 1, \"x0\")", options);
  }
  SECTION("a first line with a missing value is data, not a header") {
    require_error("1,,3\n4,5,6\n", 1, 3, "empty cell (field 2, \"x1\")");
  }
}

TEST_CASE("default_names false: no x<j> names for a file without a header", "[csv]") {
  // The readers of fit and score need only the values: a file of 1e7 columns saved 320 MB of
  // made-up names. Messages still name the column x<j>; a header's names are kept.
  CsvOptions options;
  options.default_names = false;
  const CsvTable t = parse("0,1,2\n3,4,5\n", options);
  CHECK_FALSE(t.has_header);
  CHECK(t.column_names.empty());
  CHECK(t.n_features() == 3);
  CHECK(t.features == parse("0,1,2\n3,4,5\n").features);
  // feature_name() makes the name the default would have stored (the one-shot form prints it).
  const CsvTable named = parse("0,1,2\n3,4,5\n");
  for (Eigen::Index j = 0; j < 3; ++j) CHECK(t.feature_name(j) == named.feature_name(j));
  CHECK(t.feature_name(2) == "x2");
  CHECK_THROWS_WITH(parse("0,1,2\n3,x,5\n", options),
                    Catch::Contains("\"x\" is not a number (field 2, \"x1\")"));
  CHECK(parse("a,b\n1,2\n", options).column_names == std::vector<std::string>{"a", "b"});
  options.label_column = "x2";  // selecting by a made-up name still works
  const CsvTable labelled = parse("0,1,1\n3,4,0\n", options);
  CHECK(labelled.n_features() == 2);
  CHECK(labelled.labels == Eigen::Vector2i(1, 0));
  CHECK(labelled.feature_name(1) == "x1");
}

TEST_CASE("other delimiters", "[csv]") {
  CsvOptions options;
  options.delimiter = ';';
  const CsvTable semicolon = parse("a;b\n1.5;2\n", options);
  CHECK(semicolon.column_names == std::vector<std::string>{"a", "b"});
  CHECK(semicolon.features(0, 0) == 1.5);
  require_error("a;b\n1,5;2\n", 2, 1, "\"1,5\" is not a number",
                options);  // a comma is no separator

  options.delimiter = '\t';
  const CsvTable tsv = parse("a\tb\n 1\t2 \n", options);
  CHECK(tsv.features(0, 0) == 1.0);
  CHECK(tsv.features(0, 1) == 2.0);

  options.delimiter = ' ';
  REQUIRE_THROWS_AS(parse("a b\n1 2\n", options), std::invalid_argument);
}

TEST_CASE("the label column is split off the features", "[csv]") {
  const std::string text = "a,label,b\n1,0,2\n3,1,4\n5,0.0,6\n";
  for (const char* selector : {"label", "1"}) {
    const CsvTable t = parse(text, with_label(selector));
    REQUIRE(t.label_column == std::optional<std::size_t>(1));
    CHECK(t.feature_columns == std::vector<std::size_t>{0, 2});
    REQUIRE(t.features.cols() == 2);
    CHECK(t.features(1, 0) == 3.0);
    CHECK(t.features(1, 1) == 4.0);
    CHECK(t.labels == Eigen::Vector3i(0, 1, 0));
    CHECK(t.feature_name(1) == "b");
  }
  const CsvTable last = parse("a,b,label\n1,2,1\n", with_label("last"));
  CHECK(last.label_column == std::optional<std::size_t>(2));
  CHECK(last.feature_columns == std::vector<std::size_t>{0, 1});
  CHECK(last.labels == Eigen::VectorXi::Ones(1));

  SECTION("labels other than 0 and 1 are errors at their cell") {
    require_error("a,label\n1,0\n2,2\n", 3, 3, "label \"2\" is neither 0 nor 1 (field 2, \"label\"",
                  with_label("label"));
  }
  SECTION("unknown and ambiguous names") {
    REQUIRE_THROWS_WITH(
        parse(text, with_label("lbl")),
        Catch::Contains("no column is named \"lbl\"") && Catch::Contains("a, label, b"));
    REQUIRE_THROWS_WITH(parse(text, with_label("3")), Catch::Contains("0-based index below 3"));
    REQUIRE_THROWS_WITH(parse("a,a,b\n1,2,3\n", with_label("a")),
                        Catch::Contains("is used by columns 0 and 1"));
  }
  SECTION("the label cannot be the only column") {
    require_error("label\n1\n", 1, 1, "no feature columns left", with_label("label"));
  }
}

TEST_CASE("ignored columns are skipped without being parsed", "[csv]") {
  CsvOptions options = with_label("y");
  options.ignore_columns = {"id", "3"};
  const CsvTable t = parse("id,a,y,when,b\nrow-1,1,0,monday,2\n\"row,2\",3,1,,4\n", options);
  CHECK(t.ignored_columns == std::vector<std::size_t>{0, 3});
  CHECK(t.feature_columns == std::vector<std::size_t>{1, 4});
  REQUIRE(t.features.rows() == 2);
  CHECK(t.features(1, 0) == 3.0);
  CHECK(t.features(1, 1) == 4.0);
  CHECK(t.labels == Eigen::Vector2i(0, 1));
  // A ragged row is still an error, ignored columns or not.
  CsvOptions id_only;
  id_only.ignore_columns = {"id"};
  require_error("id,a\nx,1\ny\n", 3, 2, "row has 1 cells but line 1 has 2", id_only);

  options.ignore_columns = {"zz"};
  REQUIRE_THROWS_WITH(parse("id,a,y\n1,2,0\n", options),
                      Catch::Contains("ignored column: no column is named \"zz\""));
  options.ignore_columns = {"y"};
  REQUIRE_THROWS_WITH(parse("id,a,y\n1,2,0\n", options),
                      Catch::Contains("\"y\" cannot be both the label column and ignored"));
  options.ignore_columns = {"id", "a"};
  require_error("id,a,y\n1,2,0\n", 1, 1, "no feature columns left", options);
}

TEST_CASE("malformed input is reported at its line and column", "[csv][errors]") {
  require_error("", 1, 1, "empty input");
  require_error("\n\n", 1, 1, "empty input");
  require_error("a,b\n", 2, 1, "no data rows after the header");
  require_error("a,b\n\n", 3, 1, "no data rows after the header");
  require_error("a,b,c\n1,2,3\n4,5\n", 3, 4, "row has 2 cells but line 1 has 3");
  require_error("a,b,c\r\n1,2,3\r\n4,5\r\n", 3, 4, "row has 2 cells but line 1 has 3");
  require_error("a,b\n1,2\n3,4,5\n", 3, 5, "row has 3 cells but line 1 has 2");
  require_error("a,b\n1,2\n3,4,\n", 3, 5, "row has 3 cells but line 1 has 2");
  require_error("a,b\n1,2\n3,four\n", 3, 3, "\"four\" is not a number (field 2, \"b\")");
  require_error("a,b\n1,2\n3,  4x \n", 3, 5, "\"4x\" is not a number");
  require_error("a,b\n1,0x10\n", 2, 3, "\"0x10\" is not a number");
  require_error("a,b\n1,--2\n", 2, 3, "is not a number");
  require_error("a,b\n1,+-2\n", 2, 3, "is not a number");
  require_error("a,b\n1,2\r3\n", 2, 3, "\"2\\r3\" is not a number");  // a lone CR is no line end
  // A whole file of CR-only line ends is one line: said so, not "no data rows".
  require_error("a,b\r1,2\r3,4\r", 1, 4, "lines that end in CR alone");
  require_error("a,b\n1,NaN\n", 2, 3,
                "\"NaN\" is not a finite number (field 2, \"b\"); NaN and infinity");
  require_error("a,b\n-inf,1\n", 2, 1, "\"-inf\" is not a finite number (field 1, \"a\")");
  require_error("a,b\n1,infinity\n", 2, 3, "is not a finite number");
  require_error("a,b\n1,1e999\n", 2, 3,
                "\"1e999\" is beyond the range of a double (field 2, \"b\")");
  require_error("a,b\n1,-1e400\n", 2, 3, "beyond the range of a double");
  require_error("a,b\n1,\n", 2, 3, "empty cell (field 2, \"b\"); missing values are not supported");
  require_error("a,b\n1, \t\n", 2, 5, "empty cell");
  require_error("a,b\n1,2\n\n3,4\n", 3, 1, "blank line between rows");
  require_error("\na,b\n1,2\n", 1, 1, "blank line between rows");
  require_error("a,\"b\n1,2\n", 1, 3, "unterminated quoted cell");
  require_error("a,\"b\"x\n1,2\n", 1, 6, "unexpected \"x\" after a closing quote");
  require_error("a,b\n1,\"2\n", 2, 3, "unterminated quoted cell");
  // Control bytes are escaped and long cells cut in messages.
  require_error(std::string("a,b\n1,\x01z\n", 9), 2, 3, "\"\\x01z\" is not a number");
  require_error("a\n" + std::string(100, 'q') + "\n", 2, 1, "\"" + std::string(40, 'q') + "...\"");
}

TEST_CASE("read_csv reports files it cannot open without a position", "[csv][errors]") {
  try {
    static_cast<void>(hbos::cli::read_csv("/nonexistent/dir/data.csv"));
    FAIL("no error");
  } catch (const CsvError& e) {
    CHECK(e.line() == 0);
    CHECK(std::string(e.what()) ==
          "/nonexistent/dir/data.csv: cannot open: No such file or directory");
  }
}
