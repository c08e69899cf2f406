#pragma once
// Netpbm map images (PBM, PGM, PPM: P1-P6) checked before OpenCV decodes
// them. OpenCV 4.6's PxM decoder is the wrong place to find a bad file:
// - it clamps a plain (P2, P3) sample above maxval to maxval, so a P2 with
//   maxval 100 and samples of 254 reads as all white (free);
// - it copies binary (P5, P6) samples unscaled when maxval < 255, while it
//   scales plain ones by 255 / maxval, as map_server does for both;
// - a bad header (width 0, maxval 0) gives an empty image with no reason,
//   and a truncated raster or a sign in the header prints its own message
//   on stderr before the empty image.
// So every PNM map image is checked here first, and only one that OpenCV
// reads as written reaches it; the error names the file, the line and the
// field (magic, width, height, maxval, pixels, or the pixel).
//
// Accepted (the Netpbm format pages, e.g. netpbm.sourceforge.net/doc/pgm.html):
// - 'P' and a type digit 1-6; then width, height and (not for P1 and P4)
//   maxval as decimal numbers, separated by white space and '#' comments
//   (from a '#' at the start of a token to the end of the line);
// - width and height >= 1 and within grid_size_limits.h;
// - maxval 1..255; 256..65535 is valid Netpbm but means 16-bit samples,
//   which the map loaders refuse as they do 16-bit PNGs; binary P5 and P6
//   only with maxval 255 (see the second point above);
// - binary: one white-space character after the header, then exactly the
//   raster: height rows of ceil(width / 8) (P4), width (P5) or 3 width (P6)
//   bytes. Bytes after it are refused: a second image in the file, or a
//   header saved with CR LF line ends, whose LF would shift every pixel;
// - plain: width x height samples (x 3 for P3), each at most maxval, then
//   only white space and comments. P1 samples are the digits 0 and 1, with
//   or without white space between them.
#include <string>

namespace rc {

// Throws InputError(path, line, field, problem): line is the 1-based line of
// a header number or plain sample, 0 for a binary raster's size; field is
// "magic", "width", "height", "width x height", "maxval", "pixels" (too few
// or too many), or "pixel (row R, column C)" (image row 0 at the top) for a
// sample that is not a number or exceeds maxval.
void CheckPnmImage(const std::string& path);

}  // namespace rc
