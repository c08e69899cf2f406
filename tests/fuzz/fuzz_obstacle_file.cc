// libFuzzer target: MoveBot obstacle files (locobot_obs.txt's format).
#include <sstream>

#include "fuzz/fuzz_input_file.h"
#include "workloads/movebot/obstacle_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::istringstream in{std::string(rc::fuzz::AsText(data, size))};
  rc::fuzz::ExpectParsedOrInputError([&] { rc::ReadObstacleFile(in, "obstacles.txt"); });
  return 0;
}
