#include "robocore/collision/octomap_file_check.h"

#include <cmath>
#include <cstdint>

#include "common/input_error.h"

namespace rc {
namespace {

class NodeStreamCheck {
 public:
  NodeStreamCheck(std::istream& in, const std::string& path, bool binary) : in_(in), path_(path), binary_(binary) {}

  // One node and its subtree, as OccupancyOcTreeBase::readBinaryNode (.bt:
  // two bytes, two bits per child, 11 = an inner child read next) or
  // OcTreeBaseImpl::readNodesRecurs (.ot: the node's float value, then one
  // byte, one bit per child, every child read next) consume them.
  void Node(int depth) {
    unsigned children = 0;
    if (binary_) {
      children = Byte() | (Byte() << 8);
    } else {
      for (std::size_t i = 0; i < sizeof(float); ++i) Byte();  // OcTreeNode's log-odds value
      children = Byte();
    }
    for (unsigned i = 0; i < 8; ++i) {
      const bool read_next = binary_ ? ((children >> (2 * i)) & 3u) == 3u : ((children >> i) & 1u) == 1u;
      if (!read_next) continue;
      if (depth + 1 > kOctoMapTreeDepth)
        throw InputError(path_, 0, "data",
                         "the node stream goes deeper than an OcTree's " + std::to_string(kOctoMapTreeDepth) +
                             " levels at byte " + std::to_string(static_cast<long long>(in_.tellg())) +
                             " (corrupt file)");
      Node(depth + 1);
    }
  }

 private:
  unsigned Byte() {
    const int c = in_.get();
    if (c == std::char_traits<char>::eof())
      throw InputError(path_, 0, "data", "the node stream ends in the middle of the tree (truncated file)");
    return static_cast<unsigned>(static_cast<unsigned char>(c));
  }

  std::istream& in_;
  const std::string& path_;
  bool binary_;
};

}  // namespace

CheckedOctoMapFile CheckOctoMapFile(std::istream& in, const std::string& path, bool binary) {
  std::string first;
  std::getline(in, first);
  const std::string expected = binary ? "# Octomap OcTree binary file" : "# Octomap OcTree file";
  if (first.compare(0, expected.size(), expected) != 0)
    throw InputError(path, 1, "header", "the first line is not '" + expected + "'");
  // The header's keywords, as AbstractOcTree::readHeader reads them.
  std::string id = binary ? "OcTree" : "", token;
  double resolution = 0.0;
  bool data = false;
  while (!data && in >> token) {
    if (token == "data") {
      data = true;
    } else if (token == "id") {
      in >> id;
    } else if (token == "res") {
      if (!(in >> resolution)) throw InputError(path, 0, "res", "not a number");
      continue;
    } else if (token != "size") {
      // A comment or an unknown keyword: OctoMap skips the rest of the line.
    } else {
      std::string size;
      in >> size;
      continue;
    }
    if (!data) in.ignore(1 << 20, '\n');
  }
  if (!data) throw InputError(path, 0, "data", "the header never reaches its 'data' line");
  in.ignore(1 << 20, '\n');
  if (id != "OcTree") throw InputError(path, 0, "id", "the file holds a '" + id + "', not an OcTree");
  if (!(resolution > 0.0) || !std::isfinite(resolution))
    throw InputError(path, 0, "res", "the resolution must be a positive number of metres");
  // OctoMap reads a root node after the 'data' line whatever follows it: at
  // the end of the file its reads fail and leave the child bits it recurses
  // on undefined, so a file without a node stream is refused here.
  if (in.peek() == std::char_traits<char>::eof())
    throw InputError(path, 0, "data", "no node stream follows the 'data' line (truncated file)");
  const std::streamoff node_stream_at = in.tellg();
  NodeStreamCheck(in, path, binary).Node(0);
  return {resolution, node_stream_at};
}

}  // namespace rc
