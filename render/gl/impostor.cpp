// Impostor atlas: the uploaded tree drawn unlit (albedo and normals, two render targets) from 8 or
// 16 azimuths into one atlas, with the renderer's own vertex arrays and textures.
#include "render/gl/impostor.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <string>

#include <glm/geometric.hpp>

#include <glm/gtc/matrix_transform.hpp>

#include "generators/timing.h"
#include "render/assets/textures.h"
#include "render/gl/renderer_resources.h"
#include "render/gl/shaders.h"

namespace sylva {

static_assert(leaf_archetype_count + 16 < impostor_sun_card, "impostor layers fit below the sun-card flag");

namespace {

const char* bark_vs = R"(#version 330 core
layout(location = 0) in vec3 a_position; layout(location = 1) in vec3 a_normal; layout(location = 2) in vec2 a_uv;
uniform mat4 u_viewproj;
out vec3 v_normal; out vec2 v_uv; out float v_height;
void main() { v_normal = a_normal; v_uv = a_uv; v_height = a_position.y; gl_Position = u_viewproj * vec4(a_position, 1.0); }
)";

// After the version line and glsl::bark_tint_glsl (render/gl/shaders.h): the viewport's tint by height.
const char* bark_fs_body = R"(
in vec3 v_normal; in vec2 v_uv; in float v_height;
uniform sampler2D u_bark;
layout(location = 0) out vec4 o_color; layout(location = 1) out vec4 o_normal;
void main() {
  // The viewport's tint (render/assets/textures.h, gain 1): texel (linear, sRGB texture) times tint, then sRGB.
  vec3 albedo = min(vec3(1.0), bark_tint(v_height) * texture(u_bark, v_uv).rgb);
  o_color = vec4(pow(albedo, vec3(1.0 / 2.2)), 1.0);
  o_normal = vec4(normalize(v_normal) * 0.5 + 0.5, 1.0);
}
)";

const char* leaf_vs = R"(#version 330 core
layout(location = 0) in vec2 a_corner;
layout(location = 1) in vec3 i_position; layout(location = 2) in vec4 i_rotation; layout(location = 3) in float i_size;
layout(location = 4) in uvec2 i_born_died; layout(location = 5) in uint i_texture;
uniform mat4 u_viewproj; uniform int u_step; uniform int u_layers;
out vec3 v_normal; out vec2 v_uv; flat out float v_layer;
vec3 rotate(vec4 q, vec3 v) { return v + 2.0 * cross(q.xyz, cross(q.xyz, v) + q.w * v); }
void main() {
  bool alive = int(i_born_died.x) <= u_step && u_step < int(i_born_died.y);
  vec3 world = i_position + rotate(i_rotation, vec3(a_corner, 0.0) * i_size);
  v_normal = rotate(i_rotation, vec3(0.0, 0.0, 1.0));
  v_uv = vec2(a_corner.x + 0.5, 1.0 - a_corner.y);
  v_layer = float(int(i_texture) % u_layers);
  gl_Position = alive ? u_viewproj * vec4(world, 1.0) : vec4(2.0, 2.0, 2.0, 1.0);
}
)";

const char* leaf_fs = R"(#version 330 core
in vec3 v_normal; in vec2 v_uv; flat in float v_layer;
uniform sampler2DArray u_leaf; uniform vec3 u_tint; uniform float u_cutoff;
layout(location = 0) out vec4 o_color; layout(location = 1) out vec4 o_normal;
void main() {
  vec4 t = texture(u_leaf, vec3(v_uv, v_layer));
  if (t.a < u_cutoff) discard;
  vec3 n = normalize(v_normal);
  if (!gl_FrontFacing) n = -n;   // two-sided: the side facing the view
  o_color = vec4(pow(min(vec3(1.0), u_tint * t.rgb), vec3(1.0 / 2.2)), 1.0);
  o_normal = vec4(n * 0.5 + 0.5, 1.0);
}
)";

}  // namespace

