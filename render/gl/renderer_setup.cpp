// The renderer's lifetime (programs, buffers, textures) and the tree upload (render/gl/renderer.h).
#include "render/gl/renderer_resources.h"
#include "render/mesh/leaf_shading.h"
#include "render/gl/renderer.h"
#include "render/gl/shaders.h"
#include "render/gl/renderer_resources.h"

#include "generators/wood.h"
#include "render/gl/wind_gl.h"
#include "render/mesh/leaf_shoot.h"
#include "render/mesh/lod_cards.h"
#include "render/mesh/season.h"
#include "render/assets/textures.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstddef>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

namespace sylva {

using namespace glsl;

// ---------------------------------------------------------------- lifetime

// The per-instance attributes 1-7 of a leaf card, from the bound GL_ARRAY_BUFFER of leaf_instance
// records (one per instance); attribute 0 is the card's corner. Shared by the renderer and the
// impostor's atlas pass.
void leaf_instance_attributes() {
  const GLsizei stride = sizeof(leaf_instance);
  glEnableVertexAttribArray(1);
  glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, stride, (void*)offsetof(leaf_instance, position));
  glEnableVertexAttribArray(2);
  glVertexAttribPointer(2, 4, GL_FLOAT, GL_FALSE, stride, (void*)offsetof(leaf_instance, orientation));
  glEnableVertexAttribArray(3);
  glVertexAttribPointer(3, 1, GL_FLOAT, GL_FALSE, stride, (void*)offsetof(leaf_instance, size));
  static_assert(offsetof(leaf_instance, died) == offsetof(leaf_instance, born) + 2, "born/died read as a pair");
  glEnableVertexAttribArray(4);
  glVertexAttribIPointer(4, 2, GL_UNSIGNED_SHORT, stride, (void*)offsetof(leaf_instance, born));
  glEnableVertexAttribArray(5);
  glVertexAttribIPointer(5, 1, GL_UNSIGNED_BYTE, stride, (void*)offsetof(leaf_instance, texture));
  glEnableVertexAttribArray(6);
  glVertexAttribPointer(6, 1, GL_UNSIGNED_BYTE, GL_TRUE, stride, (void*)offsetof(leaf_instance, occlusion));
  glEnableVertexAttribArray(7);
  glVertexAttribIPointer(7, 1, GL_UNSIGNED_INT, stride, (void*)offsetof(leaf_instance, node));
  for (int i = 1; i <= 7; ++i) glVertexAttribDivisor(i, 1);
}

