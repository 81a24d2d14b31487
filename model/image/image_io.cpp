#include "model/image/image_io.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include "model/color/srgb.h"
#include "model/io/output_file.h"

namespace fovea::image {

namespace {

// The file itself: regular, bounded, and (a JPEG) complete.
void checkFile(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
  if (fd < 0) throw ImageIoError(path + ": " + (errno == ENOENT ? std::string("no such file") : std::strerror(errno)));
  struct stat st {};
  const bool stat_ok = ::fstat(fd, &st) == 0;
  std::string problem;
  if (!stat_ok)
    problem = std::strerror(errno);
  else if (S_ISDIR(st.st_mode))
    problem = "is a directory, not a file";
  else if (!S_ISREG(st.st_mode))
    problem = S_ISFIFO(st.st_mode) ? "is a FIFO, not a regular file" : "is a device or a socket, not a regular file";
  else if (static_cast<std::uint64_t>(st.st_size) > kMaxImageFileBytes)
    problem = "too large: " + std::to_string(st.st_size) + " bytes (limit " + std::to_string(kMaxImageFileBytes) + ")";
  if (problem.empty()) {
    // JPEG (starts FF D8): the last marker must be EOI (FF D9), trailing zero padding allowed.
    unsigned char head[2] = {0, 0};
    if (::pread(fd, head, 2, 0) == 2 && head[0] == 0xFF && head[1] == 0xD8) {
      unsigned char tail[4096];
      const off_t n = std::min<off_t>(st.st_size, static_cast<off_t>(sizeof tail));
      const ssize_t got = ::pread(fd, tail, static_cast<std::size_t>(n), st.st_size - n);
      ssize_t end = got;
      while (end > 0 && tail[end - 1] == 0) --end;
      if (got <= 0 || end < 2 || tail[end - 2] != 0xFF || tail[end - 1] != 0xD9)
        problem = "truncated JPEG (no end-of-image marker)";
    }
  }
  ::close(fd);
  if (!problem.empty()) throw ImageIoError(path + ": " + problem);
}

// The header's pixel count, before any pixel is decoded.
void checkSpec(const std::string& path, const OIIO::ImageSpec& spec) {
  const double pixels = static_cast<double>(spec.width) * spec.height * std::max(1, spec.depth);
  if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0) throw ImageIoError(path + ": image has no pixels");
  if (pixels > kMaxImagePixels)
    throw ImageIoError(path + ": the header declares " + std::to_string(spec.width) + " x " +
                       std::to_string(spec.height) + " pixels, more than the limit of 50 Mpixel");
}

}  // namespace

void checkImageFile(const std::string& path) {
  checkFile(path);
  auto in = OIIO::ImageInput::open(path);
  if (!in) throw ImageIoError(path + ": unsupported or unreadable image: " + OIIO::geterror());
  checkSpec(path, in->spec());
  in->close();
}

cv::Mat readLinearRgb(const std::string& path) {
  checkFile(path);
  auto in = OIIO::ImageInput::open(path);
  if (!in) throw ImageIoError(path + ": unsupported or unreadable image: " + OIIO::geterror());
  const OIIO::ImageSpec& spec = in->spec();
  checkSpec(path, spec);
  const int w = spec.width, h = spec.height;
  const int nc = std::min(spec.nchannels, 3);  // RGB or grey: alpha and extra channels are not read
  std::vector<float> pixels(static_cast<std::size_t>(w) * h * nc);
  if (!in->read_image(0, 0, 0, nc, OIIO::TypeDesc::FLOAT, pixels.data()))
    throw ImageIoError(path + ": cannot decode the image: " + in->geterror());
  if (in->has_error()) throw ImageIoError(path + ": cannot decode the image: " + in->geterror());
  const bool isFloat = spec.format.basetype == OIIO::TypeDesc::FLOAT || spec.format.basetype == OIIO::TypeDesc::HALF ||
                       spec.format.basetype == OIIO::TypeDesc::DOUBLE;
  in->close();
  // Lookup table for the sRGB decode of integer images.
  cv::Mat out(h, w, CV_32FC3);
  for (int y = 0; y < h; ++y) {
    auto* row = out.ptr<cv::Vec3f>(y);
    for (int x = 0; x < w; ++x) {
      const float* p = &pixels[(static_cast<std::size_t>(y) * w + x) * nc];
      cv::Vec3f v = nc >= 3 ? cv::Vec3f(p[0], p[1], p[2]) : cv::Vec3f(p[0], p[0], p[0]);
      if (!isFloat)
        for (int c = 0; c < 3; ++c) v[c] = color::srgbToLinear(v[c]);
      for (int c = 0; c < 3; ++c)
        if (!std::isfinite(v[c])) throw ImageIoError(path + ": image holds non-finite pixel values");
      row[x] = v;
    }
  }
  return out;
}

void writeLinearRgb(const std::string& path, const cv::Mat& img, bool sixteen_bit) {
  if (img.type() != CV_32FC3) throw ImageIoError(path + ": internal: expected a float RGB image");
  if (const auto why = outputPathProblem(path)) throw ImageIoError(path + ": " + *why);
  auto out = OIIO::ImageOutput::create(path);
  if (!out) throw ImageIoError(path + ": no image format for this file name: " + OIIO::geterror());
  // Encoded in memory, then written by the one writer (atomic, checked, fsync'ed: a failed
  // write leaves the existing file as it was); a format without memory output writes directly.
  std::vector<unsigned char> bytes;
  OIIO::Filesystem::IOVecOutput memory(bytes);
  const bool in_memory = out->supports("ioproxy") && out->set_ioproxy(&memory);
  const std::string ext = std::filesystem::path(path).extension().string();
  const bool isFloat = ext == ".exr" || ext == ".EXR" || ext == ".hdr";
  const OIIO::TypeDesc type = isFloat       ? OIIO::TypeDesc::FLOAT
                              : sixteen_bit ? OIIO::TypeDesc::UINT16
                                            : OIIO::TypeDesc::UINT8;
  OIIO::ImageSpec spec(img.cols, img.rows, 3, type);
  std::vector<float> data(static_cast<std::size_t>(img.cols) * img.rows * 3);
  for (int y = 0; y < img.rows; ++y) {
    const auto* row = img.ptr<cv::Vec3f>(y);
    for (int x = 0; x < img.cols; ++x)
      for (int c = 0; c < 3; ++c) {
        const float v = row[x][c];
        data[(static_cast<std::size_t>(y) * img.cols + x) * 3 + c] = isFloat ? v : color::linearToSrgb(v);
      }
  }
  if (!out->open(path, spec)) throw ImageIoError(path + ": cannot open for writing: " + out->geterror());
  if (!out->write_image(OIIO::TypeDesc::FLOAT, data.data()))
    throw ImageIoError(path + ": cannot write the image: " + out->geterror());
  if (!out->close()) throw ImageIoError(path + ": cannot finish the file: " + out->geterror());
  if (!in_memory) return;
  try {
    writeOutputFile(path, std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
  } catch (const OutputError& e) {
    throw ImageIoError(e.what());
  }
}

}  // namespace fovea::image
