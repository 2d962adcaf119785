// The renderer's textures and render targets (render/gl/renderer_resources.h).
#include "render/gl/renderer_resources.h"
#include "render/gl/renderer.h"
#include "render/gl/shaders.h"

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

namespace {

void upload_2d(gl_texture& t, const image& img, GLenum internal_format) {
  if (!t.id) glGenTextures(1, &t.id);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glBindTexture(GL_TEXTURE_2D, t.id);
  glTexImage2D(GL_TEXTURE_2D, 0, internal_format, img.width, img.height, 0, img.channels == 3 ? GL_RGB : GL_RGBA,
               GL_UNSIGNED_BYTE, img.pixels.data());
  glGenerateMipmap(GL_TEXTURE_2D);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_REPEAT);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
}

// The user's bark: the tree's own maps, in place of the shared procedural ones.
void upload_bark_textures(renderer_gpu& r, const image& color, const image& normal, const image& rough) {
  if (!r.own_bark) r.bark_tex = r.bark_normal_tex = r.bark_rough_tex = {}, r.own_bark = true;
  upload_2d(r.bark_tex, color, GL_SRGB8_ALPHA8);
  upload_2d(r.bark_normal_tex, normal, GL_RGB8);
  upload_2d(r.bark_rough_tex, rough, GL_RGB8);
  r.uploads_total += 3;
}

// 2x2 box filter of an RGBA image (odd sizes keep their last row/column).
image half_size(const image& src) {
  const int w = std::max(1, src.width / 2), h = std::max(1, src.height / 2);
  image out{w, h, 4, std::vector<uint8_t>(size_t(w) * h * 4)};
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < 4; ++c) {
        int sum = 0;
        for (int j = 0; j < 2; ++j)
          for (int i = 0; i < 2; ++i) {
            const int sx = std::min(2 * x + i, src.width - 1), sy = std::min(2 * y + j, src.height - 1);
            sum += src.pixels[(size_t(sy) * src.width + sx) * 4 + c];
          }
        out.pixels[(size_t(y) * w + x) * 4 + c] = uint8_t((sum + 2) / 4);
      }
  return out;
}

double alpha_coverage(const image& img, float cutoff, float scale) {
  size_t n = 0;
  const float limit = cutoff * 255.0f;
  for (size_t k = 0; k < size_t(img.width) * img.height; ++k) n += float(img.pixels[k * 4 + 3]) * scale >= limit;
  return double(n) / double(size_t(img.width) * img.height);
}

// Mip chain for an alpha-tested RGBA image that keeps the share of texels passing the cutoff the
// same at every level, so thin needles and leaflets do not thin out with distance: each level's
// alpha is scaled by the factor (found by bisection) that restores the full-size coverage
// (Castaño 2010, "Computing alpha mipmaps").
std::vector<image> coverage_mips(const image& level0, float cutoff) {
  std::vector<image> chain{level0};
  const double target = alpha_coverage(level0, cutoff, 1.0f);
  while (chain.back().width > 1 || chain.back().height > 1) {
    image next = half_size(chain.back());
    float lo = 0.0f, hi = 8.0f;
    for (int it = 0; it < 14; ++it) {
      const float mid = 0.5f * (lo + hi);
      (alpha_coverage(next, cutoff, mid) < target ? lo : hi) = mid;
    }
    for (size_t k = 0; k < size_t(next.width) * next.height; ++k)
      next.pixels[k * 4 + 3] = uint8_t(std::min(255.0f, float(next.pixels[k * 4 + 3]) * hi + 0.5f));
    chain.push_back(std::move(next));
  }
  return chain;
}

