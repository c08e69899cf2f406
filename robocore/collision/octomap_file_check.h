#pragma once
// OctoMap's readers trust the file: the node stream of a .bt or .ot file is
// read by recursion with no depth limit, and a truncated stream leaves the
// child mask uninitialized, so a corrupt file overflows the stack or reads
// garbage (tests/fuzz found both). This check walks the same header and
// node stream first, bounded, and refuses what OctoMap would choke on.
#include <istream>
#include <string>

namespace rc {

// OctoMap's OcTree depth: the root is depth 0, leaves are at most 16 deep.
inline constexpr int kOctoMapTreeDepth = 16;

// Throws InputError naming the file and the problem unless `path` (.bt when
// `binary`, else .ot) has an OctoMap header with "id OcTree" (for .ot) and a
// positive resolution, then a node stream that is complete and no deeper
// than kOctoMapTreeDepth.
//
// OctoMap must then read the stream this check walked, not re-read the
// header: its header reader and this one can stop at different bytes of a
// malformed header (a repeated 'res', binary bytes in a keyword), and the
// stream after OctoMap's stop was never checked (tests/fuzz found it).
// LoadOctoMapFile builds the tree at `resolution_m` and reads its nodes
// from `node_stream_at`.
struct CheckedOctoMapFile {
  double resolution_m = 0.0;
  std::streamoff node_stream_at = 0;  // bytes from the start of the file
};
// Reads `in` (the file at `path`, opened in binary mode) from its start to
// the end of the node stream; `path` names the file in errors.
CheckedOctoMapFile CheckOctoMapFile(std::istream& in, const std::string& path, bool binary);

}  // namespace rc
