#include "maps/image_png_check.h"

#include <cctype>
#include <cstdint>
#include <fstream>

#include <zlib.h>

#include "common/input_error.h"

namespace rc {
namespace {

constexpr std::uint32_t kMaxChunkLength = 0x7fffffff;  // the specification's limit (2^31 - 1)
const std::string kSignature("\x89PNG\r\n\x1a\n", 8);

// CRC-32 as the PNG specification's annex D defines it, which is zlib's
// crc32 (the same polynomial, start and final inversion).
class Crc32 {
 public:
  void Add(const char* data, std::size_t size) { crc_ = crc32_z(crc_, reinterpret_cast<const Bytef*>(data), size); }
  std::uint32_t Value() const { return static_cast<std::uint32_t>(crc_); }

 private:
  uLong crc_ = crc32_z(0L, Z_NULL, 0);
};

std::uint32_t BigEndian(const char* bytes) {
  std::uint32_t v = 0;
  for (int i = 0; i < 4; ++i) v = (v << 8) | static_cast<std::uint8_t>(bytes[i]);
  return v;
}

bool IsLetter(char c) { return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z'); }

// Bit depths the specification allows for each colour type (table 11.1).
bool DepthAllowed(int colour_type, int depth) {
  switch (colour_type) {
    case 0: return depth == 1 || depth == 2 || depth == 4 || depth == 8 || depth == 16;
    case 3: return depth == 1 || depth == 2 || depth == 4 || depth == 8;
    case 2:
    case 4:
    case 6: return depth == 8 || depth == 16;
    default: return false;
  }
}

class PngWalker {
 public:
  explicit PngWalker(const std::string& path) : path_(path), in_(path, std::ios::binary) {
    if (!in_) throw InputError(path_, 0, "", "cannot open image file");
  }

  void Check() {
    std::string signature(8, '\0');
    if (!Read(signature.data(), 8) || signature != kSignature)
      throw InputError(path_, 0, "signature", "not the 8-byte PNG signature");
    bool seen_plte = false, in_idat_run = false, idat_run_ended = false;
    int colour_type = -1;
    for (long index = 1;; ++index) {
      const std::uint64_t start = offset_;
      char header[8];
      if (!Read(header, 8)) {
        if (offset_ == start)
          throw InputError(path_, 0, "IEND",
                           "truncated: the file ends after chunk " + std::to_string(index - 1) + ", without IEND");
        throw InputError(path_, 0, "chunk " + std::to_string(index),
                         "truncated: the file ends at byte " + std::to_string(offset_) +
                             ", inside the header of the chunk at byte " + std::to_string(start));
      }
      const std::uint32_t length = BigEndian(header);
      const std::string type(header + 4, 4);
      for (char c : type)
        if (!IsLetter(c))
          throw InputError(path_, 0, "chunk " + std::to_string(index),
                           "the chunk at byte " + std::to_string(start) +
                               " has no valid type (four ASCII letters): the file is corrupt");
      const std::string at = " (chunk " + std::to_string(index) + ", at byte " + std::to_string(start) + ")";
      if (length > kMaxChunkLength)
        throw InputError(path_, 0, type,
                         "declares " + std::to_string(length) + " data bytes, above the limit of " +
                             std::to_string(kMaxChunkLength) + at);
      if (index == 1 && type != "IHDR")
        throw InputError(path_, 0, "IHDR", "the first chunk is '" + type + "', not IHDR" + at);
      if (index > 1 && type == "IHDR") throw InputError(path_, 0, type, "appears a second time" + at);

      std::string data;
      Crc32 crc;
      crc.Add(type.data(), 4);
      if (type == "IHDR" || type == "IEND") {  // small: kept for the checks below
        if (length != (type == "IHDR" ? 13u : 0u))
          throw InputError(path_, 0, type,
                           "is " + std::to_string(length) + " bytes long, not " + (type == "IHDR" ? "13" : "0") + at);
        data.resize(length);
        if (!Read(data.data(), length)) Truncated(type, length, at);
        crc.Add(data.data(), data.size());
      } else {
        SkipData(crc, type, length, at);
      }
      char stored[4];
      if (!Read(stored, 4)) Truncated(type, length, at);
      if (BigEndian(stored) != crc.Value())
        throw InputError(path_, 0, type, "CRC mismatch: the chunk's bytes are corrupt" + at);

      if (type == "IHDR") {
        colour_type = CheckHeader(data, at);
      } else if (type == "PLTE") {
        seen_plte = true;
      } else if (type == "IDAT") {
        if (idat_run_ended) throw InputError(path_, 0, type, "follows another chunk after the IDAT chunks" + at);
        if (colour_type == 3 && !seen_plte)
          throw InputError(path_, 0, type, "comes before PLTE in a palette image" + at);
        in_idat_run = true;
      } else if (type == "IEND") {
        if (!in_idat_run && !idat_run_ended) throw InputError(path_, 0, type, "comes before any IDAT chunk" + at);
        return;
      } else if (std::isupper(static_cast<unsigned char>(type[0]))) {
        throw InputError(path_, 0, type, "is a critical chunk type that PNG readers do not know" + at);
      }
      if (type != "IDAT" && in_idat_run) {
        in_idat_run = false;
        idat_run_ended = true;
      }
    }
  }

 private:
  bool Read(char* out, std::uint64_t size) {
    in_.read(out, static_cast<std::streamsize>(size));
    offset_ += static_cast<std::uint64_t>(in_.gcount());
    return static_cast<std::uint64_t>(in_.gcount()) == size;
  }

  void SkipData(Crc32& crc, const std::string& type, std::uint32_t length, const std::string& at) {
    char block[65536];
    for (std::uint64_t left = length; left > 0;) {
      const std::uint64_t take = left < sizeof block ? left : sizeof block;
      const bool whole = Read(block, take);
      crc.Add(block, static_cast<std::size_t>(in_.gcount()));
      if (!whole) Truncated(type, length, at);
      left -= take;
    }
  }

  [[noreturn]] void Truncated(const std::string& type, std::uint32_t length, const std::string& at) const {
    throw InputError(path_, 0, type,
                     "truncated: the file ends at byte " + std::to_string(offset_) + ", inside the chunk's " +
                         std::to_string(length) + " data bytes and 4-byte CRC" + at);
  }

  // Returns the colour type.
  int CheckHeader(const std::string& d, const std::string& at) const {
    const std::uint32_t width = BigEndian(d.data()), height = BigEndian(d.data() + 4);
    const int depth = static_cast<std::uint8_t>(d[8]), colour_type = static_cast<std::uint8_t>(d[9]);
    auto fail = [&](const std::string& problem) { throw InputError(path_, 0, "IHDR", problem + at); };
    if (width < 1 || height < 1 || width > kMaxChunkLength || height > kMaxChunkLength)
      fail("width " + std::to_string(width) + " and height " + std::to_string(height) + " must be in [1, 2^31 - 1]");
    if (!DepthAllowed(colour_type, depth))
      fail("bit depth " + std::to_string(depth) + " is not allowed for colour type " + std::to_string(colour_type));
    if (d[10] != 0 || d[11] != 0) fail("compression and filter method must be 0");
    if (d[12] != 0 && d[12] != 1) fail("interlace method must be 0 or 1");
    return colour_type;
  }

  const std::string path_;
  std::ifstream in_;
  std::uint64_t offset_ = 0;
};

}  // namespace

void CheckPngImage(const std::string& path) { PngWalker(path).Check(); }

}  // namespace rc