namespace {

void free_build(impostor_build& b) {
  b.bark = b.leaf = {};   // the context's programs (gl_shared), not the build's
  delete_gl(b.color), delete_gl(b.normal), delete_gl(b.depth), delete_gl(b.fbo);
  for (gl_vertex_array* v : {&b.bark_vao, &b.leaf_vao}) delete_gl(*v);
  for (gl_buffer* u : {&b.position, &b.normal_buf, &b.uv, &b.index, &b.corner, &b.instances}) delete_gl(*u);
}

// The build's own copy of a mesh's bark positions, normals, uvs and leaf instances, laid out as the
// impostor shaders read them (the renderer's leaf attribute locations 0-5).
void upload_source(impostor_build& b, const tree_mesh& m) {
  glGenVertexArrays(1, &b.bark_vao.id);
  glGenVertexArrays(1, &b.leaf_vao.id);
  for (gl_buffer* u : {&b.position, &b.normal_buf, &b.uv, &b.index, &b.corner, &b.instances}) glGenBuffers(1, &u->id);
  glBindVertexArray(b.bark_vao.id);
  auto attribute = [](GLuint buffer, int location, int size, const void* data, size_t bytes) {
    glBindBuffer(GL_ARRAY_BUFFER, buffer);
    glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(bytes), data, GL_STATIC_DRAW);
    glEnableVertexAttribArray(GLuint(location));
    glVertexAttribPointer(GLuint(location), size, GL_FLOAT, GL_FALSE, 0, nullptr);
  };
  attribute(b.position.id, 0, 3, m.position.data(), m.position.size() * sizeof(glm::vec3));
  attribute(b.normal_buf.id, 1, 3, m.normal.data(), m.normal.size() * sizeof(glm::vec3));
  attribute(b.uv.id, 2, 2, m.uv.data(), m.uv.size() * sizeof(glm::vec2));
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, b.index.id);
  glBufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(m.index.size() * sizeof(uint32_t)), m.index.data(), GL_STATIC_DRAW);
  glBindVertexArray(b.leaf_vao.id);
  const float corners[8] = {-0.5f, 0, 0.5f, 0, -0.5f, 1, 0.5f, 1};
  attribute(b.corner.id, 0, 2, corners, sizeof corners);
  glBindBuffer(GL_ARRAY_BUFFER, b.instances.id);
  glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(m.leaves.size() * sizeof(leaf_instance)), m.leaves.data(), GL_STATIC_DRAW);
  leaf_instance_attributes();   // the renderer's layout; the atlas shaders read 1-5
  glBindVertexArray(0);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  b.bark_count = uint32_t(m.index.size());
  b.leaf_count = uint32_t(m.leaves.size());
  b.steps = m.steps;
}

}  // namespace

