// libFuzzer target: plain image maps. The first byte picks the extension
// (OpenCV decodes by content; the loader's checks do not depend on it).
#include "fuzz/fuzz_properties.h"
#include "maps/image_map_loader.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  static const char* const kNames[] = {"map.pgm", "map.png", "map.jpg"};
  const std::string path = rc::fuzz::WriteInputFile(kNames[data[0] % 3], rc::fuzz::AsText(data + 1, size - 1));
  rc::ImageMapOptions options;
  options.resolution_m = 0.05;
  rc::fuzz::ExpectParsedOrInputError([&] { rc::fuzz::RequireValidGrid(rc::LoadImageMap(path, options)); });
  return 0;
}
