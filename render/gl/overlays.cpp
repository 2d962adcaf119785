// Growth-debug overlays: kinds, step windows and the one program that draws them.
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

overlay_vertex vertex(const glm::vec3& p, const glm::vec3& c, overlay_kind k, float born = 0,
                      float died = overlay_forever, float size = 4) {
  return overlay_vertex{p, c, float(k), born, died, size};
}

glm::vec3 ramp(float x) { return overlay_ramp(x); }
const glm::vec3 &marker_colour = overlay_marker_colour, &killed_colour = overlay_killed_colour,
                &source_colour = overlay_source_colour, &endpoint_colour = overlay_endpoint_colour;
const glm::vec3* const fate_colour = overlay_fate_colour;

}  // namespace

// Neither blue nor green, the sky's and the ground's colours, at any value.
glm::vec3 overlay_ramp(float x) {
  x = std::clamp(x, 0.0f, 1.0f);
  const glm::vec3 stops[4] = {{0.28f, 0.0f, 0.65f}, {0.85f, 0.1f, 0.6f}, {1.0f, 0.5f, 0.05f}, {1.0f, 0.95f, 0.1f}};
  const float f = x * 3;
  const int i = std::min(int(f), 2);
  return glm::mix(stops[i], stops[i + 1], f - float(i));
}

int overlay_default_kind(int generator, uint32_t present) {
  static const int order[4][4] = {{overlay_shadow_grid, overlay_fates, overlay_flow, overlay_markers},
                                  {overlay_markers, overlay_killed, overlay_influence, overlay_envelope},
                                  {overlay_guides, overlay_endpoints, overlay_graph, overlay_fates},
                                  {overlay_markers, overlay_fates, overlay_flow, overlay_graph}};
  if (generator >= 0 && generator < 4)
    for (int k : order[generator])
      if ((present >> k) & 1u) return k;
  for (int k = 0; k < overlay_kind_count; ++k)
    if ((present >> k) & 1u) return k;
  return overlay_shadow_grid;
}

