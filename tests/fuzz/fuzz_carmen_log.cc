// libFuzzer target: CARMEN .clf logs, and format detection on the same bytes.
#include "fuzz/fuzz_properties.h"
#include "traces/trace_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = rc::fuzz::WriteInputFile("log.clf", rc::fuzz::AsText(data, size));
  rc::fuzz::ExpectParsedOrInputError([&] { rc::fuzz::RequireValidTrace(rc::ReadCarmenLog(path)); });
  rc::fuzz::ExpectParsedOrInputError([&] { rc::fuzz::RequireValidTrace(rc::ReadTrace(path, {})); });
  return 0;
}
