// libFuzzer target: the RoboCore micro-op assembly (robocore/programs/*.asm).
#include "fuzz/fuzz_input_file.h"
#include "robocore/micro_program.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  rc::fuzz::ExpectParsedOrInputError([&] { rc::ParseMicroProgram(rc::fuzz::AsText(data, size), "program.asm"); });
  return 0;
}
