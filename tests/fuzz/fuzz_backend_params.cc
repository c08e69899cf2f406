// libFuzzer target: --backend-params JSON, through the public parser only.
#include "backends/backend_params.h"
#include "fuzz/fuzz_input_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  rc::fuzz::ExpectParsedOrInputError(
      [&] { rc::ParseBackendParameters(std::string(rc::fuzz::AsText(data, size)), "params.json"); });
  return 0;
}
