// libFuzzer target: MRPT .gridmap files (plain; first byte odd: gzip name).
#include "fuzz/fuzz_properties.h"
#include "maps/mrpt/mrpt_map_loader.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::string path =
      rc::fuzz::WriteInputFile(data[0] % 2 ? "map.gridmap.gz" : "map.gridmap", rc::fuzz::AsText(data + 1, size - 1));
  rc::fuzz::ExpectParsedOrInputError([&] { rc::fuzz::RequireValidGrid(rc::LoadMrptGridmap(path).grid); });
  return 0;
}
