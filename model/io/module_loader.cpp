#include "model/io/module_loader.h"

#include <dlfcn.h>

#include <cstdlib>
#include <filesystem>

namespace fovea {

LoadedModule openModuleBeside(const void* anchor, const char* env_var, const std::string& file_name) {
  LoadedModule m;
  const char* given = std::getenv(env_var);
  m.from_env = given != nullptr && *given != '\0';
  if (m.from_env) {
    m.path = given;
  } else {
    Dl_info info{};
    std::filesystem::path folder;
    if (::dladdr(anchor, &info) != 0 && info.dli_fname != nullptr)
      folder = std::filesystem::path(info.dli_fname).parent_path();
    m.path = (folder / file_name).string();
  }
  m.handle = ::dlopen(m.path.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (m.handle == nullptr) {
    const char* why = ::dlerror();
    m.error = why != nullptr ? why : "unknown error";
  }
  return m;
}

}  // namespace fovea
