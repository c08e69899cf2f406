// libFuzzer target: robot-link OBB CSV (mpnet_master_obb.csv's format).
#include <sstream>

#include "fuzz/fuzz_input_file.h"
#include "robocore/collision/box_csv.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::istringstream in{std::string(rc::fuzz::AsText(data, size))};
  rc::fuzz::ExpectParsedOrInputError([&] { rc::ReadObbCsv(in, "boxes.csv"); });
  return 0;
}
