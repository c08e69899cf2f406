// libFuzzer target: MRPT .rawlog traces (first byte odd: gzip name).
#include "fuzz/fuzz_properties.h"
#include "traces/mrpt/mrpt_rawlog_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::string path =
      rc::fuzz::WriteInputFile(data[0] % 2 ? "log.rawlog.gz" : "log.rawlog", rc::fuzz::AsText(data + 1, size - 1));
  rc::fuzz::ExpectParsedOrInputError([&] { rc::fuzz::RequireValidTrace(rc::ReadMrptRawlog(path)); });
  return 0;
}
