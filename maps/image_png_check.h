#pragma once
// PNG map images checked before OpenCV decodes them. OpenCV 4.6 reads a PNG
// through libpng with libpng's default error and warning handlers, so a
// truncated or corrupt file prints "libpng error: Read Error" (or "IDAT: CRC
// error", "pHYs: CRC error", ...) on stderr before our error, which then can
// say no more than "cannot decode". This walks the file's chunk structure
// first, so that such a file is refused with the file, the chunk and what is
// wrong, and libpng only sees files whose structure is sound.
//
// Checked (the PNG specification, www.w3.org/TR/png/, sections 5 and 11):
// - the 8-byte signature;
// - every chunk: a length of at most 2^31 - 1 that the file holds, a type of
//   four ASCII letters, and a CRC-32 over type and data that matches, for
//   ancillary chunks too (libpng warns about those on stderr and reads on);
// - IHDR first, 13 bytes, width and height >= 1, a bit depth allowed for
//   its colour type, compression and filter method 0, interlace 0 or 1;
// - PLTE before the first IDAT for a palette image; IDAT chunks in one run;
//   no unknown critical chunk (libpng refuses one);
// - IEND, empty, after at least one IDAT. Bytes after IEND are ignored, as
//   libpng does.
// - the IDAT chunks' image data (sections 7.3, 8.2 and 10): one zlib stream
//   that inflates without error (its Adler-32 too) and ends within them,
//   giving exactly the filtered scanlines IHDR's size, depth, colour type
//   and interlacing need, each starting with a filter type of 0 to 4. Sound
//   chunks around a crafted stream would otherwise reach libpng.
// Not checked: what the scanlines hold (every byte value is a pixel) and
// the ancillary chunks' contents (libpng reads only those it knows and
// ignores the rest). The data is inflated twice, here and by libpng: a few
// milliseconds per megapixel, once per map.
#include <string>

namespace rc {

// Throws InputError(path, 0, field, problem) for the first defect found:
// field is "signature", a chunk type ("IHDR", "PLTE", "IDAT", "IEND", or the
// type read), or "chunk N" (1-based) when the type itself is unreadable;
// the problem gives the byte offset of the chunk.
void CheckPngImage(const std::string& path);

}  // namespace rc