bool init_renderer(renderer_gpu& r, std::shared_ptr<gl_shared> shared) {
  // The context's programs: compiled by its first renderer, given to the others.
  r.shared = shared ? std::move(shared) : make_gl_shared();
  ++r.shared->users;
  r.ok = r.shared->ok;
  r.error = r.shared->error;
  init_overlays(r.overlay, r.shared->overlay);

  glGenVertexArrays(1, &r.empty_vao.id);
  glGenVertexArrays(1, &r.bark_vao.id);
  glGenVertexArrays(1, &r.leaf_vao.id);
  for (gl_buffer* b : {&r.bark_position, &r.bark_normal, &r.bark_uv, &r.bark_node, &r.bark_ao, &r.bark_index,
                       &r.leaf_corner, &r.leaf_instances, &r.node_radius, &r.blade_index, &r.blade_table})
    glGenBuffers(1, &b->id);

  // Bark: one buffer per attribute, matching tree_mesh's arrays so upload is a straight copy.
  glBindVertexArray(r.bark_vao.id);
  glBindBuffer(GL_ARRAY_BUFFER, r.bark_position.id);
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 0, nullptr);
  glBindBuffer(GL_ARRAY_BUFFER, r.bark_normal.id);
  glEnableVertexAttribArray(1);
  glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, 0, nullptr);
  glBindBuffer(GL_ARRAY_BUFFER, r.bark_uv.id);
  glEnableVertexAttribArray(2);
  glVertexAttribPointer(2, 2, GL_FLOAT, GL_FALSE, 0, nullptr);
  glBindBuffer(GL_ARRAY_BUFFER, r.bark_node.id);
  glEnableVertexAttribArray(3);
  glVertexAttribIPointer(3, 1, GL_UNSIGNED_INT, 0, nullptr);
  glBindBuffer(GL_ARRAY_BUFFER, r.bark_ao.id);
  glVertexAttribPointer(4, 1, GL_FLOAT, GL_FALSE, 0, nullptr);   // enabled when a mesh brings its occlusion
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, r.bark_index.id);

  // Leaves: the coarse blade grid's triangles plus one leaf_instance per instance; the leaf shader looks
  // each grid vertex up in the blade table. Attribute 0 is the unit quad's corners for the impostor's
  // atlas pass (render/gl/impostor.cpp), padded to the grid's vertex count.
  float corners[2 * coarse_blade_vertices] = {-0.5f, 0, 0.5f, 0, -0.5f, 1, 0.5f, 1};
  glBindVertexArray(r.leaf_vao.id);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, r.blade_index.id);
  // The grid's triangles, then the flat card's two from the grid's corners (drawn when no leaf bends).
  std::vector<uint16_t> grid(coarse_blade_indices().begin(), coarse_blade_indices().end());
  constexpr uint16_t tip = coarse_blade_rows * (coarse_blade_columns + 1);
  grid.insert(grid.end(), {0, coarse_blade_columns, tip + coarse_blade_columns, 0, tip + coarse_blade_columns, tip});
  // Then the needle shoots' spikes (render/mesh/leaf_shoot.h), drawn by a second call.
  const std::vector<uint16_t> spikes = shoot_indices(shoot_pieces_coarse);
  grid.insert(grid.end(), spikes.begin(), spikes.end());
  glBufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(sizeof(uint16_t) * grid.size()), grid.data(), GL_STATIC_DRAW);
  glBindBuffer(GL_ARRAY_BUFFER, r.leaf_corner.id);
  glBufferData(GL_ARRAY_BUFFER, sizeof corners, corners, GL_STATIC_DRAW);
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, 0, nullptr);
  glBindBuffer(GL_ARRAY_BUFFER, r.leaf_instances.id);
  leaf_instance_attributes();

  glBindVertexArray(0);

  // Per-node radii for scrubbing, read in the vertex shader through a buffer texture.
  glGenTextures(1, &r.node_radius_tex.id);
  glBindBuffer(GL_TEXTURE_BUFFER, r.node_radius.id);
  glBufferData(GL_TEXTURE_BUFFER, 8, nullptr, GL_DYNAMIC_DRAW);
  glBindTexture(GL_TEXTURE_BUFFER, r.node_radius_tex.id);
  glTexBuffer(GL_TEXTURE_BUFFER, GL_RGBA32F, r.node_radius.id);
  glGenTextures(1, &r.blade_tex.id);
  glBindBuffer(GL_TEXTURE_BUFFER, r.blade_table.id);
  glBindTexture(GL_TEXTURE_BUFFER, r.blade_tex.id);
  glTexBuffer(GL_TEXTURE_BUFFER, GL_RGBA32F, r.blade_table.id);
  upload_blades(r, leaf_blade_shape{});

  // Procedural textures (render/assets/textures.h): the app needs no asset files. All archetype sets are
  // made once per process, on two threads, and uploaded once per context (gl_shared).
  prepare_archetype_textures(512, 1, 2);
  upload_procedural_bark(r, bark_archetype::furrowed);
  upload_procedural_leaves(r);

  resize_shadow(r, 2048);
  r.average_tex = make_color_target(1, 1, GL_RGBA16F);   // auto exposure's log-average luminance
  r.average_fbo = make_framebuffer(r.average_tex, {});
  check_gl("init renderer");
  return r.ok;
}

