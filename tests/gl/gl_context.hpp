// A headless OpenGL 4.5 core context for the shader tests, and the few calls
// they need: compile a compute program with our runtime includes prepended,
// upload a texture (from a Texture or from a DDS file's bytes as they are),
// run the program, read back a shader storage buffer.
//
// The context is Mesa's software rasterizer (llvmpipe) opened through EGL's
// surfaceless platform (EGL_MESA_platform_surfaceless with
// eglGetPlatformDisplayEXT): no window system, no display, no GPU. Only the
// GL test executable links libEGL and libOpenGL (tests/CMakeLists.txt); the
// skybake executable and libraries never do.
//
// Every helper below opens the shared context first (GlContext::shared()),
// so no GL call runs without one.
//
// Every failure throws GlError naming the step (eglInitialize, the shader's
// info log with the source's line numbers, a GL error after a call), so a
// test that cannot run fails with the reason instead of skipping.
#pragma once

#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/texture.hpp"

namespace skybake::gltest {

class GlError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Opens the context and makes it current on the calling thread; closes it in
// the destructor. One per test process is enough (GlContext::shared()).
class GlContext {
 public:
  GlContext();
  ~GlContext();
  GlContext(const GlContext&) = delete;
  GlContext& operator=(const GlContext&) = delete;

  // The context every test of the process shares, opened on first use.
  static GlContext& shared();

  std::string renderer() const;  // GL_RENDERER, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)"
  std::string version() const;   // GL_VERSION, e.g. "4.5 (Core Profile) Mesa 22.3.6"
  int major_version() const;
  int minor_version() const;

 private:
  void* display_ = nullptr;
  void* context_ = nullptr;
};

// Throws GlError "<what>: GL error 0x...." when glGetError reports one.
void check_gl(const std::string& what);

// --- Programs -------------------------------------------------------------

// The text of runtime/glsl/<name> (runtime/hlsl for .hlsl), read from the
// source tree, preceded by every file it names on a line `// requires: a, b`
// at its top (recursively, each file once, dependencies first).
std::string runtime_source(const std::vector<std::string>& includes);
// The names, in the order runtime_source concatenates them.
std::vector<std::string> runtime_include_order(const std::vector<std::string>& includes);

// A linked compute program; deletes it when destroyed.
class ComputeProgram {
 public:
  ComputeProgram() = default;
  explicit ComputeProgram(unsigned id) : id_(id) {}
  ~ComputeProgram();
  ComputeProgram(ComputeProgram&& other) noexcept;
  ComputeProgram& operator=(ComputeProgram&& other) noexcept;
  unsigned id() const { return id_; }
  // The location of a uniform; throws GlError when the program has none of that name.
  int uniform(const std::string& name) const;
  // Whether the program has an active uniform of that name (the compiler
  // drops the ones main never reads).
  bool has_uniform(const std::string& name) const;
  // Sets a uniform (glProgramUniform*); throws GlError as uniform() does.
  void set(const std::string& name, float v) const;
  void set(const std::string& name, int v) const;
  void set(const std::string& name, const glm::vec2& v) const;
  void set(const std::string& name, const glm::vec3& v) const;
  void set(const std::string& name, const glm::vec4& v) const;
  void set(const std::string& name, const glm::ivec2& v) const;

