#pragma once
/// \file
/// Readers of PyOD 3.6.5's reference vectors (tests/data/hbos_pyod: CSV and JSON written by
/// PyOD), shared by the PyOD-mode tests. Test support, not part of the library. The readers take
/// every number with strtod, which gives back the exact doubles PyOD wrote.

#include <catch2/catch.hpp>

#include <Eigen/Core>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace hbos::test {

[[nodiscard]] inline std::string read_text(const std::string& path) {
  std::ifstream in(path);
  if (!in) FAIL("cannot open " << path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

/// Every number in a CSV or JSON text, in order.
[[nodiscard]] inline std::vector<double> numbers_in(const std::string& text) {
  std::vector<double> out;
  const char* p = text.c_str();
  while (*p != '\0') {
    if ((*p >= '0' && *p <= '9') || *p == '-' || *p == '.') {
      char* end = nullptr;
      out.push_back(std::strtod(p, &end));
      p = end;
    } else {
      ++p;
    }
  }
  return out;
}

/// Every number of a file as one vector.
[[nodiscard]] inline Eigen::VectorXd read_vector(const std::string& path) {
  const std::vector<double> v = numbers_in(read_text(path));
  return Eigen::Map<const Eigen::VectorXd>(v.data(), static_cast<Eigen::Index>(v.size()));
}

/// A CSV file of numbers, one row per non-empty line, every row as long as the first.
[[nodiscard]] inline Eigen::MatrixXd read_csv_matrix(const std::string& path) {
  std::istringstream in(read_text(path));
  std::vector<std::vector<double>> rows;
  for (std::string line; std::getline(in, line);)
    if (!line.empty()) rows.push_back(numbers_in(line));
  REQUIRE(!rows.empty());
  Eigen::MatrixXd X(static_cast<Eigen::Index>(rows.size()),
                    static_cast<Eigen::Index>(rows.front().size()));
  for (Eigen::Index i = 0; i < X.rows(); ++i) {
    const auto& row = rows[static_cast<std::size_t>(i)];
    REQUIRE(static_cast<Eigen::Index>(row.size()) == X.cols());
    for (Eigen::Index j = 0; j < X.cols(); ++j) X(i, j) = row[static_cast<std::size_t>(j)];
  }
  return X;
}

/// A JSON array of d arrays of numbers.
[[nodiscard]] inline std::vector<std::vector<double>> read_json_arrays(const std::string& path) {
  const std::string text = read_text(path);
  std::vector<std::vector<double>> out;
  std::size_t pos = text.find('[');
  while ((pos = text.find('[', pos + 1)) != std::string::npos) {
    const std::size_t end = text.find(']', pos);
    out.push_back(numbers_in(text.substr(pos + 1, end - pos - 1)));
    pos = end;
  }
  return out;
}

}  // namespace hbos::test
