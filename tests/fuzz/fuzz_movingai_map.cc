// libFuzzer target: MovingAI octile .map files.
#include "fuzz/fuzz_properties.h"
#include "maps/movingai_map_loader.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = rc::fuzz::WriteInputFile("grid.map", rc::fuzz::AsText(data, size));
  rc::fuzz::ExpectParsedOrInputError([&] { rc::fuzz::RequireValidGrid(rc::LoadMovingAiMap(path)); });
  return 0;
}
