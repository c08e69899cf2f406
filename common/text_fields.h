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

// Reads a file line by line, counting 1-based line numbers.
class LineReader {
 public:
  LineReader(std::istream& in, std::string file_name);
  // False at end of file. Strips a trailing '\r' (files written on Windows).
  bool Next(std::string& line);
  long line_number() const { return line_number_; }
  const std::string& file() const { return file_; }

  // Parses a finite double; throws InputError naming the field otherwise.
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
