#pragma once
// A module beside the library that loads it (the image codec, the V4L2 camera: loaded on first
// use, issue 25): dlopen'ed with RTLD_NOW | RTLD_LOCAL and never closed.
#include <string>

namespace fovea {

struct LoadedModule {
  void* handle = nullptr;  // null when it could not be loaded
  std::string path;        // the file tried
  std::string error;       // the loader's reason when handle is null
  bool from_env = false;   // path came from the environment variable
};

// $env_var when set and not empty, else `file_name` in the folder of the shared object that
// holds `anchor` (a function of the loading library).
LoadedModule openModuleBeside(const void* anchor, const char* env_var, const std::string& file_name);

}  // namespace fovea
