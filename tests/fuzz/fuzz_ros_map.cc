// libFuzzer target: ROS map_server YAML plus its image. One input holds both:
// the YAML, a line "--- image ---", then the image bytes, written as map.pgm
// (the seed YAMLs name "image: map.pgm"; a mutated name is fuzzed too).
#include "fuzz/fuzz_properties.h"
#include "maps/ros_map_io.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::string_view yaml, image;
  rc::fuzz::SplitInput(rc::fuzz::AsText(data, size), "\n--- image ---\n", &yaml, &image);
  rc::fuzz::WriteInputFile("map.pgm", image);
  const std::string path = rc::fuzz::WriteInputFile("map.yaml", yaml);
  rc::fuzz::ExpectParsedOrInputError([&] { rc::fuzz::RequireValidGrid(rc::LoadRosMap(path).grid); });
  return 0;
}
