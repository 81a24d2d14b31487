#include <dlfcn.h>

#include <cstdlib>
#include <filesystem>
#include <mutex>
#include <string>

#include "model/image/image_codec.h"
#include "model/image/image_io.h"

namespace fovea::image {
namespace {

#ifndef FOVEA_IMAGE_CODEC_BUILTIN
// The folder of the shared object this function is in (libfovea_model.so): the codec module is
// built and installed beside it.
std::filesystem::path modelLibraryFolder() {
  Dl_info info{};
  if (::dladdr(reinterpret_cast<void*>(&modelLibraryFolder), &info) == 0 || info.dli_fname == nullptr) return {};
  return std::filesystem::path(info.dli_fname).parent_path();
}

const ImageCodecApi* loadCodec() {
  const char* given = std::getenv("FOVEA_IMAGE_CODEC");
  const std::string path = given != nullptr && *given != '\0'
                               ? std::string(given)
                               : (modelLibraryFolder() / "libfovea_image_codec.so").string();
  // Never closed: the process keeps the codec once it has read or written an image.
  void* handle = ::dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (handle == nullptr) {
    const char* why = ::dlerror();
    throw ImageIoError("cannot load the image codec " + path + ": " + (why != nullptr ? why : "unknown error") +
                       (given != nullptr ? " (from $FOVEA_IMAGE_CODEC)" : ""));
  }
  using Entry = const ImageCodecApi* (*)();
  auto entry = reinterpret_cast<Entry>(::dlsym(handle, "fovea_image_codec_api"));
  const ImageCodecApi* api = entry != nullptr ? entry() : nullptr;
  if (api == nullptr || api->version != 1 || api->read == nullptr || api->write == nullptr)
    throw ImageIoError("the image codec " + path + " is not a version 1 fovea image codec");
  return api;
}
#endif

}  // namespace

const ImageCodecApi& imageCodec() {
#ifdef FOVEA_IMAGE_CODEC_BUILTIN
  return *fovea_image_codec_api();
#else
  // Loaded once; a failure is not cached, so its message reaches every caller.
  static std::mutex mutex;
  static const ImageCodecApi* api = nullptr;
  std::lock_guard lock(mutex);
  if (api == nullptr) api = loadCodec();
  return *api;
#endif
}

}  // namespace fovea::image
