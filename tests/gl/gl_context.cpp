// The headless GL context and helpers of gl_context.hpp.
#include "gl/gl_context.hpp"

#include <EGL/egl.h>
#include <EGL/eglext.h>
#define GL_GLEXT_PROTOTYPES
#include <GL/glcorearb.h>

#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <functional>
#include <iterator>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <set>
#include <sstream>

#include "io/dds.hpp"

namespace skybake::gltest {
namespace {

std::string hex(unsigned v) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "0x%04X", v);
  return buf;
}

std::string egl_failure(const std::string& step) {
  return "cannot open a headless OpenGL 4.5 core context: " + step + " failed (EGL error " +
         hex(unsigned(eglGetError())) + ")";
}

bool has_extension(const char* list, const std::string& name) {
  if (!list) return false;
  std::istringstream words(list);
  std::string w;
  while (words >> w)
    if (w == name) return true;
  return false;
}

}  // namespace

// --- Context --------------------------------------------------------------

GlContext::GlContext() {
  const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  if (!has_extension(client, "EGL_MESA_platform_surfaceless"))
    throw GlError("cannot open a headless OpenGL 4.5 core context: EGL has no "
                  "EGL_MESA_platform_surfaceless (client extensions: " +
                  std::string(client ? client : "none") + ")");
  auto get_platform_display = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(
      eglGetProcAddress("eglGetPlatformDisplayEXT"));
  if (!get_platform_display) throw GlError(egl_failure("eglGetProcAddress(eglGetPlatformDisplayEXT)"));
  EGLDisplay display = get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
  if (display == EGL_NO_DISPLAY) throw GlError(egl_failure("eglGetPlatformDisplayEXT"));
  EGLint major = 0, minor = 0;
  if (!eglInitialize(display, &major, &minor)) throw GlError(egl_failure("eglInitialize"));
  if (!eglBindAPI(EGL_OPENGL_API)) {
    eglTerminate(display);
    throw GlError(egl_failure("eglBindAPI(EGL_OPENGL_API)"));
  }
  const EGLint attributes[] = {EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 5,
                               EGL_CONTEXT_OPENGL_PROFILE_MASK,
                               EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
  // EGL_KHR_no_config_context: no surface, so no config is needed.
  EGLContext context = eglCreateContext(display, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attributes);
  if (context == EGL_NO_CONTEXT) {
    eglTerminate(display);
    throw GlError(egl_failure("eglCreateContext (OpenGL 4.5 core)"));
  }
  if (!eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context)) {
    eglDestroyContext(display, context);
    eglTerminate(display);
    throw GlError(egl_failure("eglMakeCurrent (surfaceless)"));
  }
  display_ = display;
  context_ = context;
  if (major_version() * 10 + minor_version() < 45)
    throw GlError("the context is OpenGL " + version() + ", expected 4.5 or later");
}

GlContext::~GlContext() {
  if (!display_) return;
  eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  eglDestroyContext(display_, context_);
  eglTerminate(display_);
}

GlContext& GlContext::shared() {
  static GlContext context;
  return context;
}

std::string GlContext::renderer() const {
  return reinterpret_cast<const char*>(glGetString(GL_RENDERER));
}
std::string GlContext::version() const {
  return reinterpret_cast<const char*>(glGetString(GL_VERSION));
}
int GlContext::major_version() const {
  GLint v = 0;
  glGetIntegerv(GL_MAJOR_VERSION, &v);
  return v;
}
int GlContext::minor_version() const {
  GLint v = 0;
  glGetIntegerv(GL_MINOR_VERSION, &v);
  return v;
}

void check_gl(const std::string& what) {
  const GLenum e = glGetError();
  if (e != GL_NO_ERROR) throw GlError(what + ": GL error " + hex(e));
}

// --- Programs -------------------------------------------------------------

