#include "backends/json_document.h"

#include <algorithm>

#include "common/input_error.h"

namespace rc {
namespace {

// The 1-based line of `text` holding its 1-based byte `byte` (how nlohmann
// places a parse error); 0 when the error has no place.
long LineOfByte(const std::string& text, std::size_t byte) {
  if (byte == 0) return 0;
  const std::size_t before = std::min(byte - 1, text.size());
  return 1 + static_cast<long>(std::count(text.begin(), text.begin() + static_cast<long>(before), '\n'));
}

}  // namespace

nlohmann::json ParseJsonDocument(const std::string& text, const std::string& file_name, const std::string& field) {
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    throw InputError(file_name, LineOfByte(text, e.byte), field, std::string("not valid JSON: ") + e.what());
  } catch (const nlohmann::json::exception& e) {  // out_of_range: a number beyond a double's range
    throw InputError(file_name, 0, field, std::string("not valid JSON: ") + e.what());
  }
}

}  // namespace rc
