// Growth-debug overlays on the CPU: kinds and step windows (overlay_geometry.h).
#include "render/mesh/overlay_geometry.h"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace sylva {

namespace {

overlay_vertex vertex(const glm::vec3& p, const glm::vec3& c, overlay_kind k, float born = 0,
                      float died = overlay_forever, float size = 4) {
  return overlay_vertex{p, c, float(k), born, died, size};
}

overlay_kind line_overlay(debug_kind k) {
  switch (k) {
    case debug_kind::influence_link: return overlay_influence;
    case debug_kind::envelope_edge: return overlay_envelope;
    case debug_kind::guide_arrow: return overlay_guides;
    default: return overlay_graph;
  }
}

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

void fit_shadow_slice(overlay_view& v, const overlay_ranges& r) {
  if (v.slice_height < 0 || v.slice_height > r.shadow_max_y || v.slice_height < r.shadow_min_y)
    v.slice_height = 0.5f * (r.shadow_min_y + r.shadow_max_y);
}

overlay_geometry build_overlays(const growth_debug& d, const tree_skeleton* t) {
  assert(d.point_kind.size() == d.points.size() && "growth_debug: one kind per point");
  assert(d.line_kind.size() == d.lines.size() / 2 && "growth_debug: one kind per line");
  overlay_geometry g;
  const float last = t ? float(t->steps) : 0.0f;

  for (size_t i = 0; i + 1 < d.lines.size(); i += 2) {
    const glm::vec3 c = i / 2 < d.line_color.size() ? d.line_color[i / 2] : glm::vec3(1, 0.8f, 0.2f);
    const debug_kind dk = i / 2 < d.line_kind.size() ? d.line_kind[i / 2] : debug_kind::graph_edge;
    const overlay_kind k = line_overlay(dk);
    const float born = dk == debug_kind::influence_link ? last : 0.0f;   // only the last iteration's links
    g.lines.push_back(vertex(d.lines[i], c, k, born));
    g.lines.push_back(vertex(d.lines[i + 1], c, k, born));
  }

  auto kind_of = [&](size_t i) { return i < d.point_kind.size() ? d.point_kind[i] : debug_kind::marker; };
  float max_shade = 0;
  for (size_t i = 0; i < d.points.size() && i < d.point_value.size(); ++i)
    if (kind_of(i) == debug_kind::shadow_sample) max_shade = std::max(max_shade, d.point_value[i]);
  std::vector<float> shadow_ys;
  float gv_step = 1;   // guiding vectors: sources precede their step's endpoints
  for (size_t i = 0; i < d.points.size(); ++i) {
    const float v = i < d.point_value.size() ? d.point_value[i] : 0.0f;
    const glm::vec3& p = d.points[i];
    switch (kind_of(i)) {
      case debug_kind::shadow_sample:   // shade relative to the densest voxel
        g.points.push_back(vertex(p, overlay_ramp(max_shade > 0 ? v / max_shade : 0), overlay_shadow_grid, 0,
                                  overlay_forever, 3));
        shadow_ys.push_back(p.y);
        break;
      case debug_kind::source:   // a source of the coming step
        g.points.push_back(vertex(p, overlay_source_colour, overlay_endpoints, gv_step, gv_step + 1, 5));
        break;
      case debug_kind::endpoint:   // an endpoint of step v
        gv_step = v + 1;
        g.points.push_back(vertex(p, overlay_endpoint_colour, overlay_endpoints, v, v + 1, 7));
        break;
      default:   // a marker: alive to the end (v < 0), or killed in step v and shown red in it
        if (v < 0) {
          g.points.push_back(vertex(p, overlay_marker_colour, overlay_markers));
        } else {
          g.points.push_back(vertex(p, overlay_marker_colour, overlay_markers, 0, v));
          g.points.push_back(vertex(p, overlay_killed_colour, overlay_killed, v, v + 1, 6));
        }
        break;
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

  if (t) {
    const size_t n = std::min(d.node_fate.size(), t->size());
    for (size_t i = 0; i < n; ++i) {   // fates are those of the last step; shed nodes from their shedding on
      const int f = std::min<int>(d.node_fate[i], 2);
      const float born = f == 2 && t->died[i] != never_died ? float(t->died[i]) : last;
      g.points.push_back(vertex(t->position[i], overlay_fate_colour[f], overlay_fates, born, overlay_forever, 5));
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
        g.points.push_back(vertex(mid, overlay_ramp(x), overlay_flow, last, overlay_forever, 2 + 14 * x));
      }
    g.max_flow = max_flow;
  }
  for (const overlay_vertex& v : g.lines) g.present |= 1u << int(v.kind);
  for (const overlay_vertex& v : g.points) g.present |= 1u << int(v.kind);
  return g;
}

}  // namespace sylva
