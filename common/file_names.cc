#include "common/file_names.h"

#include <algorithm>
#include <cctype>
#include <filesystem>

namespace rc {

bool FileNameEndsWith(const std::string& path, const std::string& lowercase_suffix) {
  std::string name = std::filesystem::path(path).filename().string();
  std::transform(name.begin(), name.end(), name.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return name.size() >= lowercase_suffix.size() &&
         name.compare(name.size() - lowercase_suffix.size(), lowercase_suffix.size(), lowercase_suffix) == 0;
}

}  // namespace rc