// One array texture from equally sized layers (internal format `internal`, data `format`).
// Mipmaps: given per level in `levels` (layers' chains of equal length), or made by GL.
int upload_array(gl_texture& t, const std::vector<const image*>& layers, GLenum internal, GLenum format,
                 const std::vector<std::vector<image>>* levels = nullptr) {
  if (layers.empty()) return 0;
  const int w = layers[0]->width, h = layers[0]->height, ch = layers[0]->channels;
  for (const image* l : layers)
    if (l->width != w || l->height != h || l->channels != ch) return 0;
  if (!t.id) glGenTextures(1, &t.id);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glBindTexture(GL_TEXTURE_2D_ARRAY, t.id);
  const int count = int(layers.size());
  std::vector<uint8_t> data;
  const size_t mip_count = levels ? (*levels)[0].size() : 1;
  for (size_t level = 0; level < mip_count; ++level) {
    data.clear();
    int lw = w, lh = h;
    for (int i = 0; i < count; ++i) {
      const image& img = levels ? (*levels)[size_t(i)][level] : *layers[size_t(i)];
      lw = img.width, lh = img.height;
      data.insert(data.end(), img.pixels.begin(), img.pixels.end());
    }
    glTexImage3D(GL_TEXTURE_2D_ARRAY, GLint(level), GLint(internal), lw, lh, count, 0, format, GL_UNSIGNED_BYTE, data.data());
  }
  if (!levels) glGenerateMipmap(GL_TEXTURE_2D_ARRAY);
  glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAX_LEVEL, levels ? GLint(mip_count) - 1 : 1000);
  glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
  glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  return count;
}

// All leaf layers share one array texture per map, so every leaf is drawn in one instanced call;
// layer k is leaf archetype k (leaf_instance::texture). Colour mips keep their alpha coverage.
// Returns the layers uploaded (0 when their sizes differ).
int upload_leaf_arrays(gl_texture& color_tex, gl_texture& normal_tex, gl_texture& thickness_tex,
                       const std::vector<const image*>& color, const std::vector<const image*>& normal,
                       const std::vector<const image*>& thickness) {
  std::vector<std::vector<image>> mips;
  for (const image* c : color) mips.push_back(coverage_mips(*c, 0.5f));
  const int layers = upload_array(color_tex, color, GL_SRGB8_ALPHA8, GL_RGBA, &mips);
  upload_array(normal_tex, normal, GL_RGB8, GL_RGB);
  upload_array(thickness_tex, thickness, GL_R8, GL_RGB);
  return layers;
}

// The tree's own leaf arrays (the user's texture, or the archetypes with a LOD's baked cards).
void upload_leaf_textures(renderer_gpu& r, const std::vector<const image*>& color, const std::vector<const image*>& normal,
                          const std::vector<const image*>& thickness) {
  if (!r.own_leaves) r.leaf_tex = r.leaf_normal_tex = r.leaf_thickness_tex = {}, r.own_leaves = true;
  const int layers = upload_leaf_arrays(r.leaf_tex, r.leaf_normal_tex, r.leaf_thickness_tex, color, normal, thickness);
  r.uploads_total += 3;
  if (layers) r.leaf_layers = layers;
}

void release_own_bark(renderer_gpu& r) {
  if (r.own_bark) delete_gl(r.bark_tex), delete_gl(r.bark_normal_tex), delete_gl(r.bark_rough_tex);
  r.bark_tex = r.bark_normal_tex = r.bark_rough_tex = {};
  r.own_bark = false;
}

void release_own_leaves(renderer_gpu& r) {
  if (r.own_leaves) delete_gl(r.leaf_tex), delete_gl(r.leaf_normal_tex), delete_gl(r.leaf_thickness_tex);
  r.leaf_tex = r.leaf_normal_tex = r.leaf_thickness_tex = {};
  r.own_leaves = false;
}

// Nearest-texel scaling of a baked card to the array's layer size.
image scaled_to(const image& im, int size) {
  image out{size, size, im.channels, std::vector<uint8_t>(size_t(size) * size_t(size) * size_t(im.channels))};
  if (im.width <= 0 || im.height <= 0) return out;
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const size_t from = (size_t(y * im.height / size) * size_t(im.width) + size_t(x * im.width / size)) * size_t(im.channels);
      std::copy_n(im.pixels.begin() + std::ptrdiff_t(from), im.channels, out.pixels.begin() + std::ptrdiff_t((size_t(y) * size_t(size) + size_t(x)) * size_t(im.channels)));
    }
  return out;
}

// The archetypes' layers, then the LOD levels' baked cluster cards (render/mesh/lod_cards.h), if any.
}  // namespace

