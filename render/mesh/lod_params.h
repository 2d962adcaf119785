// Level-of-detail settings, plain data saved in presets under "render" (render/mesh/lod.h).
#pragma once

#include "generators/params.h"

namespace sylva {

// Render-side settings (saved in presets under "render"): changing them never regrows or re-meshes.
struct lod_params {
  // Triangle budgets of LOD1..LOD3 in percent of LOD0 (defaults: 40 %, 15 %, 5 %).
  float lod1_budget = 40, lod2_budget = 15, lod3_budget = 5;
  // Viewport: log2 scale on the screen coverage before the level is picked (> 0: coarser sooner).
  float bias = 0;
  // Viewport: -1 picks the level by screen size; 0..3 always shows that LOD, 4 the impostor.
  int show = -1;
  int impostor_views = 8;       // billboard views around the trunk: 8 or 16
  int impostor_size = 512;      // pixels per view (square)
  bool operator==(const lod_params&) const = default;
};

template <params_of<lod_params> P, class V>
void visit_params(P& p, V&& visitor) {
  auto v = declare_class(visitor, param_render);   // LODs are built from the kept mesh
  v(p.lod1_budget, param_info{"lod1_budget", "LOD1 budget", "", 1, 100, "Triangles of LOD1 in percent of LOD0 (fewer radial segments, thin branches dropped, leaves merged into bigger cards)", 0, "Level of detail"});
  v(p.lod2_budget, param_info{"lod2_budget", "LOD2 budget", "", 1, 100, "Triangles of LOD2 in percent of LOD0"});
  v(p.lod3_budget, param_info{"lod3_budget", "LOD3 budget", "", 1, 100, "Triangles of LOD3 in percent of LOD0"});
  v(p.bias, param_info{"lod_bias", "LOD bias", "", -3, 3, "Viewport: shifts the switch distances (positive: coarser levels sooner, in powers of two of screen size)"});
  v(p.show, param_info{"lod_show", "Show LOD", "", -1, 4, "Viewport: -1 picks the level by screen size, 0-3 always shows that level, 4 the impostor"});
  v(p.impostor_views, param_info{"impostor_views", "Impostor views", "", 8, 16, "Billboard views around the tree in the impostor atlas (8 or 16)"});
  v(p.impostor_size, param_info{"impostor_size", "Impostor view size", "", 64, 2048, "Pixels per view in the impostor atlas", param_log});
}

}  // namespace sylva