overlay_geometry build_overlays(const growth_debug& d, const tree_skeleton* t, int generator) {
  overlay_geometry g;
  const float last = t ? float(t->steps) : 0.0f;

  // Lines: the generators colour their layers distinctly; the generator tells which is which.
  for (size_t i = 0; i + 1 < d.lines.size(); i += 2) {
    const glm::vec3 c = i / 2 < d.line_color.size() ? d.line_color[i / 2] : glm::vec3(1, 0.8f, 0.2f);
    overlay_kind k = overlay_graph;
    float born = 0;
    if (generator == 1) {          // space colonization: blue outline, warm influence links
      k = c.z > 0.5f ? overlay_envelope : overlay_influence;
      if (k == overlay_influence) born = last;   // only the last iteration's links are recorded
    } else if (generator == 2) {   // guiding vectors: grey graph edges, orange arrows
      k = (c.x == c.y && c.y == c.z) ? overlay_graph : overlay_guides;
    }
    g.lines.push_back(vertex(d.lines[i], c, k, born));
    g.lines.push_back(vertex(d.lines[i + 1], c, k, born));
  }

  // Points: point_value means a different thing per generator (growth_debug's comment).
  float max_shade = 0;
  if (generator == 0)
    for (float v : d.point_value) max_shade = std::max(max_shade, v);
  std::vector<float> shadow_ys;
  float gv_step = 1;   // guiding vectors: sources precede their step's endpoints
  for (size_t i = 0; i < d.points.size(); ++i) {
    const float v = i < d.point_value.size() ? d.point_value[i] : 0.0f;
    const glm::vec3& p = d.points[i];
    if (generator == 0) {
      if (v < 0) {
        g.points.push_back(vertex(p, marker_colour, overlay_markers));
      } else {   // shade relative to the densest voxel: light blue to saturated yellow
        g.points.push_back(vertex(p, ramp(max_shade > 0 ? v / max_shade : 0), overlay_shadow_grid, 0, overlay_forever, 3));
        shadow_ys.push_back(p.y);
      }
    } else if (generator == 1) {   // v = the step in which the point was killed, -1 alive at the end
      if (v < 0) {
        g.points.push_back(vertex(p, marker_colour, overlay_markers));
      } else {
        g.points.push_back(vertex(p, marker_colour, overlay_markers, 0, v));
        g.points.push_back(vertex(p, killed_colour, overlay_killed, v, v + 1, 6));
      }
    } else if (generator == 2) {   // v = 0: a source of the coming step; v = k: an endpoint of step k
      if (v <= 0) {
        g.points.push_back(vertex(p, source_colour, overlay_endpoints, gv_step, gv_step + 1, 5));
      } else {
        gv_step = v + 1;
        g.points.push_back(vertex(p, endpoint_colour, overlay_endpoints, v, v + 1, 7));
      }
    } else {
      const glm::vec3 c = v < 0 ? glm::vec3(1, 0.2f, 0.9f) : ramp(v);
      g.points.push_back(vertex(p, c, overlay_markers));
    }
  }
  if (!shadow_ys.empty()) {
    std::sort(shadow_ys.begin(), shadow_ys.end());
    g.shadow_min_y = shadow_ys.front();
    g.shadow_max_y = shadow_ys.back();
    float gap = 0;
    for (size_t i = 1; i < shadow_ys.size(); ++i) {
      const float dy = shadow_ys[i] - shadow_ys[i - 1];
      if (dy > 1e-6f && (gap == 0 || dy < gap)) gap = dy;
    }
    g.shadow_layer = gap;
  }

  g.max_shade = max_shade;
  auto mark_present = [&] {
    for (const overlay_vertex& v : g.lines) g.present |= 1u << int(v.kind);
    for (const overlay_vertex& v : g.points) g.present |= 1u << int(v.kind);
  };
  if (!t) {
    mark_present();
    return g;
  }
  const size_t n = std::min(d.node_fate.size(), t->size());
  for (size_t i = 0; i < n; ++i) {   // fates are those of the last step; shed nodes from their shedding on
    const int f = std::min<int>(d.node_fate[i], 2);
    const float born = f == 2 && t->died[i] != never_died ? float(t->died[i]) : last;
    g.points.push_back(vertex(t->position[i], fate_colour[f], overlay_fates, born, overlay_forever, 5));
  }
  float max_flow = 0;
  const size_t nf = std::min(d.node_flow.size(), t->size());
  for (size_t i = 0; i < nf; ++i)
    if (std::isfinite(d.node_flow[i])) max_flow = std::max(max_flow, d.node_flow[i]);
  if (max_flow > 0)
    for (size_t i = 0; i < nf; ++i) {
      const float f = d.node_flow[i];
      if (!(f > 0) || t->parent[i] < 0) continue;
      // Area ∝ flow, as a pipe's cross-section carries flow: diameter ∝ √flow.
      const float x = std::sqrt(f / max_flow);
      const glm::vec3 mid = 0.5f * (t->position[i] + t->position[size_t(t->parent[i])]);
      g.points.push_back(vertex(mid, ramp(x), overlay_flow, last, overlay_forever, 2 + 14 * x));
    }
  g.max_flow = max_flow;
  mark_present();
  return g;
}

bool init_overlays(overlay_gpu& g) {
  g.program = compile_program("overlays", overlay_vs, overlay_fs);
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
  return !g.program.failed;
}

void destroy_overlays(overlay_gpu& g) {
  delete_gl(g.program);
  delete_gl(g.vao);
  delete_gl(g.vertices);
  g.line_vertices = g.point_vertices = 0;
}

void upload_overlays(overlay_gpu& g, const overlay_geometry& geo) {
  static_assert(sizeof(overlay_vertex) == 10 * sizeof(float), "tightly packed vertex");
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
  g.shadow_layer = geo.shadow_layer;
  g.shadow_min_y = geo.shadow_min_y;
  g.shadow_max_y = geo.shadow_max_y;
  g.max_shade = geo.max_shade;
  g.max_flow = geo.max_flow;
  g.present = geo.present;
  if (g.view.slice_height < 0 || g.view.slice_height > g.shadow_max_y || g.view.slice_height < g.shadow_min_y)
    g.view.slice_height = 0.5f * (g.shadow_min_y + g.shadow_max_y);
  check_gl("upload overlays");
}

int draw_overlays(const overlay_gpu& g, const glm::mat4& viewproj, int step) {
  if (g.program.failed || g.line_vertices + g.point_vertices == 0 || g.view.kinds == 0) return 0;
  glUseProgram(g.program.id);
  set_uniform(g.program, "u_viewproj", viewproj);
  set_uniform(g.program, "u_kinds", int(g.view.kinds));
  set_uniform(g.program, "u_step", float(step));
  set_uniform(g.program, "u_slice", g.view.shadow_slice ? 1 : 0);
  set_uniform(g.program, "u_slice_y", g.view.slice_height);
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
