#include "maps/image_signature.h"

#include <cctype>

namespace rc {

const char* const kMapImageFormats = "PNG, PNM (PGM/PPM/PBM), JPEG or BMP";

std::optional<std::string> MapImageFormatOf(const std::string& head) {
  auto starts = [&head](const std::string& signature) { return head.compare(0, signature.size(), signature) == 0; };
  if (starts(std::string("\x89PNG\r\n\x1a\n", 8))) return "PNG";
  if (starts("\xff\xd8\xff")) return "JPEG";
  if (starts("BM")) return "BMP";
  // Netpbm: 'P', a type digit 1-6, then white space.
  if (head.size() >= 3 && head[0] == 'P' && head[1] >= '1' && head[1] <= '6' &&
      std::isspace(static_cast<unsigned char>(head[2])))
    return "PNM";
  return std::nullopt;
}

}  // namespace rc
