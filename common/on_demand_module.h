#pragma once
// Shared libraries that rcbench opens only when a run needs them.
//
// Some Debian libraries cost more to load than a short run takes: MRPT
// brings about 290 shared libraries, each bound at load, which is 0.2 s of
// CPU and 50 MB before main() on every rcbench process. Code that needs
// them is built into a module (a CMake MODULE library, librcbench_NAME.so,
// placed beside the rcbench binary) and opened on first use, so a run that
// never reads an MRPT file never loads MRPT.
//
// Contract: OpenModuleEntry("mrpt", "rc_mrpt_module_api") opens the module
// once per process (later calls return the same entry) and returns the
// address of its extern "C" symbol. The module is looked for in the
// directory of the running executable, then in the directory the build put
// it in (RC_MODULE_DIR, so test binaries elsewhere in the build tree find
// it). A module that cannot be opened, or lacks the symbol, throws
// std::runtime_error naming every path tried and the loader's message.
#include <stdexcept>
#include <string>

namespace rc {

void* OpenModuleEntry(const std::string& module, const std::string& symbol);

// A module's table of entry points: its extern "C" `symbol` is a function
// returning `const Api*`, and Api's first member, `size`, holds
// sizeof(Api) as the module was built (a module from another build throws).
template <typename Api>
const Api& OpenModuleApi(const std::string& module, const std::string& symbol) {
  using Entry = const Api* (*)();
  const Api* api = reinterpret_cast<Entry>(OpenModuleEntry(module, symbol))();
  if (api->size != sizeof(Api))
    throw std::runtime_error("rcbench's " + module + " module comes from another build (rebuild it with the binary)");
  return *api;
}

}  // namespace rc
