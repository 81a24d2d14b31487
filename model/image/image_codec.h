#pragma once
// The image file codec behind model/image/image_io.h. OpenImageIO and the ~240 libraries it
// loads (GDAL, OpenVDB, DCMTK, Poppler, ...) cost every process that links them ~0.2 CPU-s of
// dynamic linking at start-up, whether it touches an image file or not; so the codec is a
// module of its own (libfovea_image_codec.so beside libfovea_model.so), loaded on the first
// image read or write (issue 25: the test suite starts about a thousand processes, and
// `fovea-cli --help` took 0.24 CPU-s). A static build (FOVEA_SHARED_LIBS=OFF) compiles it in.
//
// The module's functions return a problem as text (empty: done) and never throw; image_io.cpp
// turns a problem into ImageIoError "PATH: problem".

#include <functional>
#include <string>
#include <vector>

namespace fovea::image {

struct ImageHeader {
  int width = 0, height = 0, depth = 1, channels = 0;
  bool is_float = false;  // float, half or double samples (linear light by convention)
};

enum class SampleType { U8, U16, F32 };

struct ImageCodecApi {
  int version = 1;
  // Opens `path`, fills `header`, asks `accept` (a problem, or empty to go on) and, when `decode`,
  // decodes the first min(channels, max_channels) channels as float into `pixels` (row-major,
  // interleaved; integer samples scaled to [0, 1]).
  std::string (*read)(const std::string& path, const std::function<std::string(const ImageHeader&)>& accept,
                      int max_channels, bool decode, ImageHeader& header, std::vector<float>& pixels) = nullptr;
  // Encodes width x height x channels samples of `data_type` as `file_type` in the format the
  // file name says: into `bytes` when the format can write to memory (`in_memory` true), else
  // straight to `path`.
  std::string (*write)(const std::string& path, int width, int height, int channels, SampleType file_type,
                       SampleType data_type, const void* data, std::vector<unsigned char>& bytes,
                       bool& in_memory) = nullptr;
};

// The codec, loaded once (thread-safe) from $FOVEA_IMAGE_CODEC when set, else from the folder
// of the library holding the model. Throws ImageIoError naming the module path and the loader's
// reason when it cannot be loaded.
const ImageCodecApi& imageCodec();

}  // namespace fovea::image

// The module's one entry point.
extern "C" const fovea::image::ImageCodecApi*
fovea_image_codec_api();  // NOLINT(readability-identifier-naming): C ABI name