namespace {

std::string read_runtime_file(const std::string& name) {
  const bool hlsl = name.size() > 5 && name.compare(name.size() - 5, 5, ".hlsl") == 0;
  const std::string path =
      std::string(SKYBAKE_SOURCE_DIR) + (hlsl ? "/runtime/hlsl/" : "/runtime/glsl/") + name;
  std::ifstream in(path, std::ios::binary);
  if (!in) throw GlError("cannot read runtime include " + path);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// The names on the file's `// requires:` lines (comma or space separated).
std::vector<std::string> required_by(const std::string& text) {
  std::vector<std::string> names;
  std::istringstream lines(text);
  std::string line;
  const std::string tag = "// requires:";
  while (std::getline(lines, line)) {
    if (line.compare(0, tag.size(), tag) != 0) continue;
    std::string rest = line.substr(tag.size());
    std::replace(rest.begin(), rest.end(), ',', ' ');
    std::istringstream words(rest);
    std::string w;
    while (words >> w) names.push_back(w);
  }
  return names;
}

void visit_include(const std::string& name, std::set<std::string>& seen,
                   std::set<std::string>& active, std::vector<std::string>& order) {
  if (seen.count(name)) return;
  if (active.count(name)) throw GlError("runtime includes require each other in a cycle at " + name);
  active.insert(name);
  for (const std::string& dep : required_by(read_runtime_file(name)))
    visit_include(dep, seen, active, order);
  active.erase(name);
  seen.insert(name);
  order.push_back(name);
}

std::string numbered(const std::string& source) {
  std::ostringstream out;
  std::istringstream lines(source);
  std::string line;
  for (int n = 1; std::getline(lines, line); ++n) out << n << ": " << line << "\n";
  return out.str();
}

}  // namespace

std::vector<std::string> runtime_include_order(const std::vector<std::string>& includes) {
  std::set<std::string> seen, active;
  std::vector<std::string> order;
  for (const std::string& name : includes) visit_include(name, seen, active, order);
  return order;
}

std::string runtime_source(const std::vector<std::string>& includes) {
  std::string source;
  for (const std::string& name : runtime_include_order(includes)) {
    source += read_runtime_file(name);
    if (!source.empty() && source.back() != '\n') source += '\n';
  }
  return source;
}

ComputeProgram::~ComputeProgram() {
  if (id_) glDeleteProgram(id_);
}
ComputeProgram::ComputeProgram(ComputeProgram&& other) noexcept : id_(other.id_) { other.id_ = 0; }
ComputeProgram& ComputeProgram::operator=(ComputeProgram&& other) noexcept {
  std::swap(id_, other.id_);
  return *this;
}

int ComputeProgram::uniform(const std::string& name) const {
  const GLint location = glGetUniformLocation(id_, name.c_str());
  if (location < 0) throw GlError("the compute program has no active uniform " + name);
  return location;
}

bool ComputeProgram::has_uniform(const std::string& name) const {
  return glGetUniformLocation(id_, name.c_str()) >= 0;
}

void ComputeProgram::set(const std::string& name, float v) const {
  glProgramUniform1f(id_, uniform(name), v);
}
void ComputeProgram::set(const std::string& name, int v) const {
  glProgramUniform1i(id_, uniform(name), v);
}
void ComputeProgram::set(const std::string& name, const glm::vec2& v) const {
  glProgramUniform2f(id_, uniform(name), v.x, v.y);
}
void ComputeProgram::set(const std::string& name, const glm::vec3& v) const {
  glProgramUniform3f(id_, uniform(name), v.x, v.y, v.z);
}
void ComputeProgram::set(const std::string& name, const glm::vec4& v) const {
  glProgramUniform4f(id_, uniform(name), v.x, v.y, v.z, v.w);
}

void ComputeProgram::set(const std::string& name, const glm::ivec2& v) const {
  glProgramUniform2i(id_, uniform(name), v.x, v.y);
}

ComputeProgram compile_compute(const std::vector<std::string>& includes, const std::string& body) {
  GlContext::shared();
  const std::string source = "#version 450 core\n" + runtime_source(includes) + body;
  const GLuint shader = glCreateShader(GL_COMPUTE_SHADER);
  const char* text = source.c_str();
  glShaderSource(shader, 1, &text, nullptr);
  glCompileShader(shader);
  GLint ok = 0;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  auto log_of = [](GLuint object, bool program) {
    GLint length = 0;
    program ? glGetProgramiv(object, GL_INFO_LOG_LENGTH, &length)
            : glGetShaderiv(object, GL_INFO_LOG_LENGTH, &length);
    std::string log(size_t(std::max(length, 1)), '\0');
    program ? glGetProgramInfoLog(object, length, nullptr, log.data())
            : glGetShaderInfoLog(object, length, nullptr, log.data());
    log.resize(std::strlen(log.c_str()));  // the length counts the terminating NUL
    return log;
  };
  std::string names;
  for (const std::string& n : runtime_include_order(includes)) names += " " + n;
  if (!ok) {
    const std::string log = log_of(shader, false);
    glDeleteShader(shader);
    throw GlError("compute shader (includes:" + names + ") does not compile:\n" + log + "\n" +
                  numbered(source));
  }
  const GLuint program = glCreateProgram();
  glAttachShader(program, shader);
  glLinkProgram(program);
  glDeleteShader(shader);
  glGetProgramiv(program, GL_LINK_STATUS, &ok);
  if (!ok) {
    const std::string log = log_of(program, true);
    glDeleteProgram(program);
    throw GlError("compute program (includes:" + names + ") does not link:\n" + log);
  }
  return ComputeProgram(program);
}

namespace {

std::string run_command(const std::string& command, int* status) {
  std::string output;
  FILE* pipe = popen((command + " 2>&1").c_str(), "r");
  if (!pipe) throw GlError("cannot run " + command);
  char buf[4096];
  size_t n;
  while ((n = fread(buf, 1, sizeof buf, pipe)) > 0) output.append(buf, n);
  *status = pclose(pipe);
  return output;
}

}  // namespace

ComputeProgram compile_compute_hlsl(const std::vector<std::string>& includes,
                                    const std::string& body) {
  GlContext::shared();
  const std::string source = runtime_source(includes) + body;
  const std::string base = std::string(SKYBAKE_TEST_TMP) + "/hlsl_" + std::to_string(getpid()) +
                           "_" + std::to_string(std::hash<std::string>()(source));
  std::filesystem::create_directories(SKYBAKE_TEST_TMP);
  {
    std::ofstream out(base + ".hlsl", std::ios::binary);
    out << source;
  }
  int status = 0;
  const std::string log = run_command("glslangValidator -D -V -S comp -e main --auto-sampled-textures -o '" +
                                          base + ".spv' '" + base + ".hlsl'",
                                      &status);
  if (status != 0)
    throw GlError("HLSL compute shader does not compile (glslangValidator exit " +
                  std::to_string(status) + "):\n" + log + "\n" + numbered(source));
  std::ifstream in(base + ".spv", std::ios::binary);
  const std::vector<char> spirv((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::filesystem::remove(base + ".hlsl");
  std::filesystem::remove(base + ".spv");
  auto specialize = reinterpret_cast<PFNGLSPECIALIZESHADERARBPROC>(
      eglGetProcAddress("glSpecializeShaderARB"));
  if (!specialize) throw GlError("the context has no glSpecializeShaderARB (GL_ARB_gl_spirv)");
  const GLuint shader = glCreateShader(GL_COMPUTE_SHADER);
  glShaderBinary(1, &shader, GL_SHADER_BINARY_FORMAT_SPIR_V_ARB, spirv.data(), GLsizei(spirv.size()));
  specialize(shader, "main", 0, nullptr, nullptr);
  GLint ok = 0;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    GLint length = 0;
    glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
    std::string info(size_t(std::max(length, 1)), '\0');
    glGetShaderInfoLog(shader, length, nullptr, info.data());
    glDeleteShader(shader);
    throw GlError("the driver refuses the SPIR-V of an HLSL compute shader: " + info);
  }
  const GLuint program = glCreateProgram();
  glAttachShader(program, shader);
  glLinkProgram(program);
  glDeleteShader(shader);
  glGetProgramiv(program, GL_LINK_STATUS, &ok);
  if (!ok) {
    glDeleteProgram(program);
    throw GlError("an HLSL compute program does not link");
  }
  return ComputeProgram(program);
}

void dispatch(const ComputeProgram& program, unsigned groups_x, unsigned groups_y,
              unsigned groups_z) {
  glUseProgram(program.id());
  glDispatchCompute(groups_x, groups_y, groups_z);
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT |
                  GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT);
  glFinish();
  check_gl("glDispatchCompute");
}

// --- Buffers --------------------------------------------------------------

StorageBuffer::StorageBuffer(size_t bytes, const void* data) : bytes_(bytes) {
  GlContext::shared();
  glCreateBuffers(1, &id_);
  std::vector<unsigned char> zeros;
  if (!data) {
    zeros.assign(std::max<size_t>(bytes, 1), 0);
    data = zeros.data();
  }
  glNamedBufferStorage(id_, GLsizeiptr(std::max<size_t>(bytes, 1)), data, 0);
  check_gl("glNamedBufferStorage");
}
StorageBuffer::~StorageBuffer() {
  if (id_) glDeleteBuffers(1, &id_);
}
void StorageBuffer::bind(unsigned index) const {
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, index, id_);
}
std::vector<float> StorageBuffer::read_floats() const {
  std::vector<float> values(bytes_ / sizeof(float));
  glGetNamedBufferSubData(id_, 0, GLsizeiptr(values.size() * sizeof(float)), values.data());
  check_gl("glGetNamedBufferSubData");
  return values;
}

}  // namespace skybake::gltest