void destroy_renderer(renderer_gpu& r) {
  destroy_overlays(r.overlay);
  for (gl_vertex_array* v : {&r.bark_vao, &r.leaf_vao, &r.empty_vao}) delete_gl(*v);
  for (gl_buffer* b : {&r.bark_position, &r.bark_normal, &r.bark_uv, &r.bark_node, &r.bark_ao, &r.bark_index,
                       &r.leaf_corner, &r.leaf_instances, &r.node_radius, &r.wind_nodes, &r.blade_index, &r.blade_table})
    delete_gl(*b);
  delete_gl(r.wind_tex);
  r.wind_node_count = 0;
  // The tree's own textures; the shared procedural ones go with the context's set.
  release_tree_textures(r);
  for (gl_texture* t : {&r.node_radius_tex, &r.blade_tex, &r.shadow_tex, &r.hdr_color, &r.hdr_depth, &r.occlusion_tex, &r.rays_tex,
                        &r.march_tex, &r.average_tex})
    delete_gl(*t);
  for (gl_framebuffer* f : {&r.shadow_fbo, &r.hdr_fbo, &r.occlusion_fbo, &r.rays_fbo, &r.march_fbo, &r.average_fbo, &r.msaa_fbo})
    delete_gl(*f);
  delete_gl(r.msaa_color);
  delete_gl(r.msaa_depth);
  if (r.shared && --r.shared->users == 0) free_gl_shared(*r.shared);
  r.shared.reset();
  r.width = r.height = r.shadow_size = r.samples = 0;
  r.bark_shown = -1;
  r.leaf_layers = 1;
  r.sky_valid = false;
  r.user_bark = r.user_leaf = false;
  r.bark_texture_path.clear(), r.leaf_texture_path.clear(), r.leaf_opacity_path.clear();
  r.ok = false;
}

// ---------------------------------------------------------------- uploads

void upload_tree(renderer_gpu& r, const tree_mesh& m) {
  r.shadow_drawn = false;
  glBindVertexArray(0);
  glBindBuffer(GL_ARRAY_BUFFER, r.bark_position.id);
  glBufferData(GL_ARRAY_BUFFER, m.position.size() * sizeof(glm::vec3), m.position.data(), GL_STATIC_DRAW);
  glBindBuffer(GL_ARRAY_BUFFER, r.bark_normal.id);
  glBufferData(GL_ARRAY_BUFFER, m.normal.size() * sizeof(glm::vec3), m.normal.data(), GL_STATIC_DRAW);
  glBindBuffer(GL_ARRAY_BUFFER, r.bark_uv.id);
  glBufferData(GL_ARRAY_BUFFER, m.uv.size() * sizeof(glm::vec2), m.uv.data(), GL_STATIC_DRAW);
  glBindBuffer(GL_ARRAY_BUFFER, r.bark_node.id);
  glBufferData(GL_ARRAY_BUFFER, m.node.size() * sizeof(uint32_t), m.node.data(), GL_STATIC_DRAW);
  // Crown occlusion per vertex; a mesh without it (hand-made ones) reads a constant 1.
  const bool has_ao = m.occlusion.size() == m.position.size() && !m.position.empty();
  glBindBuffer(GL_ARRAY_BUFFER, r.bark_ao.id);
  glBufferData(GL_ARRAY_BUFFER, has_ao ? m.occlusion.size() * sizeof(float) : 4, has_ao ? m.occlusion.data() : nullptr,
               GL_STATIC_DRAW);
  glBindVertexArray(r.bark_vao.id);
  glBufferData(GL_ELEMENT_ARRAY_BUFFER, m.index.size() * sizeof(uint32_t), m.index.data(), GL_STATIC_DRAW);
  if (has_ao) {
    glEnableVertexAttribArray(4);
  } else {
    glDisableVertexAttribArray(4);
    glVertexAttrib1f(4, 1.0f);
  }
  glBindVertexArray(0);
  glBindBuffer(GL_ARRAY_BUFFER, r.leaf_instances.id);
  glBufferData(GL_ARRAY_BUFFER, m.leaves.size() * sizeof(leaf_instance), m.leaves.data(), GL_STATIC_DRAW);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  r.uploads_total += 7;

  if (m.cards) r.cards = m.cards;   // kept when LOD0 comes back: the layers stay valid
  r.index_end = m.index_end;
  r.leaf_end = m.leaf_end;
  r.has_shoots = std::any_of(m.leaves.begin(), m.leaves.end(),
                             [](const leaf_instance& l) { return l.texture < leaf_archetype_count && archetype_is_shoot(leaf_archetype(l.texture)); });
  upload_blades(r, m.blade);
  r.final_radius = m.final_radius;
  r.node_count = int(m.final_radius.size());
  r.radius_upload.assign(size_t(r.node_count) * 4, 0.0f);
  glBindBuffer(GL_TEXTURE_BUFFER, r.node_radius.id);
  glBufferData(GL_TEXTURE_BUFFER, std::max<size_t>(8, r.radius_upload.size() * sizeof(float)), nullptr, GL_DYNAMIC_DRAW);
  glBindBuffer(GL_TEXTURE_BUFFER, 0);
  ++r.uploads_total;
  r.wind_node_count = 0;   // the wind table belongs to the previous tree until upload_wind
  r.steps = m.steps;
  r.step = m.steps;
  r.has_tree = !m.index.empty() || !m.leaves.empty();
  if (r.has_tree) {
    r.bounds_min = m.bounds_min;
    const crown_ellipsoid crown = leaf_crown(m);
    r.crown_centre = crown.centre, r.crown_radii = crown.radii;
    r.bounds_max = m.bounds_max;
    // The trunk's base: the first ring of the bark (the root node's), where the ground meets it.
    const size_t ring = size_t(std::max(m.radial_segments, 1)) + 1;
    if (m.position.size() >= ring && !m.final_radius.empty()) {
      glm::vec3 c(0);
      for (size_t i = 0; i < ring; ++i) c += m.position[i];
      r.root = c / float(ring);
      r.root_radius = std::max(m.final_radius[0], 0.01f);
    } else {
      r.root = glm::vec3(0.5f * (m.bounds_min.x + m.bounds_max.x), 0, 0.5f * (m.bounds_min.z + m.bounds_max.z));
      r.root_radius = 0.05f;
    }
  } else {
    r.bounds_min = glm::vec3(-1, 0, -1);
    r.bounds_max = glm::vec3(1, 2, 1);
  }
  check_gl("upload tree");
}

