// Texture uploads of gl_context.hpp: from a Texture's float32 texels, and from
// the bytes of a DDS file as they are on disk.
#include <EGL/egl.h>
#define GL_GLEXT_PROTOTYPES
#include <GL/glcorearb.h>

#include <fstream>
#include <iterator>

#include "gl/gl_context.hpp"
#include "io/dds.hpp"
#include "io/dds_format_table.hpp"

namespace skybake::gltest {
namespace {

GLenum gl_filter(Filter f) { return f == Filter::linear ? GL_LINEAR : GL_NEAREST; }
GLenum gl_wrap(Wrap w) { return w == Wrap::repeat ? GL_REPEAT : GL_CLAMP_TO_EDGE; }

void apply_sampler(GLuint id, const SamplerState& s) {
  glTextureParameteri(id, GL_TEXTURE_MIN_FILTER, GLint(gl_filter(s.filter)));
  glTextureParameteri(id, GL_TEXTURE_MAG_FILTER, GLint(gl_filter(s.filter)));
  glTextureParameteri(id, GL_TEXTURE_WRAP_S, GLint(gl_wrap(s.wrap_s)));
  glTextureParameteri(id, GL_TEXTURE_WRAP_T, GLint(gl_wrap(s.wrap_t)));
  glTextureParameteri(id, GL_TEXTURE_WRAP_R, GLint(gl_wrap(s.wrap_r)));
  // One level: the LUTs are read at level 0 (a DDS mip chain is not uploaded).
  glTextureParameteri(id, GL_TEXTURE_BASE_LEVEL, 0);
  glTextureParameteri(id, GL_TEXTURE_MAX_LEVEL, 0);
}

// Creates the texture object and its storage for width x height x slices
// (slices: depth of a volume or layers of an array).
GlTexture create_storage(GLenum target, GLenum internal_format, int width, int height, int slices) {
  GLuint id = 0;
  glCreateTextures(target, 1, &id);
  if (target == GL_TEXTURE_2D)
    glTextureStorage2D(id, 1, internal_format, width, height);
  else
    glTextureStorage3D(id, 1, internal_format, width, height, slices);
  check_gl("glTextureStorage (" + std::to_string(width) + "x" + std::to_string(height) + "x" +
           std::to_string(slices) + ")");
  return GlTexture(id, target);
}

void upload_slice(const GlTexture& tex, int width, int height, int slice, GLenum format,
                  GLenum type, const void* pixels) {
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  if (tex.target() == GL_TEXTURE_2D)
    glTextureSubImage2D(tex.id(), 0, 0, 0, width, height, format, type, pixels);
  else
    glTextureSubImage3D(tex.id(), 0, 0, 0, slice, width, height, 1, format, type, pixels);
  check_gl("glTextureSubImage (slice " + std::to_string(slice) + ")");
}

void upload_compressed_slice(const GlTexture& tex, int width, int height, int slice,
                             GLenum internal_format, size_t bytes, const void* blocks) {
  if (tex.target() == GL_TEXTURE_2D)
    glCompressedTextureSubImage2D(tex.id(), 0, 0, 0, width, height, internal_format,
                                  GLsizei(bytes), blocks);
  else
    glCompressedTextureSubImage3D(tex.id(), 0, 0, 0, slice, width, height, 1, internal_format,
                                  GLsizei(bytes), blocks);
  check_gl("glCompressedTextureSubImage (slice " + std::to_string(slice) + ")");
}

GLenum target_of(bool volume, bool array) {
  return volume ? GL_TEXTURE_3D : array ? GL_TEXTURE_2D_ARRAY : GL_TEXTURE_2D;
}

}  // namespace

GlTexture::~GlTexture() {
  if (id_) glDeleteTextures(1, &id_);
}
GlTexture::GlTexture(GlTexture&& other) noexcept : id_(other.id_), target_(other.target_) {
  other.id_ = 0;
}
GlTexture& GlTexture::operator=(GlTexture&& other) noexcept {
  std::swap(id_, other.id_);
  std::swap(target_, other.target_);
  return *this;
}
void GlTexture::bind(unsigned unit) const { glBindTextureUnit(unit, id_); }

GlTexture upload_texture(const Texture& tex, const SamplerState& sampler, bool array) {
  GlContext::shared();
  static const GLenum internal[] = {GL_R32F, GL_RG32F, GL_RGB32F, GL_RGBA32F};
  static const GLenum format[] = {GL_RED, GL_RG, GL_RGB, GL_RGBA};
  const int c = tex.channel_count();
  if (c < 1 || c > 4) throw GlError("upload_texture: expected 1 to 4 channels, got " + std::to_string(c));
  const int slices = tex.is_volume() ? tex.depth : tex.layers;
  GlTexture out = create_storage(target_of(tex.is_volume(), tex.is_array() || array), internal[c - 1],
                                 tex.width, tex.height, slices);
  const size_t slice_floats = size_t(tex.width) * tex.height * c;
  for (int s = 0; s < slices; ++s)
    upload_slice(out, tex.width, tex.height, s, format[c - 1], GL_FLOAT,
                 tex.data.data() + size_t(s) * slice_floats);
  apply_sampler(out.id(), sampler);
  return out;
}

// docs/runtime.md "Loading DDS files": each DXGI format of our writer and its
// GL equivalent (same component order, same bits; UNORM as linear, not sRGB).
bool gl_format_from_dxgi(uint32_t dxgi_format, GlPixelFormat* out) {
  switch (DdsFormat(dxgi_format)) {
    case DdsFormat::R32G32B32A32_FLOAT: *out = {GL_RGBA32F, GL_RGBA, GL_FLOAT, 16}; return true;
    case DdsFormat::R16G16B16A16_FLOAT: *out = {GL_RGBA16F, GL_RGBA, GL_HALF_FLOAT, 8}; return true;
    case DdsFormat::R11G11B10_FLOAT:
      *out = {GL_R11F_G11F_B10F, GL_RGB, GL_UNSIGNED_INT_10F_11F_11F_REV, 4};
      return true;
    case DdsFormat::R8G8B8A8_UNORM: *out = {GL_RGBA8, GL_RGBA, GL_UNSIGNED_BYTE, 4}; return true;
    case DdsFormat::R16_FLOAT: *out = {GL_R16F, GL_RED, GL_HALF_FLOAT, 2}; return true;
    case DdsFormat::R8G8_UNORM: *out = {GL_RG8, GL_RG, GL_UNSIGNED_BYTE, 2}; return true;
    case DdsFormat::R8_UNORM: *out = {GL_R8, GL_RED, GL_UNSIGNED_BYTE, 1}; return true;
    // Block formats (EXT_texture_compression_s3tc, RGTC of GL 3.0): BC1 with
    // its 1-bit alpha as DXGI decodes it, BC3 = DXT5, BC4 and BC5 unsigned.
    case DdsFormat::BC1_UNORM: *out = {GL_COMPRESSED_RGBA_S3TC_DXT1_EXT, 0, 0, 0, 8}; return true;
    case DdsFormat::BC3_UNORM: *out = {GL_COMPRESSED_RGBA_S3TC_DXT5_EXT, 0, 0, 0, 16}; return true;
    case DdsFormat::BC4_UNORM: *out = {GL_COMPRESSED_RED_RGTC1, 0, 0, 0, 8}; return true;
    case DdsFormat::BC5_UNORM: *out = {GL_COMPRESSED_RG_RGTC2, 0, 0, 0, 16}; return true;
  }
  return false;
}

GlTexture upload_dds(const std::string& path, const SamplerState& sampler, bool array) {
  GlContext::shared();
  const DdsHeaderInfo h = read_dds_header(path);
  // A legacy header names the format by its pre-DX10 pixel format
  // (docs/runtime.md "Loading DDS files"); the data then starts at byte 128.
  const DdsFormatInfo* legacy = h.has_dx10 ? nullptr : find_legacy_format(h.pixel_format);
  const uint32_t dxgi = legacy ? uint32_t(legacy->format) : h.dxgi_format;
  const size_t header_bytes = h.has_dx10 ? dds::kHeaderBytes : dds::kLegacyHeaderBytes;
  GlPixelFormat px;
  if ((!h.has_dx10 && !legacy) || !gl_format_from_dxgi(dxgi, &px))
    throw GlError(path + ": no GL format for DXGI format " + std::to_string(dxgi));
  std::ifstream in(path, std::ios::binary);
  const std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const bool volume = (h.caps2 & dds::kCaps2Volume) != 0;
  const int width = int(h.width), height = int(h.height);
  const int depth = volume ? int(h.depth) : 1;
  const int layers = int(std::max<uint32_t>(h.array_size, 1));
  const int levels = int(std::max<uint32_t>(h.mip_map_count, 1));
  // Bytes of one 2D image of level l (rows tightly packed), and of a layer's
  // whole mip chain: a 2D array stores each layer with all its levels; a
  // volume stores level 0's depth slices first (Programming Guide for DDS).
  // A block format stores 4x4 blocks, a level below 4 texels padded to one.
  auto level_bytes = [&](int l) {
    const size_t w = size_t(std::max(width >> l, 1)), h = size_t(std::max(height >> l, 1));
    return px.block_bytes > 0 ? ((w + 3) / 4) * ((h + 3) / 4) * size_t(px.block_bytes)
                              : w * h * size_t(px.bytes_per_texel);
  };
  size_t chain_bytes = 0;
  for (int l = 0; l < levels; ++l)
    chain_bytes += level_bytes(l) * (volume ? size_t(std::max(depth >> l, 1)) : 1);
  const size_t needed = header_bytes + chain_bytes * (volume ? 1 : size_t(layers));
  if (bytes.size() < needed)
    throw GlError(path + ": " + std::to_string(bytes.size()) + " bytes, expected at least " +
                  std::to_string(needed));
  const int slices = volume ? depth : layers;
  GlTexture out = create_storage(target_of(volume, layers > 1 || array), px.internal_format, width, height, slices);
  for (int s = 0; s < slices; ++s) {
    const size_t offset = header_bytes + (volume ? size_t(s) * level_bytes(0) : size_t(s) * chain_bytes);
    if (px.block_bytes > 0)
      upload_compressed_slice(out, width, height, s, px.internal_format, level_bytes(0),
                              bytes.data() + offset);
    else
      upload_slice(out, width, height, s, px.format, px.type, bytes.data() + offset);
  }
  apply_sampler(out.id(), sampler);
  return out;
}

GlTexture upload_dds_cube(const std::string& path) {
  GlContext::shared();
  const DdsHeaderInfo h = read_dds_header(path);
  GlPixelFormat px;
  if (!h.has_dx10 || !(h.misc_flag & dds::kMiscTextureCube) || h.array_size != 1 ||
      !gl_format_from_dxgi(h.dxgi_format, &px) || px.bytes_per_texel == 0)
    throw GlError(path + ": expected one uncompressed DX10 cube map");
  std::ifstream in(path, std::ios::binary);
  const std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const int n = int(h.width), levels = int(std::max<uint32_t>(h.mip_map_count, 1));
  GLuint id = 0;
  glCreateTextures(GL_TEXTURE_CUBE_MAP, 1, &id);
  GlTexture out(id, GL_TEXTURE_CUBE_MAP);
  glTextureStorage2D(id, levels, px.internal_format, n, n);
  check_gl("glTextureStorage2D (cube)");
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  // Programming Guide for DDS: each face with all its levels, faces in order;
  // a cube's faces are the layers 0..5 of the direct-state-access calls.
  size_t offset = dds::kHeaderBytes;
  for (int face = 0; face < 6; ++face)
    for (int level = 0; level < levels; ++level) {
      const int side = std::max(n >> level, 1);
      const size_t level_bytes = size_t(side) * size_t(side) * size_t(px.bytes_per_texel);
      if (offset + level_bytes > bytes.size()) throw GlError(path + ": truncated cube map");
      glTextureSubImage3D(id, level, 0, 0, face, side, side, 1, px.format, px.type,
                          bytes.data() + offset);
      offset += level_bytes;
    }
  check_gl("glTextureSubImage3D (cube faces)");
  glTextureParameteri(id, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
  glTextureParameteri(id, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTextureParameteri(id, GL_TEXTURE_MAX_LEVEL, levels - 1);
  glEnable(GL_TEXTURE_CUBE_MAP_SEAMLESS);
  check_gl("cube sampler state");
  return out;
}

}  // namespace skybake::gltest
