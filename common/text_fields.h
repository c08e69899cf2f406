#pragma once
// Line-oriented text parsing that keeps track of where it is, so that every
// malformed value produces an InputError naming file, line and field.
#include <cstddef>
#include <istream>
#include <string>
#include <string_view>
#include <vector>

#include "common/input_error.h"

namespace rc {

// Splits on spaces, tabs and (optionally) commas; empty tokens are dropped
// unless the separator is a comma, where an empty field is itself an error
// the caller must see.
std::vector<std::string_view> SplitFields(std::string_view line, bool comma_separated = false);

// The UTF-8 byte-order mark (EF BB BF) that Windows editors such as Notepad
// put at the start of a text file. It is an encoding signature, not content:
// every text reader skips it at the very start of a file (and only there).
inline constexpr std::string_view kUtf8Bom = "\xEF\xBB\xBF";

// Removes a leading kUtf8Bom from the first line or the whole text of a file.
void StripUtf8Bom(std::string& text);

// Throws InputError (file, line 0) if `path` names a directory. On Linux an
// std::ifstream opens a directory without complaint and only its first read
// fails, which a reader would otherwise report as an empty or short file.
void RejectDirectory(const std::string& path);

// True when the whole token reads as a number in any form strtod knows
// (decimal, hexadecimal, inf, nan). For telling a header or a host name from
// data, never for accepting a value: ParseDouble decides that.
bool LooksNumeric(std::string_view token);

// Reads a file line by line, counting 1-based line numbers.
class LineReader {
 public:
  LineReader(std::istream& in, std::string file_name);
  // False at end of file. Strips a UTF-8 byte-order mark at the start of
  // line 1 and a trailing '\r' (files written on Windows). A failed read is
  // not an end of file: a directory given as the file, or an I/O error,
  // throws InputError naming the file.
  bool Next(std::string& line);
  long line_number() const { return line_number_; }
  const std::string& file() const { return file_; }

  // Parses a finite decimal double; throws InputError naming the field
  // otherwise. Refused: hexadecimal ("0x1p7", which strtod would take),
  // "inf", "nan", and values out of double's range. Every text format read
  // here is decimal, so a hex token is corruption or another tool's output,
  // and the ROS YAML reader refuses it too.
  double ParseDouble(std::string_view token, const std::string& field) const;
  // Parses an integer in [min_value, max_value].
  long ParseInt(std::string_view token, const std::string& field, long min_value, long max_value) const;
  [[noreturn]] void Fail(const std::string& field, const std::string& problem) const;

 private:
  std::istream& in_;
  std::string file_;
  long line_number_ = 0;
};

}  // namespace rc
