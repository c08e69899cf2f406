#include "traces/csv_table.h"

#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include <fmt/format.h>

#include "common/input_error.h"
#include "common/text_fields.h"

namespace rc {
namespace {

bool NeedsQuotes(std::string_view text) { return text.find_first_of(",\"\r\n") != std::string_view::npos; }

std::string Quoted(std::string_view text) {
  if (!NeedsQuotes(text)) return std::string(text);
  std::string out = "\"";
  for (char c : text) {
    if (c == '"') out += '"';
    out += c;
  }
  return out + "\"";
}

}  // namespace

std::string CsvCell::Format(int significant_digits) const {
  struct Visitor {
    int digits;
    std::string operator()(std::monostate) const { return ""; }
    std::string operator()(double v) const {
      if (!std::isfinite(v)) throw std::invalid_argument(std::isnan(v) ? "NaN" : "infinite value");
      return fmt::format("{:.{}g}", v, digits);
    }
    std::string operator()(long long v) const { return std::to_string(v); }
    std::string operator()(unsigned long long v) const { return std::to_string(v); }
    std::string operator()(const std::string& v) const { return Quoted(v); }
  };
  return std::visit(Visitor{significant_digits}, value_);
}

CsvTable::Row::Row(const CsvTable& table)
    : table_(&table), cells_(table.columns().size(), CsvCell::Empty()), set_(table.columns().size(), false) {}

CsvTable::Row& CsvTable::Row::Set(std::string_view column, CsvCell cell) {
  const std::size_t i = table_->ColumnIndex(column);
  cells_[i] = std::move(cell);
  set_[i] = true;
  return *this;
}

CsvTable::CsvTable(std::string path, std::vector<std::string> columns, CsvTableOptions options)
    : path_(std::move(path)), columns_(std::move(columns)), options_(std::move(options)) {
  if (columns_.empty()) throw std::invalid_argument("CSV table '" + path_ + "' has no columns");
  if (options_.significant_digits < 1 || options_.significant_digits > 17)
    throw std::invalid_argument("CSV significant digits must be in [1, 17]");
  if (!options_.timeline && !options_.hindsight_columns.empty())
    throw std::invalid_argument("CSV table '" + path_ + "': hindsight columns need a timeline");
  std::vector<std::string> all = columns_;
  all.insert(all.end(), options_.hindsight_columns.begin(), options_.hindsight_columns.end());
  for (std::size_t i = 0; i < all.size(); ++i) {
    const std::string& name = all[i];
    if (name.empty() || NeedsQuotes(name))
      throw std::invalid_argument("CSV table '" + path_ + "': column " + std::to_string(i + 1) + " name '" + name +
                                  "' is empty or holds a comma, quote or newline");
    for (std::size_t j = 0; j < i; ++j)
      if (all[j] == name) throw std::invalid_argument("CSV table '" + path_ + "': duplicate column '" + name + "'");
  }
  std::string header;
  for (std::size_t i = 0; i < columns_.size(); ++i) header += (i ? "," : "") + columns_[i];
  if (!options_.timeline) {
    file_ = std::make_unique<AtomicFile>(path_);
    file_->stream() << header << '\n';
    return;
  }
  CreateParentFolders(path_);
  live_ = std::make_unique<std::ofstream>(path_, std::ios::binary | std::ios::trunc);
  if (!*live_) throw OutputError(path_, std::string("cannot open for writing: ") + std::strerror(errno));
  WriteLine(kIncompleteMarker);
  WriteLine(header);
  header_end_ = static_cast<std::uint64_t>(live_->tellp());
}

CsvTable::~CsvTable() = default;  // a timeline keeps its marked prefix

void CsvTable::WriteLine(const std::string& line) {
  *live_ << line << '\n';
  live_->flush();  // one row at a time: a killed run leaves whole rows
  if (!*live_) throw OutputError(path_, "write error (disk full?)");
}

std::size_t CsvTable::ColumnIndex(std::string_view name) const {
  for (std::size_t i = 0; i < columns_.size(); ++i)
    if (columns_[i] == name) return i;
  throw std::invalid_argument("CSV table '" + path_ + "' has no column '" + std::string(name) + "'");
}

void CsvTable::AddRow(const Row& row) {
  if (row.table_ != this) throw std::logic_error("CSV row built for another table");
  for (std::size_t i = 0; i < columns_.size(); ++i)
    if (!row.set_[i])
      throw std::invalid_argument("CSV table '" + path_ + "' row " + std::to_string(row_count_ + 1) + ": column '" +
                                  columns_[i] + "' not set (use CsvCell::Empty() for a missing value)");
  AddRow(row.cells_);
}

std::string CsvTable::FormatRow(const std::vector<CsvCell>& cells, const std::vector<std::string>& names,
                                std::size_t row) const {
  if (cells.size() != names.size())
    throw std::invalid_argument("CSV table '" + path_ + "' row " + std::to_string(row + 1) + " has " +
                                std::to_string(cells.size()) + " cells for " + std::to_string(names.size()) +
                                " columns");
  std::string line;
  for (std::size_t i = 0; i < cells.size(); ++i) {
    if (i) line += ',';
    try {
      line += cells[i].Format(options_.significant_digits);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument("CSV table '" + path_ + "' row " + std::to_string(row + 1) + " column '" + names[i] +
                                  "': " + e.what() + " (write CsvCell::Empty() for a missing value)");
    }
  }
  return line;
}

void CsvTable::AddRow(const std::vector<CsvCell>& cells) {
  if (!file_ && !live_) throw std::logic_error("CSV table '" + path_ + "' is already committed");
  const std::string line = FormatRow(cells, columns_, row_count_);
  if (file_) {
    file_->stream() << line << '\n';
  } else {
    WriteLine(line);
    row_ends_.push_back(static_cast<std::uint64_t>(live_->tellp()));
  }
  ++row_count_;
}

void CsvTable::Commit() {
  if (!options_.hindsight_columns.empty())
    throw std::logic_error("CSV table '" + path_ + "' has hindsight columns: commit with their cells");
  Commit({});
}

void CsvTable::Commit(const std::function<std::vector<CsvCell>(std::size_t row)>& cells_of_row) {
  if (!file_ && !live_) throw std::logic_error("CSV table '" + path_ + "' is already committed");
  if (file_) {
    file_->Commit();
    file_.reset();
    return;
  }
  live_->close();
  live_.reset();
  // The complete table replaces the marked prefix in one rename.
  std::ifstream prefix(path_, std::ios::binary);
  if (!prefix) throw OutputError(path_, "cannot reopen the timeline to complete it");
  AtomicFile complete(path_);
  std::ostream& out = complete.stream();
  for (std::size_t i = 0; i < columns_.size(); ++i) out << (i ? "," : "") << columns_[i];
  for (const std::string& name : options_.hindsight_columns) out << ',' << name;
  out << '\n';
  prefix.seekg(static_cast<std::streamoff>(header_end_));
  std::uint64_t at = header_end_;
  std::string text;
  for (std::size_t r = 0; r < row_ends_.size(); ++r) {
    text.resize(row_ends_[r] - at - 1);  // without the newline
    prefix.read(text.data(), static_cast<std::streamsize>(text.size()));
    prefix.get();
    if (!prefix) throw OutputError(path_, "the timeline changed while it was being written");
    at = row_ends_[r];
    out << text;
    if (!options_.hindsight_columns.empty()) out << ',' << FormatRow(cells_of_row(r), options_.hindsight_columns, r);
    out << '\n';
  }
  complete.Commit();
}

CsvContents ReadCsv(const std::string& path) {
  RejectDirectory(path);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, 0, "", "cannot open CSV file");
  std::stringstream buffer;
  buffer << in.rdbuf();
  std::string text = buffer.str();
  StripUtf8Bom(text);

