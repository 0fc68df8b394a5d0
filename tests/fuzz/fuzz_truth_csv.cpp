// libFuzzer target: the CSV reader of syncap-hil-compare (compare::read_csv and its typed
// getters) on the simulator's truth tables, each read as truth.cpp reads it. The first input
// byte picks the table (frames.csv, projections.csv, targets.csv), the rest is the file's text.
//
// Contract: the reader and the getters return or throw compare::InputError, nothing else; a
// row's number() is finite and its flag() is what the field says.
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string>
#include <vector>

#include "csv_reader.hpp"
#include "fuzz_check.hpp"
#include "input_error.hpp"

namespace {

// How each table's columns are read: i integer, n number, t text, f flag.
struct Table {
  std::vector<std::string> columns;
  const char* getters;
};

const std::array<Table, 3> kTables{{
    {{"frame", "time_s", "phase", "phase_type", "led_on", "gain"}, "initfn"},
    {{"frame", "camera", "target", "x_px", "y_px", "radius_px", "visible"}, "iiinnnf"},
    {{"frame", "target", "X_mm", "Y_mm", "Z_mm", "radius_mm"}, "iinnnn"},
}};

void read_row(const syncap::compare::CsvRow& row, const char* getters) {
  for (std::size_t column = 0; getters[column] != '\0'; ++column) {
    switch (getters[column]) {
      case 'i':
        row.integer(column);
        break;
      case 'n':
        syncap::fuzz::check(std::isfinite(row.number(column)), "number() is not finite");
        break;
      case 'f':
        syncap::fuzz::check(row.flag(column) == (row.text(column) == "1"), "flag() is wrong");
        break;
      default:
        row.text(column);
        break;
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  const Table& table = kTables[data[0] % kTables.size()];
  std::istringstream in(std::string(reinterpret_cast<const char*>(data) + 1, size - 1));
  syncap::fuzz::decodes<syncap::compare::InputError>("read_csv", [&] {
    syncap::compare::read_csv(
        in, "truth.csv", table.columns,
        [&](const syncap::compare::CsvRow& row) { read_row(row, table.getters); });
  });
  return 0;
}
