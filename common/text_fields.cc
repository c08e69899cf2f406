#include "common/text_fields.h"

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <system_error>

namespace rc {

std::vector<std::string_view> SplitFields(std::string_view line, bool comma_separated) {
  std::vector<std::string_view> out;
  if (comma_separated) {
    std::size_t start = 0;
    while (true) {
      std::size_t comma = line.find(',', start);
      std::string_view field = line.substr(start, comma == std::string_view::npos ? comma : comma - start);
      while (!field.empty() && (field.front() == ' ' || field.front() == '\t')) field.remove_prefix(1);
      while (!field.empty() && (field.back() == ' ' || field.back() == '\t')) field.remove_suffix(1);
      out.push_back(field);
      if (comma == std::string_view::npos) break;
      start = comma + 1;
    }
    return out;
  }
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
    std::size_t j = i;
    while (j < line.size() && line[j] != ' ' && line[j] != '\t') ++j;
    if (j > i) out.push_back(line.substr(i, j - i));
    i = j;
  }
  return out;
}

void StripUtf8Bom(std::string& text) {
  if (text.compare(0, kUtf8Bom.size(), kUtf8Bom) == 0) text.erase(0, kUtf8Bom.size());
}

void RejectDirectory(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw InputError(path, 0, "", "is a directory, not a file");
}

bool LooksNumeric(std::string_view token) {
  if (token.empty()) return false;
  const std::string text(token);
  char* end = nullptr;
  std::strtod(text.c_str(), &end);
  return end == text.c_str() + text.size();
}

LineReader::LineReader(std::istream& in, std::string file_name) : in_(in), file_(std::move(file_name)) {}

bool LineReader::Next(std::string& line) {
  errno = 0;
  if (!std::getline(in_, line)) {
    // getline sets badbit when the stream buffer's read fails (EISDIR for a
    // directory, EIO), and only eofbit/failbit at a true end of file.
    if (!in_.bad()) return false;
    const int error = errno;
    RejectDirectory(file_);
    if (error == EISDIR) throw InputError(file_, 0, "", "is a directory, not a file");
    throw InputError(file_, line_number_ + 1, "",
                     std::string("read error") + (error ? std::string(": ") + std::strerror(error) : ""));
  }
  ++line_number_;
  if (line_number_ == 1) StripUtf8Bom(line);
  if (!line.empty() && line.back() == '\r') line.pop_back();
  return true;
}

double LineReader::ParseDouble(std::string_view token, const std::string& field) const {
  // The common case without a copy: a plain decimal token that from_chars
  // reads whole, to a finite double. from_chars and strtod both round
  // correctly, so they give the same double (tested). Anything else (a '+'
  // sign, hexadecimal, inf, nan, out of range, junk) goes on to strtod,
  // which accepts or refuses it as it always has.
  double value = 0.0;
  const char* const last = token.data() + token.size();
  const auto [stop, error] = std::from_chars(token.data(), last, value);
  if (error == std::errc() && stop == last && std::isfinite(value)) return value;
  if (token.empty()) Fail(field, "empty value where a number was expected");
  std::string text(token);
  // strtod reads C99 hexadecimal floats; no format here writes them.
  if (text.find_first_of("xX") != std::string::npos && LooksNumeric(text))
    Fail(field, "'" + text + "' is a hexadecimal number; only decimal numbers are accepted");
  char* end = nullptr;
  errno = 0;
  value = std::strtod(text.c_str(), &end);
  if (end != text.c_str() + text.size()) Fail(field, "'" + text + "' is not a number");
  if (errno == ERANGE && std::abs(value) > 1.0) Fail(field, "'" + text + "' is out of range");
  if (!std::isfinite(value)) Fail(field, "'" + text + "' is not finite (NaN or inf)");
  return value;
}

long LineReader::ParseInt(std::string_view token, const std::string& field, long min_value, long max_value) const {
  if (token.empty()) Fail(field, "empty value where an integer was expected");
  std::string text(token);
  char* end = nullptr;
  errno = 0;
  long value = std::strtol(text.c_str(), &end, 10);
  if (end != text.c_str() + text.size() || errno == ERANGE) Fail(field, "'" + text + "' is not an integer");
  if (value < min_value || value > max_value)
    Fail(field,
         std::to_string(value) + " is outside [" + std::to_string(min_value) + ", " + std::to_string(max_value) + "]");
  return value;
}

void LineReader::Fail(const std::string& field, const std::string& problem) const {
  throw InputError(file_, line_number_, field, problem);
}

}  // namespace rc
