// GL handles, shader compilation, error counting and read-back.
#include "render/gl/gl_util.h"

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <mutex>
#include <vector>

#include <glm/gtc/type_ptr.hpp>

namespace sylva {

namespace {
std::atomic<int> g_errors{0};
std::mutex g_message_mutex;
std::string g_message;

void set_message(const std::string& m) {
  std::lock_guard<std::mutex> lock(g_message_mutex);
  g_message = m;
  std::fprintf(stderr, "sylva gl: %s\n", m.c_str());
}

void GLAPIENTRY on_debug_message(GLenum, GLenum type, GLuint, GLenum severity, GLsizei, const GLchar* text,
                                 const void*) {
  // Only real errors count: llvmpipe reports performance notes we have no reason to fail on.
  if (type != GL_DEBUG_TYPE_ERROR && severity != GL_DEBUG_SEVERITY_HIGH) return;
  ++g_errors;
  set_message(std::string("GL debug: ") + text);
}

GLuint compile_stage(const char* name, GLenum stage, const char* src, std::string& log) {
  GLuint s = glCreateShader(stage);
  glShaderSource(s, 1, &src, nullptr);
  glCompileShader(s);
  GLint ok = 0;
  glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    GLint n = 0;
    glGetShaderiv(s, GL_INFO_LOG_LENGTH, &n);
    std::string text(size_t(n > 1 ? n : 1), '\0');
    glGetShaderInfoLog(s, n, nullptr, text.data());
    log = std::string(name) + (stage == GL_VERTEX_SHADER ? " (vertex): " : " (fragment): ") + text.c_str();
    glDeleteShader(s);
    return 0;
  }
  return s;
}
}  // namespace

void delete_gl(gl_buffer& b) { if (b.id) glDeleteBuffers(1, &b.id); b.id = 0; }
void delete_gl(gl_texture& t) { if (t.id) glDeleteTextures(1, &t.id); t.id = 0; }
void delete_gl(gl_vertex_array& v) { if (v.id) glDeleteVertexArrays(1, &v.id); v.id = 0; }
void delete_gl(gl_framebuffer& f) { if (f.id) glDeleteFramebuffers(1, &f.id); f.id = 0; }
void delete_gl(gl_renderbuffer& b) { if (b.id) glDeleteRenderbuffers(1, &b.id); b.id = 0; }
void delete_gl(gl_program& p) { if (p.id) glDeleteProgram(p.id); p.id = 0; }

namespace {
std::atomic<int> g_programs{0};
}  // namespace

int gl_programs_compiled() { return g_programs.load(); }

gl_program compile_program(const char* name, const char* vertex_src, const char* fragment_src) {
  ++g_programs;
  gl_program p;
  std::string log;
  GLuint vs = compile_stage(name, GL_VERTEX_SHADER, vertex_src, log);
  GLuint fs = vs ? compile_stage(name, GL_FRAGMENT_SHADER, fragment_src, log) : 0;
  if (!vs || !fs) {
    if (vs) glDeleteShader(vs);
    set_message("shader " + log);
    p.failed = true;
    return p;
  }
  p.id = glCreateProgram();
  glAttachShader(p.id, vs);
  glAttachShader(p.id, fs);
  glLinkProgram(p.id);
  glDeleteShader(vs);
  glDeleteShader(fs);
  GLint ok = 0;
  glGetProgramiv(p.id, GL_LINK_STATUS, &ok);
  if (!ok) {
    GLint n = 0;
    glGetProgramiv(p.id, GL_INFO_LOG_LENGTH, &n);
    std::string text(size_t(n > 1 ? n : 1), '\0');
    glGetProgramInfoLog(p.id, n, nullptr, text.data());
    set_message(std::string("shader ") + name + " (link): " + text.c_str());
    glDeleteProgram(p.id);
    p.id = 0;
    p.failed = true;
  }
  return p;
}

void install_gl_debug_output() {
  if (!epoxy_has_gl_extension("GL_KHR_debug") && epoxy_gl_version() < 43) return;
  glEnable(GL_DEBUG_OUTPUT);
  glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
  glDebugMessageCallback(on_debug_message, nullptr);
}

int check_gl(const char* where) {
  int n = 0;
  for (GLenum e = glGetError(); e != GL_NO_ERROR && n < 16; e = glGetError()) {
    ++n;
    char text[128];
    std::snprintf(text, sizeof text, "glGetError 0x%04x after %s", unsigned(e), where);
    set_message(text);
  }
  g_errors += n;
  return n;
}

int gl_error_count() { return g_errors.load(); }
void reset_gl_error_count() { g_errors = 0; }
std::string gl_last_message() {
  std::lock_guard<std::mutex> lock(g_message_mutex);
  return g_message;
}

void set_uniform(const gl_program& p, const char* name, float v) { glUniform1f(glGetUniformLocation(p.id, name), v); }
void set_uniform(const gl_program& p, const char* name, int v) { glUniform1i(glGetUniformLocation(p.id, name), v); }
void set_uniform(const gl_program& p, const char* name, const glm::vec2& v) {
  glUniform2fv(glGetUniformLocation(p.id, name), 1, glm::value_ptr(v));
}
void set_uniform(const gl_program& p, const char* name, const glm::vec3& v) {
  glUniform3fv(glGetUniformLocation(p.id, name), 1, glm::value_ptr(v));
}
void set_uniform(const gl_program& p, const char* name, const glm::vec4& v) {
  glUniform4fv(glGetUniformLocation(p.id, name), 1, glm::value_ptr(v));
}
void set_uniform(const gl_program& p, const char* name, const glm::mat4& v) {
  glUniformMatrix4fv(glGetUniformLocation(p.id, name), 1, GL_FALSE, glm::value_ptr(v));
}

std::string create_color_target(int width, int height, gl_texture& color, gl_framebuffer& fbo) {
  glGenTextures(1, &color.id);
  glBindTexture(GL_TEXTURE_2D, color.id);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, width, height, 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
  glGenFramebuffers(1, &fbo.id);
  glBindFramebuffer(GL_FRAMEBUFFER, fbo.id);
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, color.id, 0);
  const bool complete = glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  return complete ? "" : "cannot create the image target";
}

image read_back_rgba(int x, int y, int width, int height) {
  image img;
  img.width = std::max(width, 0), img.height = std::max(height, 0), img.channels = 4;
  std::vector<uint8_t> rows(size_t(img.width) * size_t(img.height) * 4);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  if (!rows.empty()) glReadPixels(x, y, width, height, GL_RGBA, GL_UNSIGNED_BYTE, rows.data());
  img.pixels.resize(rows.size());
  const size_t row = size_t(img.width) * 4;
  for (int r = 0; r < img.height; ++r)
    std::copy_n(&rows[size_t(img.height - 1 - r) * row], row, &img.pixels[size_t(r) * row]);
  return img;
}

}  // namespace sylva
