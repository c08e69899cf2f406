// libFuzzer target: axis-aligned box CSV scenes (collide --boxes).
#include <sstream>

#include "fuzz/fuzz_input_file.h"
#include "robocore/collision/box_csv.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::istringstream in{std::string(rc::fuzz::AsText(data, size))};
  rc::fuzz::ExpectParsedOrInputError([&] { rc::ReadBoxCsv(in, "scene.csv"); });
  return 0;
}
