#pragma once
// Tables as CSV: columns are declared up front by name, and the names carry
// their units ("est_x_m", "cycles", "energy_J"). Memory stays constant
// however long the table (a timeline's hindsight columns aside, see below).
//
// Two ways to reach the output path:
// - atomic (the default, for results such as a path): rows stream into a
//   temporary file beside the output and Commit() renames it into place, so
//   a run that fails midway leaves no table at all (common/atomic_file.h);
// - timeline (CsvTableOptions::timeline): rows stream into the output path
//   itself, flushed one by one, below a first line kIncompleteMarker. A run
//   that is killed or fails leaves that marked, valid prefix; Commit()
//   replaces it atomically with the complete table, which has no marker.
//   A timeline may declare hindsight columns, whose values exist only when
//   the run is over (the hindsight oracle's schedule): the prefix lacks them
//   and Commit() appends them to every row.
//
// No NaN or inf reaches a table: a missing value must be written as an
// explicit CsvCell::Empty(), so "not computed" is always a decision.
#include <cstddef>
#include <cstdint>
#include <fstream>
#include <functional>
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
    if constexpr (std::is_signed_v<T>)
      value_ = static_cast<long long>(value);
    else
      value_ = static_cast<unsigned long long>(value);
  }
  CsvCell(bool) = delete;  // a pointer or condition passed by mistake; write 0/1 explicitly
  CsvCell(std::string value) : value_(std::move(value)) {}         // NOLINT
  CsvCell(std::string_view value) : value_(std::string(value)) {}  // NOLINT
  CsvCell(const char* value) : value_(std::string(value)) {}       // NOLINT

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
  // Stream to the output path with the incomplete marker (see above).
  bool timeline = false;
  // Timeline only: columns appended by Commit(hindsight), after `columns`.
  std::vector<std::string> hindsight_columns;
};

// First line of a timeline until its run completes. It starts with '#', so
// CSV readers that skip comments (ReadCsv, pandas comment='#') read the rows
// below it; readers that do not will fail loudly rather than take the prefix
// for a complete run.
inline constexpr const char* kIncompleteMarker =
    "# rcbench: INCOMPLETE timeline - the run has not finished (still running, killed or failed); "
    "the rows below are a valid prefix";

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

  // Opens the temporary file (timeline: the output, creating its folders)
  // and writes the header. Throws std::invalid_argument for empty, duplicate
  // or unquotable (comma, quote, newline) column names; OutputError if the
  // file cannot be opened.
  CsvTable(std::string path, std::vector<std::string> columns, CsvTableOptions options = {});
  ~CsvTable();
  CsvTable(const CsvTable&) = delete;
  CsvTable& operator=(const CsvTable&) = delete;

  const std::vector<std::string>& columns() const { return columns_; }
  // Throws std::invalid_argument for a name that is not a column.
  std::size_t ColumnIndex(std::string_view name) const;
  std::size_t row_count() const { return row_count_; }

  Row NewRow() const { return Row(*this); }
  void AddRow(const Row& row);
  // Cells in column order. Throws std::invalid_argument on a wrong cell count
  // or a NaN/inf cell (naming column and row); std::logic_error after Commit.
  void AddRow(const std::vector<CsvCell>& cells);

  // Flushes and renames into place; throws OutputError on I/O failure.
  // Not for a table with hindsight columns.
  void Commit();
  // Timeline with hindsight columns: cells_of_row(i) gives row i's
  // hindsight cells, in hindsight_columns order.
  void Commit(const std::function<std::vector<CsvCell>(std::size_t row)>& cells_of_row);

 private:
  std::string FormatRow(const std::vector<CsvCell>& cells, const std::vector<std::string>& names,
                        std::size_t row) const;
  void WriteLine(const std::string& line);

  std::string path_;
  std::vector<std::string> columns_;
  CsvTableOptions options_;
  std::unique_ptr<AtomicFile> file_;     // atomic mode; null after Commit
  std::unique_ptr<std::ofstream> live_;  // timeline mode; null after Commit
  // Timeline mode: byte offset just past each row's newline, so Commit can
  // find the rows again (a quoted cell may hold a newline).
  std::vector<std::uint64_t> row_ends_;
  std::uint64_t header_end_ = 0;
  std::size_t row_count_ = 0;
};

// A minimal RFC 4180 reader (quoted fields, doubled quotes, embedded commas
// and newlines), for tests and tools that check written tables. Throws
// InputError (file, line, field) on an unterminated quote, text after a
// closing quote, a row whose width differs from the header, an empty file or
// a directory. A leading UTF-8 byte-order mark is skipped (spreadsheets write
// one).
// A first line kIncompleteMarker marks a timeline prefix: complete is then
// false, and a last row cut off before its newline (the writer was killed
// mid-row) is dropped and counted rather than reported as an error.
struct CsvContents {
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
  bool complete = true;
  long dropped_partial_rows = 0;
};
CsvContents ReadCsv(const std::string& path);

}  // namespace rc
