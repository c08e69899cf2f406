#pragma once
// JPEG map images checked before OpenCV decodes them. OpenCV 4.6 reads a
// JPEG through libjpeg(-turbo) and leaves libjpeg's warnings to its default
// handler, so a truncated or corrupt file prints "Premature end of JPEG
// file" or "Corrupt JPEG data: ..." on stderr and still decodes, the rest
// filled grey; and libjpeg's errors are silent, leaving our error no more to
// say than "cannot decode". So this decodes the file once first, with the
// same libjpeg, under an error manager that prints nothing and stops at
// the first error or warning; OpenCV then only sees files libjpeg reads
// without a word.
//
// Checked: everything libjpeg refuses (an unsupported or broken header, a
// missing table, a size over its 65500-pixel limit) or warns about (data
// cut short, a bad Huffman or arithmetic code, a restart marker out of
// order, bytes between markers, an unknown JFIF version or Adobe colour
// transform, an inconsistent progression), in every scan, Huffman- or
// arithmetic-coded; and the image size against the map size limits
// (grid_size_limits.h), before libjpeg allocates anything for it. Bytes
// after EOI are ignored, as libjpeg ignores them.
// Not checked: a value that a sound code stream may hold (a changed
// coefficient, quantization or Huffman table value): such a file decodes
// without a message but may not show what was meant; and what libjpeg
// passes over silently (a progressive file that ends before its last
// refinement scan, a quantization value of 0, a few stray bytes after a
// scan that its bit buffer takes in). APPn and COM contents are skipped;
// OpenCV's EXIF reader is silent.
// Cost: the file is decoded twice, here and by OpenCV. This decode runs at
// 1/8 scale in grey (every coefficient is still entropy-decoded, which is
// most of the work; only the inverse DCT and colour conversion shrink) and
// costs 80-90% of OpenCV's: measured with libjpeg-turbo 2.1.5, 1.5 ms per
// megapixel for a map-like grey file (6 progressive), 8 for colour noise
// (28 progressive). A JPEG map takes about twice as long to load.
#include <string>

namespace rc {

// Throws InputError(path, 0, field, problem) when libjpeg refuses or warns
// about the file. Field: the stage libjpeg was in:
// - "header": the markers up to the first scan header (SOI, SOFn, DHT,
//   DQT, DRI, APPn, SOS), and the map size limits;
// - "scan data": the scans' entropy-coded data and the markers between
//   scans (a progressive or multi-scan file is read to its EOI here);
// - "EOI": what follows the last scan of a one-scan file, up to EOI.
// Problem: libjpeg's own message, after "truncated: " when the file ends
// too soon ("Premature end of JPEG file", "Empty input file"), then the
// byte libjpeg was reading from: the start of the marker segment item or
// MCU it was decoding (its input advances in those steps), so the defect
// lies at or after it; extraneous bytes lie just before it, the marker
// they precede.
void CheckJpegImage(const std::string& path);

}  // namespace rc
