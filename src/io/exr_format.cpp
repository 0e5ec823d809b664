#include "io/exr_format.hpp"

#include <mutex>
#include <type_traits>

#include <ImfThreading.h>
#include <tbb/global_control.h>

namespace skybake {

const std::string kExrPrefix = "skybake:";

namespace {

const char* const kReservedKeys[] = {"shape",      "channels",    "layout",       "atlas_columns",
                                     "atlas_rows", "slice_width", "slice_height", "slice_count"};

template <class T>
Imf::FrameBuffer frame_buffer(const std::vector<std::string>& channels, const T* pixels,
                              int64_t width, int64_t min_x, int64_t min_y) {
  const Imf::PixelType type = std::is_same_v<T, half> ? Imf::HALF : Imf::FLOAT;
  const size_t x_stride = sizeof(T) * channels.size();
  const size_t y_stride = x_stride * size_t(width);
  // OpenEXR addresses texel (x, y) at base + x x_stride + y y_stride.
  char* base = reinterpret_cast<char*>(const_cast<T*>(pixels)) -
               (min_x * int64_t(x_stride) + min_y * int64_t(y_stride));
  Imf::FrameBuffer fb;
  for (size_t c = 0; c < channels.size(); ++c)
    fb.insert(channels[c], Imf::Slice(type, base + c * sizeof(T), x_stride, y_stride));
  return fb;
}

}  // namespace

bool is_reserved_exr_key(const std::string& key) {
  for (const char* r : kReservedKeys)
    if (key == r) return true;
  return false;
}

std::string join_exr_channels(const std::vector<std::string>& channels) {
  std::string s;
  for (size_t i = 0; i < channels.size(); ++i) s += (i ? "," : "") + channels[i];
  return s;
}

std::vector<std::string> split_exr_channels(const std::string& text) {
  std::vector<std::string> out;
  size_t start = 0;
  for (size_t comma; (comma = text.find(',', start)) != std::string::npos; start = comma + 1)
    out.push_back(text.substr(start, comma - start));
  out.push_back(text.substr(start));
  return out;
}

std::vector<std::string> exr_part_channels(const std::string& part,
                                           const std::vector<std::string>& channels) {
  if (part.empty()) return channels;
  std::vector<std::string> out;
  for (const std::string& c : channels) out.push_back(part + "." + c);
  return out;
}

Imf::FrameBuffer exr_frame_buffer(const std::vector<std::string>& channels, const float* pixels,
                                  int64_t width, int64_t min_x, int64_t min_y) {
  return frame_buffer(channels, pixels, width, min_x, min_y);
}

Imf::FrameBuffer exr_frame_buffer(const std::vector<std::string>& channels, const half* pixels,
                                  int64_t width, int64_t min_x, int64_t min_y) {
  return frame_buffer(channels, pixels, width, min_x, min_y);
}

int exr_threads() {
  const int n = int(
      tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism));
  const int threads = n > 1 ? n : 0;  // 0: the calling thread only, no pool
  static std::mutex resize;
  const std::lock_guard<std::mutex> lock(resize);
  if (Imf::globalThreadCount() != threads) Imf::setGlobalThreadCount(threads);
  return threads;
}

}  // namespace skybake
