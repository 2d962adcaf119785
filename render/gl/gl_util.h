// Typed OpenGL handles, shader compilation with logged errors, and GL error counting.
#pragma once

#include <string>

#include <epoxy/gl.h>
#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "render/assets/textures.h"

namespace sylva {

// Distinct types so that a buffer can never be bound as a texture (docs/design/08-renderer.md).
struct gl_buffer { GLuint id = 0; };
struct gl_texture { GLuint id = 0; };
struct gl_vertex_array { GLuint id = 0; };
struct gl_framebuffer { GLuint id = 0; };
struct gl_renderbuffer { GLuint id = 0; };
struct gl_program {
  GLuint id = 0;
  bool failed = false;   // compile or link failed: callers fall back and never draw with it
};

void delete_gl(gl_buffer& b);
void delete_gl(gl_texture& t);
void delete_gl(gl_vertex_array& v);
void delete_gl(gl_framebuffer& f);
void delete_gl(gl_renderbuffer& b);
void delete_gl(gl_program& p);

// Compiles and links; on failure logs "<name>: <driver log>" to stderr and to gl_last_message(),
// and returns a program marked failed (id 0).
gl_program compile_program(const char* name, const char* vertex_src, const char* fragment_src);
// Programs compile_program has been asked for so far in this process (the startup count).
int gl_programs_compiled();

// Counts GL errors: a KHR_debug callback where the driver has one, plus glGetError polls.
void install_gl_debug_output();
int check_gl(const char* where);   // polls glGetError, counts and logs; returns errors found
int gl_error_count();
void reset_gl_error_count();
std::string gl_last_message();     // the last error or shader log, "" when none

// Uniform setters; location lookups are cheap and allocate nothing.
void set_uniform(const gl_program& p, const char* name, float v);
void set_uniform(const gl_program& p, const char* name, int v);
void set_uniform(const gl_program& p, const char* name, const glm::vec2& v);
void set_uniform(const gl_program& p, const char* name, const glm::vec3& v);
void set_uniform(const gl_program& p, const char* name, const glm::vec4& v);
void set_uniform(const gl_program& p, const char* name, const glm::mat4& v);

// An off-screen RGBA8 colour target of the given size (hidden windows have no reliable back buffer
// to read). Returns "" or the error; the framebuffer is left unbound.
std::string create_color_target(int width, int height, gl_texture& color, gl_framebuffer& fbo);

// Reads a rectangle of the bound read framebuffer as RGBA8 with rows top to bottom, as images and
// PNG files (render/assets/textures.h, the one PNG path) have them; GL's rows run bottom to top.
image read_back_rgba(int x, int y, int width, int height);

}  // namespace sylva
