#pragma once
// Parses the text of a user's JSON file (--backend-params, a preset, a
// --set value) into a document. The one place such text is parsed, so that
// every way JSON can be bad (a syntax error, a number beyond a double's
// range such as 1e400) becomes an InputError naming the file, the line where
// nlohmann reports one, and the field, never an escaped nlohmann exception.
#include <string>

#include <nlohmann/json.hpp>

namespace rc {

// Throws InputError(file_name, line, field, "not valid JSON: ...").
nlohmann::json ParseJsonDocument(const std::string& text, const std::string& file_name, const std::string& field = "");

}  // namespace rc