void upload_blades(renderer_gpu& r, const leaf_blade_shape& shape) {
  const bool flat = r.user_leaf;
  if (r.blade_uploaded && shape == r.blade_shown && flat == r.blade_flat_shown) return;
  std::vector<glm::vec4> table;
  table.reserve(size_t(2 * (blade_prototypes * coarse_blade_vertices + leaf_archetype_count * shoot_vertices_coarse)));
  for (int k = 0; k < blade_prototypes; ++k) {
    const bool card = flat || k == leaf_archetype_count || archetype_is_fruit(leaf_archetype(k));
    const auto grid = card ? coarse_blade(full_card_outline(), leaf_blade_shape{})
                           : coarse_blade(shape.on ? archetype_outline(leaf_archetype(k)) : full_card_outline(), shape);
    for (const blade_vertex& v : grid) table.emplace_back(v.position, v.uv.x), table.emplace_back(v.normal, v.uv.y);
  }
  // Then per archetype its needle shoot's coarse spikes (render/mesh/leaf_shoot.h); zeros for the others.
  for (int k = 0; k < leaf_archetype_count; ++k) {
    if (flat || !shape.on || !archetype_is_shoot(leaf_archetype(k))) {
      table.insert(table.end(), size_t(2 * shoot_vertices_coarse), glm::vec4(0));
      continue;
    }
    const leaf_mesh shoot = shoot_prototype(leaf_archetype(k), shape, shoot_pieces_coarse, archetype_swatches(leaf_archetype(k)));
    for (const blade_vertex& v : shoot.vertex) table.emplace_back(v.position, v.uv.x), table.emplace_back(v.normal, v.uv.y);
  }
  glBindBuffer(GL_TEXTURE_BUFFER, r.blade_table.id);
  glBufferData(GL_TEXTURE_BUFFER, GLsizeiptr(table.size() * sizeof(glm::vec4)), table.data(), GL_STATIC_DRAW);
  glBindBuffer(GL_TEXTURE_BUFFER, 0);
  ++r.uploads_total;
  r.blade_shown = shape, r.blade_flat_shown = flat, r.blade_uploaded = true;
}

void upload_procedural_leaves(renderer_gpu& r) {
  std::vector<const image*> color, normal, thickness;
  for (int i = 0; i < leaf_archetype_count; ++i) {
    const leaf_texture_set& t = leaf_archetype_textures(leaf_archetype(i), 512);
    color.push_back(&t.color), normal.push_back(&t.normal), thickness.push_back(&t.thickness);
  }
  if (!r.cards) {   // the archetypes alone: the context's shared arrays, uploaded by their first user
    gl_shared& s = *r.shared;
    if (!s.leaf_layers) {
      s.leaf_layers = upload_leaf_arrays(s.leaf_color, s.leaf_normal, s.leaf_thickness, color, normal, thickness);
      r.uploads_total += 3;
    }
    release_own_leaves(r);
    r.leaf_tex = s.leaf_color, r.leaf_normal_tex = s.leaf_normal, r.leaf_thickness_tex = s.leaf_thickness;
    r.leaf_layers = std::max(s.leaf_layers, 1);
    r.cards_shown = nullptr;
    return;
  }
  std::vector<image> scaled;
  if (r.cards) {
    scaled.reserve(r.cards->sets.size() * 3);
    for (const leaf_texture_set& t : r.cards->sets) {
      scaled.push_back(scaled_to(t.color, 512));
      color.push_back(&scaled.back());
      scaled.push_back(scaled_to(t.normal, 512));
      normal.push_back(&scaled.back());
      scaled.push_back(scaled_to(t.thickness, 512));
      thickness.push_back(&scaled.back());
    }
  }
  upload_leaf_textures(r, color, normal, thickness);
  r.cards_shown = r.cards.get();
}

void upload_procedural_bark(renderer_gpu& r, bark_archetype a) {
  gl_shared::bark_maps& maps = r.shared->bark_sets[size_t(std::clamp(int(a), 0, bark_archetype_count - 1))];
  if (!maps.color.id) {   // the archetype's first use in this context
    const bark_texture_set& t = bark_archetype_textures(a, 512);
    upload_2d(maps.color, t.color, GL_SRGB8_ALPHA8);
    upload_2d(maps.normal, t.normal, GL_RGB8);
    upload_2d(maps.roughness, t.roughness, GL_RGB8);
    r.uploads_total += 3;
  }
  release_own_bark(r);
  r.bark_tex = maps.color, r.bark_normal_tex = maps.normal, r.bark_rough_tex = maps.roughness;
  r.bark_shown = int(a);
}

void release_tree_textures(renderer_gpu& r) {
  release_own_bark(r);
  release_own_leaves(r);
}

