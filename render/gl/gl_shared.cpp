// One GL context's programs and procedural textures (render/gl/gl_shared.h).
#include "render/gl/gl_shared.h"

#include "render/gl/overlays.h"
#include "render/gl/shaders.h"
#include "render/gl/wind_gl.h"
#include "render/mesh/leaf_blade.h"
#include "render/mesh/leaf_shoot.h"

namespace sylva {

using namespace glsl;

namespace {

// The leaf vertex shader's blade table sizes (render/mesh/leaf_blade.h), after its #version line.
std::string with_blade_sizes(std::string s) {
  const size_t eol = s.find('\n');
  const std::string sizes = "const int BLADE_VERTICES = " + std::to_string(coarse_blade_vertices) +
                            ";\nconst int BLADE_PROTOTYPES = " + std::to_string(blade_prototypes) +
                            ";\nconst int SHOOT_VERTICES = " + std::to_string(shoot_vertices_coarse) + ";\n";
  return eol == std::string::npos ? s : s.substr(0, eol + 1) + sizes + s.substr(eol + 1);
}

}  // namespace

std::shared_ptr<gl_shared> make_gl_shared() {
  auto s = std::make_shared<gl_shared>();
  const std::string bark_fs = lit_source((std::string(bark_tint_glsl) + bark_fs_body).c_str()), leaf_fs = lit_source(leaf_fs_body),
                    ground_fs = lit_source(ground_fs_body), sky_fs = sky_source(sky_fs_body),
                    occ_fs = sky_source(occlusion_fs_body);
  const std::string bark_vs_wind = with_wind_glsl(bark_vs), leaf_vs_wind = with_blade_sizes(with_wind_glsl(leaf_vs));
  s->bark = compile_program("bark", bark_vs_wind.c_str(), bark_fs.c_str());
  s->bark_depth = compile_program("bark depth", bark_vs_wind.c_str(), depth_fs);
  s->leaf = compile_program("leaf", leaf_vs_wind.c_str(), leaf_fs.c_str());
  s->leaf_depth = compile_program("leaf depth", leaf_vs_wind.c_str(), leaf_depth_fs);
  s->sky = compile_program("sky", fullscreen_vs, sky_fs.c_str());
  s->ground = compile_program("ground", ground_vs, ground_fs.c_str());
  s->occlusion = compile_program("occlusion", fullscreen_vs, occ_fs.c_str());
  s->radial = compile_program("radial blur", fullscreen_vs, radial_fs);
  s->march = compile_program("light shafts", fullscreen_vs, march_source().c_str());
  s->exposure = compile_program("auto exposure", fullscreen_vs, exposure_fs);
  s->composite = compile_program("composite", fullscreen_vs, sky_source(composite_fs_body).c_str());
  s->overlay = compile_overlay_program();
  s->fallback = compile_program("fallback", bark_vs_wind.c_str(), fallback_fs);
  s->ok = !s->composite.failed && !s->fallback.failed;
  if (!s->ok) s->error = "renderer: " + gl_last_message();
  return s;
}

void free_gl_shared(gl_shared& s) {
  for (gl_program* p : {&s.bark, &s.bark_depth, &s.leaf, &s.leaf_depth, &s.sky, &s.ground, &s.occlusion, &s.radial, &s.march,
                        &s.exposure, &s.composite, &s.fallback, &s.overlay, &s.impostor_bark, &s.impostor_leaf})
    delete_gl(*p);
  for (gl_texture* t : {&s.leaf_color, &s.leaf_normal, &s.leaf_thickness}) delete_gl(*t);
  s.leaf_layers = 0;
  for (gl_shared::bark_maps& b : s.bark_sets)
    for (gl_texture* t : {&b.color, &b.normal, &b.roughness}) delete_gl(*t);
  s.ok = false;
}

}  // namespace sylva
