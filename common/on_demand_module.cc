#include "common/on_demand_module.h"

#include <dlfcn.h>

#include <filesystem>
#include <map>
#include <mutex>
#include <stdexcept>
#include <system_error>
#include <vector>

namespace rc {
namespace {

std::vector<std::filesystem::path> SearchDirectories() {
  std::vector<std::filesystem::path> dirs;
  std::error_code error;
  const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", error);
  if (!error) dirs.push_back(self.parent_path());
#ifdef RC_MODULE_DIR
  dirs.emplace_back(RC_MODULE_DIR);
#endif
  return dirs;
}

}  // namespace

void* OpenModuleEntry(const std::string& module, const std::string& symbol) {
  static std::mutex mutex;
  static std::map<std::string, void*> opened;  // module name -> dlopen handle
  const std::lock_guard<std::mutex> lock(mutex);
  void*& handle = opened[module];
  std::string tried;
  if (!handle) {
    const std::string file = "librcbench_" + module + ".so";
    for (const std::filesystem::path& dir : SearchDirectories()) {
      const std::string path = (dir / file).string();
      if (!std::filesystem::exists(path)) {
        tried += "\n  " + path + ": no such file";
        continue;
      }
      // RTLD_LOCAL: a module's symbols stay out of the global scope, so they
      // never take the place of rcbench's (the MRPT module's adapters have
      // the names of rcbench's forwarders to them).
      handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
      if (handle) break;
      tried += "\n  " + path + ": " + dlerror();
    }
  }
  if (!handle)
    throw std::runtime_error("cannot open rcbench's " + module + " module (" + "librcbench_" + module +
                             ".so, built beside the rcbench binary); tried:" + tried);
  dlerror();
  void* entry = dlsym(handle, symbol.c_str());
  if (!entry) throw std::runtime_error("rcbench's " + module + " module has no entry '" + symbol + "'");
  return entry;
}

}  // namespace rc