// A user's texture through load_user_texture's checks, and within this GL's size limit.
static std::string load_checked(renderer_gpu& r, const std::string& path, image& out) {
  ++r.user_texture_loads;
  if (std::string err = load_user_texture(path, out); !err.empty()) return err;
  GLint max_size = 0;
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_size);
  if (out.width > max_size || out.height > max_size)
    return path + ": " + std::to_string(out.width) + "x" + std::to_string(out.height) + " is larger than this GPU's " +
           std::to_string(max_size) + " px limit";
  return "";
}

// Loads the user's PNGs when their paths change (a failure says why in texture_message and keeps
// the procedural textures), and uploads the procedural bark archetype when it changes.
void update_user_textures(renderer_gpu& r, const render_params& rp) {
  const bool paths_changed = rp.bark_texture != r.bark_texture_path || rp.leaf_texture != r.leaf_texture_path ||
                             rp.leaf_opacity != r.leaf_opacity_path;
  if (paths_changed) {
    r.bark_texture_path = rp.bark_texture;
    r.leaf_texture_path = rp.leaf_texture;
    r.leaf_opacity_path = rp.leaf_opacity;
    r.texture_message.clear();
    auto say = [&](const std::string& what, const std::string& err) {
      r.texture_message += (r.texture_message.empty() ? "" : "; ") + what + ": " + err + "; using the procedural one";
    };
    const bool had_user_bark = r.user_bark;
    r.user_bark = r.user_leaf = false;
    image bark;
    if (!rp.bark_texture.empty()) {
      if (std::string err = load_checked(r, rp.bark_texture, bark); !err.empty()) say("bark texture", err);
      else r.user_bark = true;
    }
    if (r.user_bark) {
      const image flat{1, 1, 3, {128, 128, 255}};   // a foreign colour map gets no procedural relief
      const image rough{1, 1, 3, {230, 230, 0}};
      upload_bark_textures(r, bark, flat, rough);
      r.bark_shown = -1;
    } else if (had_user_bark) {
      r.bark_shown = -1;   // the procedural bark goes back up below
    }
    image leaf;
    if (!rp.leaf_texture.empty()) {
      if (std::string err = load_checked(r, rp.leaf_texture, leaf); !err.empty()) {
        say("leaf texture", err);
      } else {
        r.user_leaf = true;
        image opacity;
        if (!rp.leaf_opacity.empty()) {
          if (std::string err2 = load_checked(r, rp.leaf_opacity, opacity); !err2.empty())
            r.texture_message += (r.texture_message.empty() ? "" : "; ") + ("leaf opacity: " + err2 + "; using the texture's alpha");
          else if (opacity.width != leaf.width || opacity.height != leaf.height)
            r.texture_message += (r.texture_message.empty() ? "" : "; ") +
                                 std::string("leaf opacity map must be the size of the leaf texture; using the texture's alpha");
          else
            for (size_t i = 0; i < size_t(leaf.width) * leaf.height; ++i) leaf.pixels[i * 4 + 3] = opacity.pixels[i * 4];
        }
      }
    }
    if (r.user_leaf) {   // one layer: the shader's layer index wraps, so every archetype shows it
      const image flat{1, 1, 3, {128, 128, 255}}, thin{1, 1, 3, {200, 200, 200}};
      upload_leaf_textures(r, {&leaf}, {&flat}, {&thin});
    } else if (r.leaf_layers != leaf_archetype_count) {
      upload_procedural_leaves(r);
    }
  }
  if (!r.user_bark && r.bark_shown != int(rp.bark)) upload_procedural_bark(r, rp.bark);
  if (!r.user_leaf && r.cards.get() != r.cards_shown) upload_procedural_leaves(r);   // a LOD's baked cards
  upload_blades(r, r.blade_shown);   // the user's picture shows on flat cards
  if (paths_changed) check_gl("user textures");
}

// ---------------------------------------------------------------- render targets

gl_texture make_color_target(int w, int h, GLenum internal_format) {
  gl_texture t;
  glGenTextures(1, &t.id);
  glBindTexture(GL_TEXTURE_2D, t.id);
  glTexImage2D(GL_TEXTURE_2D, 0, internal_format, w, h, 0, GL_RGBA, GL_FLOAT, nullptr);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  return t;
}

gl_framebuffer make_framebuffer(const gl_texture& color, const gl_texture& depth) {
  gl_framebuffer f;
  glGenFramebuffers(1, &f.id);
  glBindFramebuffer(GL_FRAMEBUFFER, f.id);
  if (color.id) glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, color.id, 0);
  if (depth.id) glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, depth.id, 0);
  if (!color.id) {
    glDrawBuffer(GL_NONE);
    glReadBuffer(GL_NONE);
  }
  if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) check_gl("incomplete framebuffer");
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  return f;
}

