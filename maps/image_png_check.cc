#include "maps/image_png_check.h"

#include <cctype>
#include <cstdint>
#include <fstream>
#include <stdexcept>
#include <vector>

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

// Channels per pixel of each colour type (table 11.1).
int Channels(int colour_type) {
  switch (colour_type) {
    case 2: return 3;
    case 4: return 2;
    case 6: return 4;
    default: return 1;  // 0 (grey), 3 (palette index)
  }
}

// The IDAT chunks' zlib stream, inflated as the chunks are read and checked
// against what IHDR says the image holds: the stream inflates without a
// zlib error (its Adler-32 too), ends within the IDAT chunks, and yields
// exactly the image's filtered scanlines, each starting with a filter type
// of 0 to 4 (section 7.3; interlaced images scanline by scanline of each
// Adam7 pass, section 8.2). Nothing is kept but a 64 KB window.
class ImageData {
 public:
  ImageData() = default;
  ImageData(const ImageData&) = delete;
  ImageData& operator=(const ImageData&) = delete;
  ~ImageData() {
    if (started_) inflateEnd(&stream_);
  }

  // The image's scanlines from IHDR's fields. Returns false, starting
  // nothing, when their bytes would pass 2^62 (IHDR allows 2^31 - 1 by
  // 2^31 - 1 pixels of 8 bytes, about 2^68: no real file, and beyond the
  // counts kept here).
  bool Start(std::uint32_t width, std::uint32_t height, int depth, int colour_type, bool interlaced) {
    const std::uint64_t bits_per_pixel = static_cast<std::uint64_t>(depth) * Channels(colour_type);
    auto add_pass = [&](int number, std::uint32_t x0, std::uint32_t y0, std::uint32_t dx, std::uint32_t dy) {
      const std::uint64_t w = width > x0 ? (width - x0 + dx - 1) / dx : 0;
      const std::uint64_t h = height > y0 ? (height - y0 + dy - 1) / dy : 0;
      if (w == 0 || h == 0) return;  // an empty pass has no scanlines, not even filter bytes
      passes_.push_back({number, h, 1 + (w * bits_per_pixel + 7) / 8});
    };
    if (interlaced) {
      const std::uint32_t adam7[7][4] = {{0, 0, 8, 8}, {4, 0, 8, 8}, {0, 4, 4, 8}, {2, 0, 4, 4},
                                         {0, 2, 2, 4}, {1, 0, 2, 2}, {0, 1, 1, 2}};
      for (int pass = 0; pass < 7; ++pass) {
        const auto& p = adam7[pass];
        add_pass(pass + 1, p[0], p[1], p[2], p[3]);
      }
    } else {
      add_pass(0, 0, 0, 1, 1);
    }
    constexpr std::uint64_t kMostBytes = std::uint64_t{1} << 62;
    for (const Pass& p : passes_) {
      if (p.row_bytes > kMostBytes / p.rows) return false;
      expected_ += p.rows * p.row_bytes;  // each below 2^62, seven at most: no wrap
    }
    if (expected_ > kMostBytes) return false;
    if (inflateInit(&stream_) != Z_OK) throw std::runtime_error("zlib: cannot start an inflate stream");
    started_ = true;
    return true;
  }

