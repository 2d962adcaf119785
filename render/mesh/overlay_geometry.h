// Growth-debug overlays on the CPU: growth_debug split into kinds with their step windows. Built on
// the growth worker with the rest of a result; render/gl/overlays.h only uploads and draws them.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "generators/skeleton.h"

namespace sylva {

// One toggle each in the editor's View menu. The index is the bit in overlay_view::kinds.
enum overlay_kind : int {
  overlay_shadow_grid,    // self-organizing: shadow values s of the sparse grid (Palubicki 2009 §4)
  overlay_markers,        // attraction points / markers alive at the step
  overlay_killed,         // attraction points killed in exactly this step (Runions 2007 §3)
  overlay_influence,      // point → node influence links of the last iteration
  overlay_envelope,       // the crown envelope's outline
  overlay_graph,          // guiding vectors: Yao-8 graph edges near the tree (Xu & Mould 2015)
  overlay_guides,         // guiding vectors g_u as short arrows
  overlay_endpoints,      // guiding vectors: the step's sources and endpoints
  overlay_fates,          // bud fate per node: grew / dormant / shed
  overlay_flow,           // resource flow per internode, as point size and colour
  overlay_kind_count
};
inline constexpr const char* overlay_kind_labels[] = {
    "Shadow grid",   "Attraction points", "Killed this step", "Influence links", "Envelope outline",
    "Graph edges",   "Guiding vectors",   "Sources / endpoints", "Bud fates",     "Resource flow", nullptr};

// What the user chose to see; render state only (never part of a preset). One layer at a time
// by default (overlay_default_kind for the generator); `combine` lets several show together.
struct overlay_view {
  uint32_t kinds = 1u << overlay_shadow_grid;
  bool combine = false;
  bool shadow_slice = true;    // one horizontal layer of the shadow grid, not the whole cloud
  float slice_height = -1;     // metres; < 0: the middle of the grid once it is known
};

// High-contrast colours that read against both the sky and the ground.
glm::vec3 overlay_ramp(float x);   // low to high: deep violet, magenta, orange, yellow (plasma-like)
inline const glm::vec3 overlay_marker_colour(1.0f, 0.25f, 0.95f), overlay_killed_colour(1.0f, 0.1f, 0.05f),
    overlay_source_colour(0.0f, 0.85f, 1.0f), overlay_endpoint_colour(1.0f, 0.55f, 0.0f);
inline const glm::vec3 overlay_fate_colour[3] = {{0.0f, 0.9f, 1.0f}, {0.25f, 0.1f, 0.6f}, {1.0f, 0.1f, 0.05f}};  // grew, dormant, shed

// The layer shown first for a generator's tree (the tree_spec index): the one its paper is about.
int overlay_default_kind(int generator, uint32_t present);

// Visible while born <= step < died (died = overlay_forever for "to the end").
inline constexpr float overlay_forever = 1e9f;
struct overlay_vertex {
  glm::vec3 position{0};
  glm::vec3 color{1};
  float kind = 0, born = 0, died = overlay_forever, size = 4;   // size: point diameter in pixels
};

// What the View menu, the legend and the shadow slice need to know of a tree's overlays.
struct overlay_ranges {
  float shadow_layer = 0;               // vertical spacing of the shadow grid's layers (0: none)
  float shadow_min_y = 0, shadow_max_y = 0;
  float max_shade = 0, max_flow = 0;    // the ramps' top values, for the legend
  uint32_t present = 0;                 // bit k: some vertex of kind k exists
};

struct overlay_geometry : overlay_ranges {
  std::vector<overlay_vertex> lines;    // pairs
  std::vector<overlay_vertex> points;
};

// Puts the shadow slice in the middle of the grid when it lies outside it (or is not set yet).
void fit_shadow_slice(overlay_view& v, const overlay_ranges& r);

// Splits a generator's debug output into overlay kinds by each item's debug_kind. `t` (may be null)
// supplies node positions for fates and flow and the last step for the last-iteration layers.
overlay_geometry build_overlays(const growth_debug& d, const tree_skeleton* t);

}  // namespace sylva