gl_texture make_depth_texture(int w, int h, bool compare) {
  gl_texture t;
  glGenTextures(1, &t.id);
  glBindTexture(GL_TEXTURE_2D, t.id);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_DEPTH_COMPONENT24, w, h, 0, GL_DEPTH_COMPONENT, GL_UNSIGNED_INT, nullptr);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, compare ? GL_LINEAR : GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, compare ? GL_LINEAR : GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  if (compare) {  // hardware 2x2 compare under each PCF tap
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
  }
  return t;
}

void resize_targets(renderer_gpu& r, int w, int h, int samples) {
  GLint max_samples = 0;
  glGetIntegerv(GL_MAX_SAMPLES, &max_samples);
  samples = std::clamp(samples, 0, int(max_samples));
  if (samples == 1) samples = 0;
  if (r.width == w && r.height == h && r.samples == samples) return;
  r.width = w;
  r.height = h;
  r.samples = samples;
  delete_gl(r.msaa_fbo);
  delete_gl(r.msaa_color);
  delete_gl(r.msaa_depth);
  if (samples > 1) {
    glGenRenderbuffers(1, &r.msaa_color.id);
    glBindRenderbuffer(GL_RENDERBUFFER, r.msaa_color.id);
    glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples, GL_RGBA16F, w, h);
    glGenRenderbuffers(1, &r.msaa_depth.id);
    glBindRenderbuffer(GL_RENDERBUFFER, r.msaa_depth.id);
    glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples, GL_DEPTH_COMPONENT24, w, h);
    glBindRenderbuffer(GL_RENDERBUFFER, 0);
    glGenFramebuffers(1, &r.msaa_fbo.id);
    glBindFramebuffer(GL_FRAMEBUFFER, r.msaa_fbo.id);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, r.msaa_color.id);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, r.msaa_depth.id);
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) check_gl("incomplete MSAA framebuffer");
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
  }
  for (gl_framebuffer* f : {&r.hdr_fbo, &r.occlusion_fbo, &r.rays_fbo, &r.march_fbo}) delete_gl(*f);
  for (gl_texture* t : {&r.hdr_color, &r.hdr_depth, &r.occlusion_tex, &r.rays_tex, &r.march_tex}) delete_gl(*t);
  r.hdr_color = make_color_target(w, h, GL_RGBA16F);
  r.hdr_depth = make_depth_texture(w, h, false);
  r.hdr_fbo = make_framebuffer(r.hdr_color, r.hdr_depth);
  const int hw = std::max(1, w / 2), hh = std::max(1, h / 2);   // god rays at half resolution
  r.occlusion_tex = make_color_target(hw, hh, GL_RGBA16F);
  r.occlusion_fbo = make_framebuffer(r.occlusion_tex, {});
  r.rays_tex = make_color_target(hw, hh, GL_RGBA16F);
  r.rays_fbo = make_framebuffer(r.rays_tex, {});
  r.march_tex = make_color_target(hw, hh, GL_RGBA16F);   // volumetric shafts at half resolution too
  r.march_fbo = make_framebuffer(r.march_tex, {});
  r.uploads_total += samples > 1 ? 7 : 5;
  check_gl("resize targets");
}

void resize_shadow(renderer_gpu& r, int size) {
  if (r.shadow_size == size) return;
  r.shadow_size = size;
  r.shadow_drawn = false;
  delete_gl(r.shadow_fbo);
  delete_gl(r.shadow_tex);
  r.shadow_tex = make_depth_texture(size, size, true);
  r.shadow_fbo = make_framebuffer({}, r.shadow_tex);
  ++r.uploads_total;
  check_gl("resize shadow map");
}

// Orthographic sun frustum fitted to the tree's bounds (docs/SCENE.md, "What a frame draws", 1).
void set_bark_tint_uniforms(const gl_program& p, const render_params& rp) {
  set_uniform(p, "u_bark_color", rp.bark_color);
  set_uniform(p, "u_bark_base_color", rp.bark_base_color);
  set_uniform(p, "u_bark_base_height", std::isfinite(rp.bark_base_height) ? rp.bark_base_height : 0.0f);
}

}  // namespace sylva
