// Growth-debug overlays on the GPU: the one program that draws them (overlays.h).
#include "render/gl/overlays.h"

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace sylva {

namespace {

// Hidden vertices go outside the clip volume: GL core has no per-vertex discard, and a line whose
// two ends share one step window is then clipped whole. Points carry their own size, because GL
// 3.3 core (forward compatible, as on llvmpipe) rejects glLineWidth > 1: flow is drawn as point
// size and colour, not as line width.
const char* overlay_vs = R"(#version 330 core
layout(location = 0) in vec3 a_position; layout(location = 1) in vec3 a_color; layout(location = 2) in vec4 a_meta;
uniform mat4 u_viewproj; uniform int u_kinds; uniform float u_step;
uniform int u_slice; uniform float u_slice_y; uniform float u_slice_half;
out vec3 v_color;
void main() {
  int kind = int(a_meta.x + 0.5);
  bool show = ((u_kinds >> kind) & 1) != 0 && a_meta.y <= u_step && u_step < a_meta.z;
  if (kind == 0 && u_slice != 0 && abs(a_position.y - u_slice_y) > u_slice_half) show = false;
  v_color = a_color;
  gl_Position = show ? u_viewproj * vec4(a_position, 1.0) : vec4(2.0, 2.0, 2.0, 1.0);
  gl_PointSize = (kind == 0 && u_slice != 0) ? 3.0 * a_meta.w : a_meta.w;   // a slice shows cells, not a fog
}
)";
const char* overlay_fs = R"(#version 330 core
in vec3 v_color; out vec4 o_color;
void main() { o_color = vec4(v_color, 1.0); }
)";

}  // namespace

gl_program compile_overlay_program() { return compile_program("overlays", overlay_vs, overlay_fs); }

bool init_overlays(overlay_gpu& g, const gl_program& program) {
  g.program = program;
  glGenVertexArrays(1, &g.vao.id);
  glGenBuffers(1, &g.vertices.id);
  glBindVertexArray(g.vao.id);
  glBindBuffer(GL_ARRAY_BUFFER, g.vertices.id);
  constexpr GLsizei stride = sizeof(overlay_vertex);
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, stride, (void*)offsetof(overlay_vertex, position));
  glEnableVertexAttribArray(1);
  glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, stride, (void*)offsetof(overlay_vertex, color));
  glEnableVertexAttribArray(2);
  glVertexAttribPointer(2, 4, GL_FLOAT, GL_FALSE, stride, (void*)offsetof(overlay_vertex, kind));
  glBindVertexArray(0);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  g.stale = true;   // a new buffer: the geometry set before goes up again
  return !g.program.failed;
}

void destroy_overlays(overlay_gpu& g) {
  g.program = {};
  delete_gl(g.vao);
  delete_gl(g.vertices);
  g.line_vertices = g.point_vertices = 0;
}

void set_overlays(overlay_gpu& g, std::shared_ptr<const overlay_geometry> geo) {
  static_cast<overlay_ranges&>(g) = geo ? static_cast<const overlay_ranges&>(*geo) : overlay_ranges{};
  g.geometry = std::move(geo);
  g.stale = true;
}

bool sync_overlays(overlay_gpu& g) {
  static_assert(sizeof(overlay_vertex) == 10 * sizeof(float), "tightly packed vertex");
  if (!g.stale) return false;
  g.stale = false;
  static const overlay_geometry none;
  const overlay_geometry& geo = g.geometry ? *g.geometry : none;
  glBindBuffer(GL_ARRAY_BUFFER, g.vertices.id);
  const size_t n = geo.lines.size() + geo.points.size();
  glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(n * sizeof(overlay_vertex)), nullptr, GL_STATIC_DRAW);
  if (!geo.lines.empty())
    glBufferSubData(GL_ARRAY_BUFFER, 0, GLsizeiptr(geo.lines.size() * sizeof(overlay_vertex)), geo.lines.data());
  if (!geo.points.empty())
    glBufferSubData(GL_ARRAY_BUFFER, GLintptr(geo.lines.size() * sizeof(overlay_vertex)),
                    GLsizeiptr(geo.points.size() * sizeof(overlay_vertex)), geo.points.data());
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  g.line_vertices = int(geo.lines.size());
  g.point_vertices = int(geo.points.size());
  check_gl("upload overlays");
  return true;
}

int draw_overlays(const overlay_gpu& g, const overlay_view& v, const glm::mat4& viewproj, int step) {
  if (g.program.failed || g.line_vertices + g.point_vertices == 0 || v.kinds == 0) return 0;
  glUseProgram(g.program.id);
  set_uniform(g.program, "u_viewproj", viewproj);
  set_uniform(g.program, "u_kinds", int(v.kinds));
  set_uniform(g.program, "u_step", float(step));
  set_uniform(g.program, "u_slice", v.shadow_slice ? 1 : 0);
  set_uniform(g.program, "u_slice_y", v.slice_height);
  // One layer of voxels: half the spacing between layers (a sliver when the grid has one layer).
  set_uniform(g.program, "u_slice_half", g.shadow_layer > 0 ? 0.5f * g.shadow_layer : 1e-3f);
  glEnable(GL_PROGRAM_POINT_SIZE);
  glDepthFunc(GL_LEQUAL);
  glBindVertexArray(g.vao.id);
  int calls = 0;
  if (g.line_vertices) glDrawArrays(GL_LINES, 0, g.line_vertices), ++calls;
  if (g.point_vertices) glDrawArrays(GL_POINTS, g.line_vertices, g.point_vertices), ++calls;
  glDepthFunc(GL_LESS);
  glBindVertexArray(0);
  return calls;
}

}  // namespace sylva
