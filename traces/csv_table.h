#pragma once
// Timeline tables as CSV: columns are declared up front by name, and the
// names carry their units ("est_x_m", "cycles", "energy_J"). Rows stream into
// a temporary file beside the output; Commit() renames it into place, so a
// run that fails midway leaves no partial table (common/atomic_file.h).
// Memory stays constant however long the timeline.
//
// No NaN or inf reaches a table: a missing value must be written as an
// explicit CsvCell::Empty(), so "not computed" is always a decision.
#include <cstddef>
#include <memory>
#include <string>
#include <string_view>
#include <type_traits>
#include <variant>
#include <vector>

#include "common/atomic_file.h"

namespace rc {

class CsvCell {
 public:
  CsvCell(double value) : value_(value) {}  // NOLINT: cells are built implicitly
  template <typename T, std::enable_if_t<std::is_integral_v<T> && !std::is_same_v<T, bool>, int> = 0>
  CsvCell(T value) {  // NOLINT
    if constexpr (std::is_signed_v<T>) value_ = static_cast<long long>(value);
    else value_ = static_cast<unsigned long long>(value);
  }
  CsvCell(bool) = delete;  // a pointer or condition passed by mistake; write 0/1 explicitly
  CsvCell(std::string value) : value_(std::move(value)) {}  // NOLINT
  CsvCell(std::string_view value) : value_(std::string(value)) {}  // NOLINT
  CsvCell(const char* value) : value_(std::string(value)) {}  // NOLINT

  static CsvCell Empty() { return CsvCell(); }

  bool is_empty() const { return std::holds_alternative<std::monostate>(value_); }
  // The text written to the file (unquoted); throws std::invalid_argument for
  // NaN or inf, naming nothing: the table adds the column and row.
  std::string Format(int significant_digits) const;

 private:
  CsvCell() = default;
  std::variant<std::monostate, double, long long, unsigned long long, std::string> value_;
};

struct CsvTableOptions {
  // %.9g by default: float-exact, nm-exact for positions in m. Absolute
  // CARMEN times (about 1e9 s) need 16 or 17 to keep microseconds.
  int significant_digits = 9;
};

class CsvTable {
 public:
  // A row filled by column name; every column must be set before AddRow.
  class Row {
   public:
    Row& Set(std::string_view column, CsvCell cell);

   private:
    friend class CsvTable;
    explicit Row(const CsvTable& table);
    const CsvTable* table_;
    std::vector<CsvCell> cells_;
    std::vector<bool> set_;
  };

  // Opens the temporary file and writes the header. Throws
  // std::invalid_argument for empty, duplicate or unquotable (comma, quote,
  // newline) column names; std::runtime_error if the file cannot be opened.
  CsvTable(std::string path, std::vector<std::string> columns, CsvTableOptions options = {});

  const std::vector<std::string>& columns() const { return columns_; }
  // Throws std::invalid_argument for a name that is not a column.
  std::size_t ColumnIndex(std::string_view name) const;
  std::size_t row_count() const { return row_count_; }

  Row NewRow() const { return Row(*this); }
  void AddRow(const Row& row);
  // Cells in column order. Throws std::invalid_argument on a wrong cell count
  // or a NaN/inf cell (naming column and row); std::logic_error after Commit.
  void AddRow(const std::vector<CsvCell>& cells);

  // Flushes and renames into place; throws std::runtime_error on I/O failure.
  void Commit();

 private:
  std::string path_;
  std::vector<std::string> columns_;
  CsvTableOptions options_;
  std::unique_ptr<AtomicFile> file_;  // null after Commit
  std::size_t row_count_ = 0;
};

// A minimal RFC 4180 reader (quoted fields, doubled quotes, embedded commas
// and newlines), for tests and tools that check written tables. Throws
// InputError (file, line, field) on an unterminated quote, text after a
// closing quote, a row whose width differs from the header, or an empty file.
struct CsvContents {
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
};
CsvContents ReadCsv(const std::string& path);

}  // namespace rc
