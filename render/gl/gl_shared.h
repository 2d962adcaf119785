// What every renderer in one GL context shares: the compiled programs and the procedural
// textures, the leaf archetypes' arrays and each bark archetype's maps (uploaded on first use).
// The editor's view, its slot B and the library's thumbnails draw in one context, so each program
// is compiled once there: the first renderer makes the set (init_renderer with no set to share),
// the others are given it, and the last one to be destroyed frees it. Main thread only.
#pragma once

#include <array>
#include <memory>
#include <string>

#include "generators/archetypes.h"
#include "render/gl/gl_util.h"

namespace sylva {

struct gl_shared {
  // The frame's programs (render/gl/shaders.h), the overlays' (render/gl/overlays.h) and, compiled
  // by the first impostor atlas, the atlas's (render/gl/impostor.h).
  gl_program bark, bark_depth, leaf, leaf_depth, sky, ground, occlusion, radial, march, exposure, composite, fallback, overlay;
  gl_program impostor_bark, impostor_leaf;
  bool ok = false;
  std::string error;   // why a program every frame needs failed
  // The leaf archetypes' colour, normal and thickness arrays (layer k: archetype k).
  gl_texture leaf_color, leaf_normal, leaf_thickness;
  int leaf_layers = 0;   // 0 until uploaded
  // Each bark archetype's colour, normal and roughness maps (ids 0 until first used).
  struct bark_maps {
    gl_texture color, normal, roughness;
  };
  std::array<bark_maps, bark_archetype_count> bark_sets;
  int users = 0;       // renderers holding the set (for tests and the startup count)
};

// Compiles every program of the frame and the overlays. Needs a current GL 3.3 core context.
std::shared_ptr<gl_shared> make_gl_shared();
// Frees the set's GL objects (its context current): by the last renderer that holds it.
void free_gl_shared(gl_shared& s);

}  // namespace sylva