void set_tree_step(renderer_gpu& r, const tree_skeleton& t, float min_radius, int step) {
  r.shadow_drawn = false;
  r.step = std::clamp(step, 0, std::max(r.steps, 0));
  if (r.node_count == 0) return;
  std::vector<float> radii = radii_at_step(t, r.step);
  // The bend of that step (generators/wood.h): replayed, never regrown; none when the tree is unbent.
  const std::vector<glm::vec3> x = t.wood ? positions_at_step(t, r.step) : std::vector<glm::vec3>();
  const size_t n = std::min(radii.size(), size_t(r.node_count));
  for (size_t i = 0; i < size_t(r.node_count); ++i) {
    const bool alive = i < n && i < t.size() && t.alive(i, r.step);
    const glm::vec3 d = alive && i < x.size() ? x[i] - t.position[i] : glm::vec3(0);
    r.radius_upload[4 * i] = d.x;
    r.radius_upload[4 * i + 1] = d.y;
    r.radius_upload[4 * i + 2] = d.z;
    r.radius_upload[4 * i + 3] = alive ? std::max(radii[i], min_radius) - r.final_radius[i] : -1e30f;
  }
  glBindBuffer(GL_TEXTURE_BUFFER, r.node_radius.id);
  glBufferSubData(GL_TEXTURE_BUFFER, 0, r.radius_upload.size() * sizeof(float), r.radius_upload.data());
  ++r.uploads_total;
  glBindBuffer(GL_TEXTURE_BUFFER, 0);
  check_gl("set tree step");
}


void set_overlays(renderer_gpu& r, std::shared_ptr<const overlay_geometry> g) { set_overlays(r.overlay, std::move(g)); }

}  // namespace sylva