std::string impostor_begin(impostor_build& b, renderer_gpu& r, const render_params& rp, int views, int cell, const tree_mesh* m) {
  impostor_cancel(b);
  const auto start = std::chrono::steady_clock::now();
  impostor_atlas& a = b.atlas;
  a = impostor_atlas{};
  a.views = views > 12 ? 16 : 8;
  a.columns = 4;
  a.rows = a.views / a.columns;
  a.cell = std::clamp(cell, 16, 2048);
  a.width = a.columns * a.cell;
  a.height = a.rows * a.cell;
  b.rp = rp;
  b.next = 0;
  b.worst_step_ms = 0;
  b.st = impostor_build::state::failed;
  auto fail = [&](std::string why) {
    a.error = std::move(why);
    free_build(b);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    return a.error;
  };
  if (!r.ok) return fail("renderer not initialised");
  const bool has_tree = m ? !m->index.empty() || !m->leaves.empty() : r.has_tree;
  if (!has_tree) return fail("no tree to render");
  // The atlas's programs: compiled by the context's first atlas, kept with its other programs.
  gl_shared& s = *r.shared;
  if (!s.impostor_bark.id) {
    const std::string bark_fs = std::string("#version 330 core\n") + glsl::bark_tint_glsl + bark_fs_body;
    s.impostor_bark = compile_program("impostor bark", bark_vs, bark_fs.c_str());
  }
  if (!s.impostor_leaf.id) s.impostor_leaf = compile_program("impostor leaf", leaf_vs, leaf_fs);
  b.bark = s.impostor_bark;
  b.leaf = s.impostor_leaf;
  if (b.bark.failed || b.leaf.failed) return fail("impostor shaders: " + gl_last_message());
  for (gl_texture* t : {&b.color, &b.normal}) {
    glGenTextures(1, &t->id);
    glBindTexture(GL_TEXTURE_2D, t->id);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, a.width, a.height, 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  }
  glGenRenderbuffers(1, &b.depth.id);
  glBindRenderbuffer(GL_RENDERBUFFER, b.depth.id);
  glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, a.width, a.height);
  glGenFramebuffers(1, &b.fbo.id);
  glBindFramebuffer(GL_FRAMEBUFFER, b.fbo.id);
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, b.color.id, 0);
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT1, GL_TEXTURE_2D, b.normal.id, 0);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, b.depth.id);
  const GLenum targets[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
  glDrawBuffers(2, targets);
  if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) return fail("impostor framebuffer incomplete");
  glViewport(0, 0, a.width, a.height);
  glDisable(GL_SCISSOR_TEST);
  glDepthMask(GL_TRUE);
  glClearColor(0, 0, 0, 0);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  // The source: the mesh given, copied into the build's own buffers (the renderer may show another
  // level meanwhile), or the renderer's uploaded tree (which then must stay uploaded).
  b.own_mesh = m != nullptr;
  if (m) {
    upload_source(b, *m);
  } else {
    b.bark_count = r.index_end.empty() ? 0 : r.index_end.back();
    b.leaf_count = r.leaf_end.empty() ? 0 : r.leaf_end.back();
    b.steps = r.steps;
  }
  // One square cell fits the tree from every azimuth: the box's horizontal radius about its centre
  // line and its half height.
  const glm::vec3 lo = m ? m->bounds_min : r.bounds_min, hi = m ? m->bounds_max : r.bounds_max;
  a.centre = 0.5f * (lo + hi);
  const float half = 1.02f * std::max(0.5f * glm::length(glm::vec2(hi.x - lo.x, hi.z - lo.z)), 0.5f * (hi.y - lo.y));
  a.cell_metres = 2 * half;
  if (check_gl("impostor begin")) return fail("GL error while preparing the impostor atlas: " + gl_last_message());
  b.st = impostor_build::state::rendering;
  const double ms = ms_since(start);
  b.ms = ms;
  b.worst_step_ms = ms;
  return "";
}