 private:
  unsigned id_ = 0;
};

// Compiles "#version 450 core", the runtime includes (runtime_source) and
// `body` (which declares the local size, its buffers and main) into a compute
// program. Throws GlError with the info log, the includes and the numbered
// source when compiling or linking fails.
ComputeProgram compile_compute(const std::vector<std::string>& includes, const std::string& body);

// The HLSL twin: the runtime/hlsl includes and `body` (an HLSL compute
// shader with entry point `main`) compiled by glslangValidator's HLSL front
// end to SPIR-V (-D -V --auto-sampled-textures: each Texture becomes a
// combined sampler, its SamplerState comes from the GL texture object) and
// loaded through GL_ARB_gl_spirv. Bindings follow the registers: t<n> is
// texture unit n or, for a StructuredBuffer, storage buffer n; u<n> storage
// buffer n. SPIR-V keeps no uniform names: pass parameters in buffers.
// Throws GlError with the compiler's output when glslangValidator is
// missing or fails, or when the driver refuses the module.
ComputeProgram compile_compute_hlsl(const std::vector<std::string>& includes,
                                    const std::string& body);

// Runs `program` over groups_x * groups_y * groups_z work groups and waits
// for its writes to buffers and images to be visible.
void dispatch(const ComputeProgram& program, unsigned groups_x, unsigned groups_y = 1,
              unsigned groups_z = 1);

// --- Textures -------------------------------------------------------------

enum class Filter { nearest, linear };
enum class Wrap { clamp_to_edge, repeat };

// How a texture is sampled: one filter for minification and magnification
// (no mips: our LUTs are read at level 0), and the wrap per axis (s, t, r).
struct SamplerState {
  Filter filter = Filter::linear;
  Wrap wrap_s = Wrap::clamp_to_edge;
  Wrap wrap_t = Wrap::clamp_to_edge;
  Wrap wrap_r = Wrap::clamp_to_edge;
};

// A texture object; deletes it when destroyed. `target` is GL_TEXTURE_2D,
// GL_TEXTURE_2D_ARRAY or GL_TEXTURE_3D.
class GlTexture {
 public:
  GlTexture() = default;
  GlTexture(unsigned id, unsigned target) : id_(id), target_(target) {}
  ~GlTexture();
  GlTexture(GlTexture&& other) noexcept;
  GlTexture& operator=(GlTexture&& other) noexcept;
  unsigned id() const { return id_; }
  unsigned target() const { return target_; }
  // Binds to texture unit `unit`.
  void bind(unsigned unit) const;

 private:
  unsigned id_ = 0;
  unsigned target_ = 0;
};

// Uploads the float32 texels of `tex` (1 to 4 channels, as R, RG, RGB or
// RGBA32F), level 0 only. A volume becomes a 3D texture, layers a 2D array
// (and one layer too when `array` is set, for shaders that read a
// sampler2DArray whatever the layer count).
GlTexture upload_texture(const Texture& tex, const SamplerState& sampler, bool array = false);

// Uploads the bytes of a DDS file written by skybake's DDS writer as they
// are, level 0 of every layer or slice, with the GL internal format matching
// its DXGI format (docs/runtime.md "Loading DDS files"); `array` as for
// upload_texture. Throws GlError for a format without a mapping.
GlTexture upload_dds(const std::string& path, const SamplerState& sampler, bool array = false);

// Uploads the bytes of a DDS cube map written by write_dds_cube (one cube,
// an uncompressed format) as they are, every face and level, into a
// GL_TEXTURE_CUBE_MAP sampled trilinear with seamless filtering across faces.
GlTexture upload_dds_cube(const std::string& path);

// The GL internal format, pixel format and pixel type of a DXGI format code
// (the DdsFormat values of io/dds.hpp); false when there is no mapping.
struct GlPixelFormat {
  unsigned internal_format = 0, format = 0, type = 0;
  int bytes_per_texel = 0;  // 0 for a block format
  int block_bytes = 0;      // bytes per 4x4 block of a block format, else 0
};
bool gl_format_from_dxgi(uint32_t dxgi_format, GlPixelFormat* out);

// --- Buffers --------------------------------------------------------------

// A shader storage buffer; deletes it when destroyed.
class StorageBuffer {
 public:
  // `bytes` bytes, filled from `data` when given (else zero).
  StorageBuffer(size_t bytes, const void* data = nullptr);
  template <typename T>
  explicit StorageBuffer(const std::vector<T>& values)
      : StorageBuffer(values.size() * sizeof(T), values.data()) {}
  ~StorageBuffer();
  StorageBuffer(const StorageBuffer&) = delete;
  StorageBuffer& operator=(const StorageBuffer&) = delete;
  unsigned id() const { return id_; }
  size_t bytes() const { return bytes_; }
  // Binds to binding point `index` of GL_SHADER_STORAGE_BUFFER.
  void bind(unsigned index) const;
  // The buffer's contents as floats (bytes / 4 of them).
  std::vector<float> read_floats() const;

 private:
  unsigned id_ = 0;
  size_t bytes_ = 0;
};

}  // namespace skybake::gltest
