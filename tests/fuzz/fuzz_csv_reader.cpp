// libFuzzer target: the CSV reader of hbos-score (examples/hbos_score/csv_reader.hpp), whole and
// streaming, with fuzzed options. Documented outcomes: a table, CsvError for malformed text, or
// std::invalid_argument for options naming no column; nothing else.

#include <cstdint>
#include <stdexcept>
#include <string>

#include "csv_reader.hpp"
#include "fuzz_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  hbos::fuzz::FuzzInput in(data, size);
  hbos::cli::CsvOptions options;
  const std::uint8_t mode = in.byte();
  options.header = static_cast<hbos::cli::HeaderMode>(mode % 3);
  if ((mode & 0x10U) != 0) options.delimiter = static_cast<char>(in.byte());
  if ((mode & 0x20U) != 0) options.label_column = (mode & 0x40U) != 0 ? "last" : "1";
  if ((mode & 0x80U) != 0) options.ignore_columns = {"0"};
  const std::string_view text = in.rest();
  try {
    const hbos::cli::CsvTable table = hbos::cli::parse_csv(text, "fuzz.csv", options);
    if (table.features.rows() != static_cast<Eigen::Index>(table.row_lines.size())) std::abort();
  } catch (const hbos::cli::CsvError&) {
  } catch (const std::invalid_argument&) {
  }
  try {
    std::size_t rows = 0;
    hbos::cli::CsvHandlers handlers;
    handlers.on_layout = [](const hbos::cli::CsvLayout&) {};
    handlers.on_row = [&rows](const hbos::cli::CsvRow&) { ++rows; };
    hbos::cli::parse_csv_rows(text, "fuzz.csv", options, handlers);
  } catch (const hbos::cli::CsvError&) {
  } catch (const std::invalid_argument&) {
  }
  return 0;
}
