#pragma once
// File-name tests that format detection shares.
#include <string>

namespace rc {

// True when the file name of `path` ends with `lowercase_suffix`, ignoring
// the case of the name (".gridmap.gz" matches "Map.GRIDMAP.gz").
bool FileNameEndsWith(const std::string& path, const std::string& lowercase_suffix);

}  // namespace rc