  CsvContents contents;
  long line = 1;
  const std::string marker = std::string(kIncompleteMarker) + "\n";
  if (text.compare(0, marker.size(), marker) == 0) {
    contents.complete = false;
    text.erase(0, marker.size());
    line = 2;
    // A writer killed mid-row leaves a last line without its newline.
    if (!text.empty() && text.back() != '\n') {
      const std::size_t last = text.rfind('\n');
      text.erase(last == std::string::npos ? 0 : last + 1);
      contents.dropped_partial_rows = 1;
    }
  }
  std::vector<std::string> record;
  std::string field;
  long record_line = line;
  auto field_name = [&] { return "column " + std::to_string(record.size() + 1); };
  auto end_record = [&] {
    record.push_back(field);
    field.clear();
    if (contents.header.empty()) {
      contents.header = std::move(record);
    } else if (record.size() != contents.header.size()) {
      throw InputError(path, record_line, "column count",
                       std::to_string(record.size()) + " fields, header has " + std::to_string(contents.header.size()));
    } else {
      contents.rows.push_back(std::move(record));
    }
    record.clear();
  };

  std::size_t i = 0;
  bool at_field_start = true;
  while (i < text.size()) {
    const char c = text[i];
    if (at_field_start && c == '"') {
      const long quote_line = line;
      ++i;
      while (true) {
        if (i >= text.size()) throw InputError(path, quote_line, field_name(), "unterminated quote");
        if (text[i] == '"') {
          if (i + 1 < text.size() && text[i + 1] == '"') {
            field += '"';
            i += 2;
            continue;
          }
          ++i;
          break;
        }
        if (text[i] == '\n') ++line;
        field += text[i++];
      }
      if (i < text.size() && text[i] != ',' && text[i] != '\n' && text[i] != '\r')
        throw InputError(path, line, field_name(), "text after a closing quote");
      at_field_start = false;
      continue;
    }
    if (c == ',') {
      record.push_back(field);
      field.clear();
      at_field_start = true;
    } else if (c == '\r' && i + 1 < text.size() && text[i + 1] == '\n') {
      // CRLF: the '\n' ends the record
    } else if (c == '\n') {
      end_record();
      ++line;
      record_line = line;
      at_field_start = true;
    } else {
      field += c;
      at_field_start = false;
    }
    ++i;
  }
  if (!field.empty() || !record.empty() || !at_field_start) end_record();
  if (contents.header.empty()) throw InputError(path, 0, "header", "empty CSV file");
  return contents;
}

}  // namespace rc
