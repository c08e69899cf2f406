// libFuzzer target: CMU robotdata .log traces.
#include "fuzz/fuzz_properties.h"
#include "traces/cmu_log_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = rc::fuzz::WriteInputFile("robotdata.log", rc::fuzz::AsText(data, size));
  rc::fuzz::ExpectParsedOrInputError([&] { rc::fuzz::RequireValidTrace(rc::ReadCmuLog(path)); });
  return 0;
}
