#pragma once
// Reading an MRPT serialization archive (.rawlog, .gridmap, .simplemap,
// plain or gzip-compressed) into memory, so a reader can tell a clean end of
// file from a truncated object: the archive ends cleanly only at its last
// byte. Kept free of MRPT headers so callers stay light.
#include <string>
#include <vector>

namespace rc {

// The uncompressed bytes of the file. Throws InputError naming the file when
// it cannot be opened, is empty, or its gzip stream is corrupt. `what` names
// the kind of file in messages ("rawlog", "gridmap").
std::vector<unsigned char> ReadArchiveBytes(const std::string& path, const std::string& what);

// MRPT's exception texts nest exceptions and call traces over many lines;
// returns the innermost "Message:" text, the one a user needs.
std::string MrptMessage(const std::string& text);

}  // namespace rc
