// libFuzzer target: RoWild one-line laser logs.
#include "fuzz/fuzz_properties.h"
#include "traces/rowild_log_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = rc::fuzz::WriteInputFile("rowild_log.txt", rc::fuzz::AsText(data, size));
  rc::fuzz::ExpectParsedOrInputError([&] { rc::fuzz::RequireValidTrace(rc::ReadRowildLog(path)); });
  return 0;
}
