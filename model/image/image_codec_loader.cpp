#include <dlfcn.h>

#include <mutex>
#include <string>

#include "model/image/image_codec.h"
#include "model/image/image_io.h"
#include "model/io/module_loader.h"

namespace fovea::image {
namespace {

#ifndef FOVEA_IMAGE_CODEC_BUILTIN
const ImageCodecApi* loadCodec() {
  // Beside libfovea_model.so (this function's library), where it is built and installed.
  const LoadedModule m =
      openModuleBeside(reinterpret_cast<const void*>(&loadCodec), "FOVEA_IMAGE_CODEC", "libfovea_image_codec.so");
  if (m.handle == nullptr)
    throw ImageIoError("cannot load the image codec " + m.path + ": " + m.error +
                       (m.from_env ? " (from $FOVEA_IMAGE_CODEC)" : ""));
  using Entry = const ImageCodecApi* (*)();
  auto entry = reinterpret_cast<Entry>(::dlsym(m.handle, "fovea_image_codec_api"));
  const ImageCodecApi* api = entry != nullptr ? entry() : nullptr;
  if (api == nullptr || api->version != 1 || api->read == nullptr || api->write == nullptr)
    throw ImageIoError("the image codec " + m.path + " is not a version 1 fovea image codec");
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