bool impostor_step(impostor_build& b, renderer_gpu& r) {
  using st = impostor_build::state;
  if (b.st != st::rendering) return b.st != st::idle;
  const auto start = std::chrono::steady_clock::now();
  impostor_atlas& a = b.atlas;
  glBindFramebuffer(GL_FRAMEBUFFER, b.fbo.id);
  const GLenum targets[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
  glDrawBuffers(2, targets);
  if (b.next < a.views) {
    glDisable(GL_SCISSOR_TEST);
    glDisable(GL_BLEND);
    glDisable(GL_CULL_FACE);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    const int k = b.next++;
    const float half = 0.5f * a.cell_metres, far = 4 * half + 1;
    const float az = 6.2831853f * float(k) / float(a.views);
    const glm::vec3 dir(std::sin(az), 0, std::cos(az));   // toward the camera
    const glm::mat4 view = glm::lookAt(a.centre + dir * (2 * half + 0.5f), a.centre, glm::vec3(0, 1, 0));
    const glm::mat4 proj = glm::ortho(-half, half, -half, half, 0.01f, far);
    const glm::mat4 vp = proj * view;
    const int col = k % a.columns, row = k / a.columns;
    glViewport(col * a.cell, (a.rows - 1 - row) * a.cell, a.cell, a.cell);   // row 0 at the image's top
    if (b.bark_count) {
      glUseProgram(b.bark.id);
      set_uniform(b.bark, "u_viewproj", vp);
      set_uniform(b.bark, "u_bark", 0);
      set_bark_tint_uniforms(b.bark, b.rp);
      glActiveTexture(GL_TEXTURE0);
      glBindTexture(GL_TEXTURE_2D, r.bark_tex.id);
      glBindVertexArray(b.own_mesh ? b.bark_vao.id : r.bark_vao.id);
      glDrawElements(GL_TRIANGLES, GLsizei(b.bark_count), GL_UNSIGNED_INT, nullptr);
    }
    if (b.leaf_count) {
      glUseProgram(b.leaf.id);
      set_uniform(b.leaf, "u_viewproj", vp);
      set_uniform(b.leaf, "u_leaf", 1);
      set_uniform(b.leaf, "u_tint", b.rp.leaf_color);
      set_uniform(b.leaf, "u_cutoff", b.rp.alpha_cutoff);
      set_uniform(b.leaf, "u_step", b.steps);
      set_uniform(b.leaf, "u_layers", std::max(r.leaf_layers, 1));
      glActiveTexture(GL_TEXTURE1);
      glBindTexture(GL_TEXTURE_2D_ARRAY, r.leaf_tex.id);
      glBindVertexArray(b.own_mesh ? b.leaf_vao.id : r.leaf_vao.id);
      glDrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, GLsizei(b.leaf_count));
    }
    glBindVertexArray(0);
    glActiveTexture(GL_TEXTURE0);
    glFinish();   // the view's work lands in this step, not in the next frame's
  } else {
    // Read back, flipping GL's bottom-up rows.
    auto read = [&](GLenum attachment, std::vector<unsigned char>& out) {
      glReadBuffer(attachment);
      out = read_back_rgba(0, 0, a.width, a.height).pixels;
    };
    read(GL_COLOR_ATTACHMENT0, a.color);
    read(GL_COLOR_ATTACHMENT1, a.normal);
    if (check_gl("impostor atlas")) a.error = "GL error while rendering the impostor atlas: " + gl_last_message();
    free_build(b);
    b.st = a.error.empty() ? st::complete : st::failed;
  }
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  const double ms = ms_since(start);
  b.ms += ms;
  b.worst_step_ms = std::max(b.worst_step_ms, ms);
  a.ms = b.ms;
  return b.st != st::rendering;
}

void impostor_cancel(impostor_build& b) {
  free_build(b);
  b.st = impostor_build::state::idle;
  b.next = 0;
}

impostor_atlas render_impostor(renderer_gpu& r, const render_params& rp, int views, int cell) {
  impostor_build b;
  if (impostor_begin(b, r, rp, views, cell, nullptr).empty())
    while (!impostor_step(b, r)) {
    }
  impostor_atlas a = std::move(b.atlas);
  impostor_cancel(b);
  return a;
}

std::string impostor_pngs(const impostor_atlas& a, std::string& color_png, std::string& normal_png) {
  image img;
  img.width = a.width;
  img.height = a.height;
  img.channels = 4;
  img.pixels.assign(a.color.begin(), a.color.end());
  if (std::string e = encode_png(img, color_png); !e.empty()) return e;
  img.pixels.assign(a.normal.begin(), a.normal.end());
  return encode_png(img, normal_png);
}