  // One IDAT chunk's bytes; `fail` is called with what is wrong.
  template <class Fail>
  void Add(const char* data, std::size_t size, Fail fail) {
    stream_.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(data));
    stream_.avail_in = static_cast<uInt>(size);
    while (stream_.avail_in > 0) {
      if (ended_) fail("holds bytes after the end of the image data's zlib stream");
      const int status = Inflate(fail);
      if (status == Z_BUF_ERROR) break;  // no progress possible without more input
      if (status != Z_OK && status != Z_STREAM_END)
        fail(std::string("has image data that zlib cannot inflate (") + (stream_.msg ? stream_.msg : "error") + ")");
    }
  }

  // At IEND: the stream ended and gave every byte of the image.
  template <class Fail>
  void Finish(Fail fail) {
    // Output may remain buffered inside zlib with no input left.
    stream_.avail_in = 0;
    while (!ended_ && Inflate(fail) == Z_OK) {
    }
    if (!ended_)
      fail("the image data's zlib stream does not end within the IDAT chunks (" + std::to_string(inflated_) + " of " +
           std::to_string(expected_) + " image bytes inflated)");
    if (inflated_ != expected_)
      fail("the image data inflates to " + std::to_string(inflated_) + " bytes; IHDR's size needs " +
           std::to_string(expected_));
  }

 private:
  struct Pass {
    int number;  // Adam7's 1 to 7; 0 without interlacing
    std::uint64_t rows, row_bytes;
  };

  // One call of inflate into the window, whose output Scan checks; returns
  // zlib's status.
  template <class Fail>
  int Inflate(Fail fail) {
    stream_.next_out = window_;
    stream_.avail_out = sizeof window_;
    const int status = inflate(&stream_, Z_NO_FLUSH);
    Scan(sizeof window_ - stream_.avail_out, fail);
    ended_ = ended_ || status == Z_STREAM_END;
    return status;
  }

  // The window's first `size` inflated bytes: counts them and checks the
  // filter type at each scanline's start.
  template <class Fail>
  void Scan(std::size_t size, Fail fail) {
    const std::uint64_t end = inflated_ + size;
    if (end > expected_)
      fail("the image data inflates to more than the " + std::to_string(expected_) + " bytes IHDR's size needs");
    while (pass_ < passes_.size() && next_row_at_ < end) {
      const std::uint8_t filter = window_[next_row_at_ - inflated_];
      if (filter > 4)
        fail("scanline " + std::to_string(row_) +
             (passes_[pass_].number > 0 ? " of pass " + std::to_string(passes_[pass_].number) : "") +
             " has filter type " + std::to_string(filter) + " (0 to 4 exist): the image data is corrupt");
      next_row_at_ += passes_[pass_].row_bytes;
      if (++row_ == passes_[pass_].rows) {
        row_ = 0;
        ++pass_;
      }
    }
    inflated_ = end;
  }

  z_stream stream_{};
  bool started_ = false, ended_ = false;
  std::vector<Pass> passes_;
  std::size_t pass_ = 0;
  std::uint64_t row_ = 0, next_row_at_ = 0, inflated_ = 0, expected_ = 0;
  Bytef window_[65536];
};

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
        SkipData(crc, type, length, at, type == "IDAT" ? &image_data_ : nullptr);
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
        // The chunk's bytes went to image_data_ as they were read, but a
        // zlib error is reported only once the chunk's CRC is known sound.
        if (!idat_problem_.empty()) throw InputError(path_, 0, type, idat_problem_ + at);
      } else if (type == "IEND") {
        if (!in_idat_run && !idat_run_ended) throw InputError(path_, 0, type, "comes before any IDAT chunk" + at);
        image_data_.Finish([&](const std::string& problem) { throw InputError(path_, 0, "IDAT", problem); });
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

  // Reads past a chunk's data, adding it to the CRC and, for IDAT, to the
  // image data (whose first problem is kept in idat_problem_).
  void SkipData(Crc32& crc, const std::string& type, std::uint32_t length, const std::string& at,
                ImageData* image_data) {
    char block[65536];
    for (std::uint64_t left = length; left > 0;) {
      const std::uint64_t take = left < sizeof block ? left : sizeof block;
      const bool whole = Read(block, take);
      const auto got = static_cast<std::size_t>(in_.gcount());
      crc.Add(block, got);
      if (!whole) Truncated(type, length, at);
      if (image_data && idat_problem_.empty()) {
        try {
          image_data->Add(block, got, [](const std::string& problem) { throw ImageDataProblem{problem}; });
        } catch (const ImageDataProblem& p) {
          idat_problem_ = p.what;
        }
      }
      left -= take;
    }
  }

  [[noreturn]] void Truncated(const std::string& type, std::uint32_t length, const std::string& at) const {
    throw InputError(path_, 0, type,
                     "truncated: the file ends at byte " + std::to_string(offset_) + ", inside the chunk's " +
                         std::to_string(length) + " data bytes and 4-byte CRC" + at);
  }

  // Returns the colour type.
  int CheckHeader(const std::string& d, const std::string& at) {
    const std::uint32_t width = BigEndian(d.data()), height = BigEndian(d.data() + 4);
    const int depth = static_cast<std::uint8_t>(d[8]), colour_type = static_cast<std::uint8_t>(d[9]);
    auto fail = [&](const std::string& problem) { throw InputError(path_, 0, "IHDR", problem + at); };
    if (width < 1 || height < 1 || width > kMaxChunkLength || height > kMaxChunkLength)
      fail("width " + std::to_string(width) + " and height " + std::to_string(height) + " must be in [1, 2^31 - 1]");
    if (!DepthAllowed(colour_type, depth))
      fail("bit depth " + std::to_string(depth) + " is not allowed for colour type " + std::to_string(colour_type));
    if (d[10] != 0 || d[11] != 0) fail("compression and filter method must be 0");
    if (d[12] != 0 && d[12] != 1) fail("interlace method must be 0 or 1");
    if (!image_data_.Start(width, height, depth, colour_type, d[12] == 1))
      fail("width " + std::to_string(width) + " by height " + std::to_string(height) + " at bit depth " +
           std::to_string(depth) + " is more than 2^62 bytes of image data");
    return colour_type;
  }

  struct ImageDataProblem {
    std::string what;
  };

  const std::string path_;
  std::ifstream in_;
  std::uint64_t offset_ = 0;
  ImageData image_data_;
  std::string idat_problem_;  // the image data's first problem, reported with its chunk
};

}  // namespace

void CheckPngImage(const std::string& path) { PngWalker(path).Check(); }

}  // namespace rc
