// The simulator's truth tables: comma-separated, one header line, no quoting (docs in
// hil/sim/src/truth_writer.cpp). Every error names the file, the line and the column.
#pragma once

#include <filesystem>
#include <functional>
#include <istream>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace syncap::compare {

// One data row; typed getters throw InputError "<file>:<line>: field <column>: ...".
class CsvRow {
 public:
  CsvRow(const std::string& file, long line, const std::vector<std::string>& columns,
         std::vector<std::string_view> fields)
      : file_(file), line_(line), columns_(columns), fields_(std::move(fields)) {}

  std::string_view text(std::size_t column) const { return fields_.at(column); }
  long integer(std::size_t column) const;
  double number(std::size_t column) const;  // finite
  bool flag(std::size_t column) const;      // 0 or 1
  long line() const { return line_; }
  [[noreturn]] void fail(const std::string& what) const;

 private:
  [[noreturn]] void fail_field(std::size_t column, const std::string& what) const;

  const std::string& file_;
  long line_;
  const std::vector<std::string>& columns_;
  std::vector<std::string_view> fields_;
};

// Reads `path`: the first line must be the columns joined by commas, every further non-empty
// line must have as many fields; `on_row` sees each data row in file order.
void read_csv(const std::filesystem::path& path, const std::vector<std::string>& columns,
              const std::function<void(const CsvRow&)>& on_row);
// The same on a stream; `file` names it in messages.
void read_csv(std::istream& in, const std::string& file, const std::vector<std::string>& columns,
              const std::function<void(const CsvRow&)>& on_row);

}  // namespace syncap::compare
