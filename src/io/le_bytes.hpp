// Little-endian integers in byte buffers, for the binary formats we write
// and read ourselves (KTX2). Byte by byte, so host order and alignment never
// matter.
#pragma once

#include <cstdint>
#include <cstring>

namespace skybake::le {

inline void put_u16(uint8_t* p, uint16_t v) {
  p[0] = uint8_t(v);
  p[1] = uint8_t(v >> 8);
}
inline void put_u32(uint8_t* p, uint32_t v) {
  for (int i = 0; i < 4; ++i) p[i] = uint8_t(v >> (8 * i));
}
inline void put_u64(uint8_t* p, uint64_t v) {
  for (int i = 0; i < 8; ++i) p[i] = uint8_t(v >> (8 * i));
}
inline void put_f32(uint8_t* p, float v) {
  uint32_t u;
  std::memcpy(&u, &v, 4);
  put_u32(p, u);
}
inline uint16_t get_u16(const uint8_t* p) {
  return uint16_t(p[0] | p[1] << 8);
}
inline uint32_t get_u32(const uint8_t* p) {
  return uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24;
}
inline uint64_t get_u64(const uint8_t* p) {
  return uint64_t(get_u32(p)) | uint64_t(get_u32(p + 4)) << 32;
}
inline float get_f32(const uint8_t* p) {
  const uint32_t u = get_u32(p);
  float v;
  std::memcpy(&v, &u, 4);
  return v;
}

}  // namespace skybake::le
