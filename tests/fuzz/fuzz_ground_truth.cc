// libFuzzer target: ground-truth pose files (t x y theta per line).
#include "fuzz/fuzz_properties.h"
#include "traces/ground_truth_io.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = rc::fuzz::WriteInputFile("truth.txt", rc::fuzz::AsText(data, size));
  rc::fuzz::ExpectParsedOrInputError([&] {
    for (const auto& p : rc::ReadGroundTruth(path).poses)
      rc::fuzz::Require(rc::fuzz::Finite(p.pose) && std::isfinite(p.time_s), "a pose is not finite");
  });
  return 0;
}
