// libFuzzer target: OctoMap .bt (binary) and .ot (full) files (first byte
// picks which), built into the collision scene's tree.
#include "fuzz/fuzz_input_file.h"
#include "robocore/collision/octree_from_octomap.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::string path =
      rc::fuzz::WriteInputFile(data[0] % 2 ? "scene.ot" : "scene.bt", rc::fuzz::AsText(data + 1, size - 1));
  rc::fuzz::ExpectParsedOrInputError([&] { rc::LoadOctoMapFile(path); });
  return 0;
}
