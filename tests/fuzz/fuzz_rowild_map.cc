// libFuzzer target: RoWild DeliBot .dat maps.
#include "fuzz/fuzz_properties.h"
#include "maps/rowild_map_loader.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = rc::fuzz::WriteInputFile("map.dat", rc::fuzz::AsText(data, size));
  rc::fuzz::ExpectParsedOrInputError([&] { rc::fuzz::RequireValidGrid(rc::LoadRowildMap(path)); });
  return 0;
}