std::shared_ptr<const baked_card_textures> impostor_layers(const impostor_atlas& a) {
  auto out = std::make_shared<baked_card_textures>();
  if (a.views <= 0 || a.cell <= 0 || a.color.size() != size_t(a.width) * size_t(a.height) * 4 || a.normal.size() != a.color.size())
    return out;
  for (int k = 0; k < a.views; ++k) {
    const float az = 6.2831853f * float(k) / float(a.views);
    // View k's card frame: x to the image's right, y up, z toward the camera (render_impostor's camera).
    const glm::vec3 x(std::cos(az), 0, -std::sin(az)), y(0, 1, 0), z(std::sin(az), 0, std::cos(az));
    leaf_texture_set set;
    for (image* im : {&set.color, &set.normal, &set.thickness}) {
      im->width = im->height = a.cell;
      im->channels = im == &set.color ? 4 : 3;
      im->pixels.assign(size_t(a.cell) * size_t(a.cell) * size_t(im->channels), 0);   // thickness 0: no glow through
    }
    const int x0 = (k % a.columns) * a.cell, y0 = (k / a.columns) * a.cell;
    for (int j = 0; j < a.cell; ++j)
      for (int i = 0; i < a.cell; ++i) {
        const size_t from = (size_t(y0 + j) * size_t(a.width) + size_t(x0 + i)) * 4, to = size_t(j) * size_t(a.cell) + size_t(i);
        std::copy_n(a.color.begin() + std::ptrdiff_t(from), 4, set.color.pixels.begin() + std::ptrdiff_t(to * 4));
        glm::vec3 n = glm::vec3(a.normal[from], a.normal[from + 1], a.normal[from + 2]) / 127.5f - 1.0f;
        glm::vec3 t(glm::dot(n, x), glm::dot(n, y), glm::dot(n, z));
        t = a.normal[from + 3] >= 128 && glm::length(t) > 0.1f ? glm::normalize(t) : glm::vec3(0, 0, 1);
        for (int c = 0; c < 3; ++c) set.normal.pixels[to * 3 + size_t(c)] = uint8_t(std::clamp((t[c] + 1.0f) * 127.5f, 0.0f, 255.0f));
      }
    out->sets.push_back(std::move(set));
    out->source.push_back(255);   // never deciduous: the atlas holds final colours
  }
  return out;
}

int impostor_view(const impostor_atlas& a, float azimuth_deg) {
  const int views = std::max(a.views, 1);
  const float step = 360.0f / float(views);
  const int k = int(std::lround((std::isfinite(azimuth_deg) ? azimuth_deg : 0.0f) / step));
  return ((k % views) + views) % views;
}

tree_mesh impostor_mesh(const impostor_atlas& a, std::shared_ptr<const baked_card_textures> layers, const tree_mesh& like,
                        float azimuth_deg, float sun_azimuth_deg) {
  tree_mesh m;
  m.steps = like.steps;
  m.radial_segments = like.radial_segments;
  m.final_radius = like.final_radius;
  m.bounds_min = like.bounds_min;
  m.bounds_max = like.bounds_max;
  m.index_end.assign(size_t(std::max(like.steps, 0)) + 1, 0);
  m.leaf_end.assign(size_t(std::max(like.steps, 0)) + 1, 0);
  if (a.views <= 0 || !layers || layers->sets.size() != size_t(a.views)) return m;
  auto card = [&](float az, int flag) {
    const float half = 0.5f * glm::radians(std::isfinite(az) ? az : 0.0f);
    leaf_instance l{};
    l.orientation = glm::vec4(0, std::sin(half), 0, std::cos(half));   // about +Y: the card's +Z to the azimuth
    l.size = a.cell_metres;
    l.position = a.centre - glm::vec3(0, 0.5f * a.cell_metres, 0);   // the petiole point: the bottom edge's centre
    l.born = 0;
    l.died = 0xffff;
    l.node = 0;
    l.texture = uint8_t(impostor_texture_base + flag + leaf_archetype_count + impostor_view(a, az));
    l.occlusion = 255;
    m.leaves.push_back(l);
  };
  card(azimuth_deg, 0);
  card(sun_azimuth_deg, impostor_sun_card);
  for (uint32_t& e : m.leaf_end) e = 2;
  m.cards = std::move(layers);
  return m;
}

float impostor_sun_azimuth(const render_params& rp) {
  const glm::vec3 s = sun_direction(rp);
  return glm::degrees(std::atan2(s.x, s.z));
}

}  // namespace sylva
