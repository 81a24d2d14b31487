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
#include <string_view>
#include <variant>

#include "model/color/srgb.h"
#include "model/image/image_codec.h"
#include "model/io/json_input.h"
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

// The header's pixel count, before any pixel is decoded ("" when acceptable).
std::string specProblem(const ImageHeader& h) {
  const double pixels = static_cast<double>(h.width) * h.height * std::max(1, h.depth);
  if (h.width <= 0 || h.height <= 0 || h.channels <= 0) return "image has no pixels";
  if (pixels > kMaxImagePixels)
    return "the header declares " + std::to_string(h.width) + " x " + std::to_string(h.height) +
           " pixels, more than the limit of 50 Mpixel";
  return {};
}

// Checks the file, then decodes its first `max_channels` channels as float (header in `h`).
std::vector<float> decode(const std::string& path, int max_channels, ImageHeader& h) {
  checkFile(path);
  std::vector<float> pixels;
  const std::string problem = imageCodec().read(path, specProblem, max_channels, true, h, pixels);
  if (!problem.empty()) throw ImageIoError(path + ": " + problem);
  return pixels;
}

// A private directory under $TMPDIR (mkdtemp: mode 0700), removed with everything in it when
// the object goes out of scope: where a format that cannot encode to memory is staged.
class StagingDirectory {
 public:
  StagingDirectory() {
    std::string tmpl = (std::filesystem::temp_directory_path() / "fovea-image-XXXXXX").string();
    if (::mkdtemp(tmpl.data()) == nullptr)
      throw ImageIoError("cannot create a staging directory in " + std::filesystem::temp_directory_path().string() +
                         ": " + std::strerror(errno));
    dir_ = tmpl;
  }
  ~StagingDirectory() {
    std::error_code ignored;
    std::filesystem::remove_all(dir_, ignored);
  }
  StagingDirectory(const StagingDirectory&) = delete;
  StagingDirectory& operator=(const StagingDirectory&) = delete;
  const std::filesystem::path& path() const { return dir_; }

 private:
  std::filesystem::path dir_;
};

// Encodes through the codec and writes the bytes by the one writer (atomic, checked, fsync'ed:
// a failed write leaves the existing file as it was). A format the codec cannot encode to
// memory (SGI, ICO, FITS, HEIF, RLA, zfile in OpenImageIO 2.4) is encoded into a file of the
// same name in a private staging directory and its bytes then go through the same writer, so
// no format writes the target directly (issue 28).
void encode(const std::string& path, int width, int height, int channels, SampleType file_type, SampleType data_type,
            const void* data) {
  if (const auto why = outputPathProblem(path)) throw ImageIoError(path + ": " + *why);
  StagingDirectory staging;
  // Same file name, so the codec picks the format by the same extension.
  const std::filesystem::path staged = staging.path() / std::filesystem::path(path).filename();
  std::vector<unsigned char> bytes;
  bool in_memory = false;
  const std::string problem =
      imageCodec().write(staged.string(), width, height, channels, file_type, data_type, data, bytes, in_memory);
  if (!problem.empty()) throw ImageIoError(path + ": " + problem);
  std::string staged_bytes;  // read back through the program's one input reader
  if (!in_memory) {
    auto read = readInputFile(staged, kMaxImageFileBytes);
    if (read.index() == 1)
      throw ImageIoError(path + ": cannot read back the staged image " + staged.string() + ": " + std::get<1>(read));
    staged_bytes = std::move(std::get<0>(read));
  }
  const std::string_view text =
      in_memory ? std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()) : staged_bytes;
  try {
    writeOutputFile(path, text);
  } catch (const OutputError& e) {
    throw ImageIoError(e.what());
  }
}

}  // namespace

void checkImageFile(const std::string& path) {
  checkFile(path);
  ImageHeader h;
  std::vector<float> none;
  const std::string problem = imageCodec().read(path, specProblem, 0, false, h, none);
  if (!problem.empty()) throw ImageIoError(path + ": " + problem);
}

cv::Mat readLinearRgb(const std::string& path) {
  ImageHeader h;
  const std::vector<float> pixels = decode(path, 3, h);  // RGB or grey: alpha and extra channels are not read
  const int w = h.width, nc = std::min(h.channels, 3);
  cv::Mat out(h.height, w, CV_32FC3);
  for (int y = 0; y < h.height; ++y) {
    auto* row = out.ptr<cv::Vec3f>(y);
    for (int x = 0; x < w; ++x) {
      const float* p = &pixels[(static_cast<std::size_t>(y) * w + x) * nc];
      cv::Vec3f v = nc >= 3 ? cv::Vec3f(p[0], p[1], p[2]) : cv::Vec3f(p[0], p[0], p[0]);
      if (!h.is_float)
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
  const std::string ext = std::filesystem::path(path).extension().string();
  const bool isFloat = ext == ".exr" || ext == ".EXR" || ext == ".hdr";
  const SampleType type = isFloat ? SampleType::F32 : sixteen_bit ? SampleType::U16 : SampleType::U8;
  std::vector<float> data(static_cast<std::size_t>(img.cols) * img.rows * 3);
  for (int y = 0; y < img.rows; ++y) {
    const auto* row = img.ptr<cv::Vec3f>(y);
    for (int x = 0; x < img.cols; ++x)
      for (int c = 0; c < 3; ++c) {
        const float v = row[x][c];
        data[(static_cast<std::size_t>(y) * img.cols + x) * 3 + c] = isFloat ? v : color::linearToSrgb(v);
      }
  }
  encode(path, img.cols, img.rows, 3, type, SampleType::F32, data.data());
}

cv::Mat readCameraImage(const std::string& path) {
  ImageHeader h;
  const std::vector<float> pixels = decode(path, 3, h);
  const int nc = std::min(h.channels, 3);
  cv::Mat out(h.height, h.width, CV_8UC1);
  for (int y = 0; y < h.height; ++y) {
    auto* row = out.ptr<std::uint8_t>(y);
    for (int x = 0; x < h.width; ++x) {
      const float* p = &pixels[(static_cast<std::size_t>(y) * h.width + x) * nc];
      // Colour files to grey with cv::IMREAD_GRAYSCALE's weights (ITU-R BT.601), samples as stored.
      const double v = nc >= 3 ? 0.299 * p[0] + 0.587 * p[1] + 0.114 * p[2] : p[0];
      if (!std::isfinite(v)) throw ImageIoError(path + ": image holds non-finite pixel values");
      row[x] = static_cast<std::uint8_t>(std::lround(std::clamp(v, 0.0, 1.0) * 255.0));
    }
  }
  return out;
}

void writeCameraImage(const std::string& path, const cv::Mat& image) {
  if (image.channels() != 1 || (image.depth() != CV_8U && image.depth() != CV_16U))
    throw ImageIoError(path + ": internal: expected a one-channel 8- or 16-bit camera image");
  const cv::Mat dense = image.isContinuous() ? image : image.clone();
  const SampleType type = image.depth() == CV_8U ? SampleType::U8 : SampleType::U16;
  encode(path, image.cols, image.rows, 1, type, type, dense.data);
}

}  // namespace fovea::image
