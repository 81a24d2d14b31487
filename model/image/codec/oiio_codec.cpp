// libfovea_image_codec: model/image/image_codec.h's functions over OpenImageIO.

#include <algorithm>

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include "model/image/image_codec.h"

namespace fovea::image {
namespace {

OIIO::TypeDesc typeOf(SampleType t) {
  switch (t) {
    case SampleType::U8:
      return OIIO::TypeDesc::UINT8;
    case SampleType::U16:
      return OIIO::TypeDesc::UINT16;
    case SampleType::F32:
      break;
  }
  return OIIO::TypeDesc::FLOAT;
}

std::string read(const std::string& path, const std::function<std::string(const ImageHeader&)>& accept,
                 int max_channels, bool decode, ImageHeader& header, std::vector<float>& pixels) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) return "unsupported or unreadable image: " + OIIO::geterror();
  const OIIO::ImageSpec& spec = in->spec();
  header.width = spec.width;
  header.height = spec.height;
  header.depth = spec.depth;
  header.channels = spec.nchannels;
  header.is_float = spec.format.basetype == OIIO::TypeDesc::FLOAT || spec.format.basetype == OIIO::TypeDesc::HALF ||
                    spec.format.basetype == OIIO::TypeDesc::DOUBLE;
  if (std::string problem = accept(header); !problem.empty()) return problem;
  if (!decode) {
    in->close();
    return {};
  }
  const int nc = std::min(spec.nchannels, max_channels);
  pixels.assign(static_cast<std::size_t>(spec.width) * spec.height * nc, 0.0f);
  if (!in->read_image(0, 0, 0, nc, OIIO::TypeDesc::FLOAT, pixels.data()))
    return "cannot decode the image: " + in->geterror();
  if (in->has_error()) return "cannot decode the image: " + in->geterror();
  in->close();
  return {};
}

std::string write(const std::string& path, int width, int height, int channels, SampleType file_type,
                  SampleType data_type, const void* data, std::vector<unsigned char>& bytes, bool& in_memory) {
  auto out = OIIO::ImageOutput::create(path);
  if (!out) return "no image format for this file name: " + OIIO::geterror();
  OIIO::Filesystem::IOVecOutput memory(bytes);
  in_memory = out->supports("ioproxy") && out->set_ioproxy(&memory);
  const OIIO::ImageSpec spec(width, height, channels, typeOf(file_type));
  if (!out->open(path, spec)) return "cannot open for writing: " + out->geterror();
  if (!out->write_image(typeOf(data_type), data)) return "cannot write the image: " + out->geterror();
  if (!out->close()) return "cannot finish the file: " + out->geterror();
  return {};
}

}  // namespace
}  // namespace fovea::image

extern "C" const fovea::image::ImageCodecApi* fovea_image_codec_api() {
  static const fovea::image::ImageCodecApi api{1, &fovea::image::read, &fovea::image::write};
  return &api;
}
