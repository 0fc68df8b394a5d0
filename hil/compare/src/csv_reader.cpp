#include "csv_reader.hpp"

#include <charconv>
#include <cmath>
#include <fstream>

#include "input_error.hpp"

namespace syncap::compare {
namespace {

std::vector<std::string_view> split(std::string_view line) {
  std::vector<std::string_view> fields;
  for (std::size_t start = 0;;) {
    const std::size_t comma = line.find(',', start);
    fields.push_back(line.substr(start, comma - start));
    if (comma == std::string_view::npos) return fields;
    start = comma + 1;
  }
}

std::string joined(const std::vector<std::string>& columns) {
  std::string header;
  for (const auto& c : columns) header += (header.empty() ? "" : ",") + c;
  return header;
}

// Lines written on Windows end in "\r\n"; the "\r" is not part of the last field.
void drop_carriage_return(std::string& line) {
  if (!line.empty() && line.back() == '\r') line.pop_back();
}

template <typename T>
bool parse_whole(std::string_view text, T& value) {
  const char* end = text.data() + text.size();
  const auto [stop, ec] = std::from_chars(text.data(), end, value);
  return ec == std::errc() && stop == end && !text.empty();
}

}  // namespace

long CsvRow::integer(std::size_t column) const {
  long value = 0;
  if (!parse_whole(text(column), value)) fail_field(column, "is not an integer");
  return value;
}

double CsvRow::number(std::size_t column) const {
  double value = 0;
  if (!parse_whole(text(column), value) || !std::isfinite(value)) {
    fail_field(column, "is not a finite number");
  }
  return value;
}

bool CsvRow::flag(std::size_t column) const {
  if (text(column) != "0" && text(column) != "1") fail_field(column, "must be 0 or 1");
  return text(column) == "1";
}

void CsvRow::fail(const std::string& what) const { fail_at(file_, line_, what); }

void CsvRow::fail_field(std::size_t column, const std::string& what) const {
  fail("field " + columns_.at(column) + " '" + std::string(text(column)) + "' " + what);
}

void read_csv(const std::filesystem::path& path, const std::vector<std::string>& columns,
              const std::function<void(const CsvRow&)>& on_row) {
  std::ifstream in(path);
  if (!in) throw InputError(path.string() + ": cannot read");
  read_csv(in, path.string(), columns, on_row);
}

void read_csv(std::istream& in, const std::string& file, const std::vector<std::string>& columns,
              const std::function<void(const CsvRow&)>& on_row) {
  std::string line;
  const std::string header = joined(columns);
  if (!std::getline(in, line)) fail_at(file, 1, "empty, expected the header '" + header + "'");
  drop_carriage_return(line);
  if (line != header) fail_at(file, 1, "expected the header '" + header + "', got '" + line + "'");
  for (long number = 2; std::getline(in, line); ++number) {
    drop_carriage_return(line);
    if (line.empty()) continue;
    auto fields = split(line);
    if (fields.size() != columns.size()) {
      fail_at(file, number,
              "expected " + std::to_string(columns.size()) + " fields, got " +
                  std::to_string(fields.size()));
    }
    on_row(CsvRow(file, number, columns, std::move(fields)));
  }
}

}  // namespace syncap::compare
