#pragma once
// The image formats a map may come in, told by their first bytes (never by
// the file name): PNG, PNM (PBM/PGM/PPM, P1-P6), JPEG and BMP, the formats
// ROS map_server users save maps in. OpenCV decodes whatever its decoders
// recognize, including DICOM through GDCM, which aborts the process on a
// malformed file instead of failing; so only these reach OpenCV.
#include <optional>
#include <string>

namespace rc {

// The list above, for messages: "PNG, PNM (PGM/PPM/PBM), JPEG or BMP".
extern const char* const kMapImageFormats;

// The format whose signature `head` (the file's first bytes, at least 8
// when the file has them) starts with: "PNG", "PNM", "JPEG" or "BMP";
// nullopt for anything else.
std::optional<std::string> MapImageFormatOf(const std::string& head);

}  // namespace rc
