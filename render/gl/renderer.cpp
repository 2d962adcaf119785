// The frame renderer: programs, procedural textures, tree upload, and the passes of DESIGN §8.
#include "render/gl/renderer.h"
#include "render/gl/shaders.h"

#include "generators/wood.h"
#include "render/gl/wind_gl.h"
#include "render/lod_cards.h"
#include "render/season.h"
#include "render/textures.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstddef>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

namespace sylva {

namespace {

using namespace glsl;   // the programs' sources (render/gl/shaders.h)

// ---------------------------------------------------------------- helpers

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

void upload_bark_textures(renderer_gpu& r, const image& color, const image& normal, const image& rough) {
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
void upload_leaf_textures(renderer_gpu& r, const std::vector<const image*>& color, const std::vector<const image*>& normal,
                          const std::vector<const image*>& thickness) {
  std::vector<std::vector<image>> mips;
  for (const image* c : color) mips.push_back(coverage_mips(*c, 0.5f));
  const int layers = upload_array(r.leaf_tex, color, GL_SRGB8_ALPHA8, GL_RGBA, &mips);
  upload_array(r.leaf_normal_tex, normal, GL_RGB8, GL_RGB);
  upload_array(r.leaf_thickness_tex, thickness, GL_R8, GL_RGB);
  r.uploads_total += 3;
  if (layers) r.leaf_layers = layers;
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

// The archetypes' layers, then the LOD levels' baked cluster cards (render/lod_cards.h), if any.
void upload_procedural_leaves(renderer_gpu& r) {
  std::vector<const image*> color, normal, thickness;
  for (int i = 0; i < leaf_archetype_count; ++i) {
    const leaf_texture_set& t = leaf_archetype_textures(leaf_archetype(i), 512);
    color.push_back(&t.color), normal.push_back(&t.normal), thickness.push_back(&t.thickness);
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
  const bark_texture_set& t = bark_archetype_textures(a, 512);
  upload_bark_textures(r, t.color, t.normal, t.roughness);
  r.bark_shown = int(a);
}

// A user's texture through load_user_texture's checks, and within this GL's size limit.
std::string load_checked(const std::string& path, image& out) {
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
      if (std::string err = load_checked(rp.bark_texture, bark); !err.empty()) say("bark texture", err);
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
      if (std::string err = load_checked(rp.leaf_texture, leaf); !err.empty()) {
        say("leaf texture", err);
      } else {
        r.user_leaf = true;
        image opacity;
        if (!rp.leaf_opacity.empty()) {
          if (std::string err2 = load_checked(rp.leaf_opacity, opacity); !err2.empty())
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
  if (paths_changed) check_gl("user textures");
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
  delete_gl(r.shadow_fbo);
  delete_gl(r.shadow_tex);
  r.shadow_tex = make_depth_texture(size, size, true);
  r.shadow_fbo = make_framebuffer({}, r.shadow_tex);
  ++r.uploads_total;
  check_gl("resize shadow map");
}

// Orthographic sun frustum fitted to the tree's bounds (DESIGN §8 pass 1).
glm::mat4 light_viewproj(const renderer_gpu& r, const glm::vec3& sun, float* texel_world) {
  glm::vec3 lo = r.bounds_min, hi = r.bounds_max;
  glm::vec3 center = 0.5f * (lo + hi);
  float radius = std::max(glm::length(hi - lo) * 0.5f, 0.01f);
  glm::vec3 up = std::abs(sun.y) > 0.99f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
  glm::mat4 view = glm::lookAt(center + sun * radius * 2.0f, center, up);
  glm::vec3 a(1e30f), b(-1e30f);
  for (int i = 0; i < 8; ++i) {
    glm::vec3 c((i & 1) ? hi.x : lo.x, (i & 2) ? hi.y : lo.y, (i & 4) ? hi.z : lo.z);
    glm::vec3 v = glm::vec3(view * glm::vec4(c, 1));
    a = glm::min(a, v);
    b = glm::max(b, v);
  }
  const float pad = radius * 0.02f + r.wind_reach;   // the swaying crown stays inside the map
  glm::mat4 proj = glm::ortho(a.x - pad, b.x + pad, a.y - pad, b.y + pad, -b.z - pad, -a.z + pad);
  if (texel_world) *texel_world = std::max(b.x - a.x, b.y - a.y) / float(std::max(r.shadow_size, 1));
  return proj * view;
}

void set_lighting(const renderer_gpu& r, const gl_program& p, const render_params& rp, const glm::vec3& sun,
                  const glm::mat4& light, float texel_world) {
  set_uniform(p, "u_sun_dir", sun);
  // The sun's colour and the sky light come from the sky model (render/sky.h); the sun dims as it sets.
  set_uniform(p, "u_sun_light", r.daylight.sun_light);
  static const char* const sh_names[4] = {"u_sh[0]", "u_sh[1]", "u_sh[2]", "u_sh[3]"};
  for (int k = 0; k < 4; ++k) set_uniform(p, sh_names[k], r.daylight.sh[k]);
  set_uniform(p, "u_shadows", rp.shadows && r.has_tree ? 1 : 0);
  set_uniform(p, "u_pcf", int(rp.shadow_pcf));
  set_uniform(p, "u_bias", rp.shadow_bias);
  set_uniform(p, "u_normal_offset", rp.shadow_normal_offset);
  set_uniform(p, "u_shadow_texel", texel_world);
  set_uniform(p, "u_light_viewproj", light);
  set_uniform(p, "u_shadow", 1);
}

// The parameters the sky model reads, compared and copied one by one (no string copies per frame).
bool same_sky_inputs(const render_params& a, const render_params& b) {
  return a.sun_azimuth == b.sun_azimuth && a.sun_elevation == b.sun_elevation && a.physical_sky == b.physical_sky &&
         a.turbidity == b.turbidity && a.sun_color == b.sun_color && a.sun_intensity == b.sun_intensity &&
         a.sky_zenith == b.sky_zenith && a.sky_horizon == b.sky_horizon && a.ambient == b.ambient &&
         a.ground_color == b.ground_color;
}

void update_sky(renderer_gpu& r, const render_params& rp) {
  if (r.sky_valid && same_sky_inputs(r.sky_inputs, rp)) return;
  render_params& k = r.sky_inputs;
  k.sun_azimuth = rp.sun_azimuth, k.sun_elevation = rp.sun_elevation, k.physical_sky = rp.physical_sky;
  k.turbidity = rp.turbidity, k.sun_color = rp.sun_color, k.sun_intensity = rp.sun_intensity;
  k.sky_zenith = rp.sky_zenith, k.sky_horizon = rp.sky_horizon, k.ambient = rp.ambient, k.ground_color = rp.ground_color;
  compute_sky(rp, r.daylight);
  r.sky_valid = true;
}

void set_sky_uniforms(const renderer_gpu& r, const gl_program& p) {
  static const char* const perez_names[5] = {"u_perez[0]", "u_perez[1]", "u_perez[2]", "u_perez[3]", "u_perez[4]"};
  set_uniform(p, "u_physical", r.daylight.physical ? 1 : 0);
  for (int k = 0; k < 5; ++k) set_uniform(p, perez_names[k], r.daylight.perez[k]);
  set_uniform(p, "u_zenith", r.daylight.zenith);
  set_uniform(p, "u_perez_zenith", r.daylight.perez_zenith);
  set_uniform(p, "u_sky_scale", r.daylight.scale);
  set_uniform(p, "u_sky_zenith", r.daylight.legacy_zenith);
  set_uniform(p, "u_sky_horizon", r.daylight.legacy_horizon);
}

double now_ms() {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

void bind_tree_textures(const renderer_gpu& r) {
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, r.bark_tex.id);
  glActiveTexture(GL_TEXTURE1);
  glBindTexture(GL_TEXTURE_2D, r.shadow_tex.id);
  glActiveTexture(GL_TEXTURE2);
  glBindTexture(GL_TEXTURE_BUFFER, r.node_radius_tex.id);
  glActiveTexture(GL_TEXTURE3);
  glBindTexture(GL_TEXTURE_2D_ARRAY, r.leaf_tex.id);
  glActiveTexture(GL_TEXTURE4);
  glBindTexture(GL_TEXTURE_2D, r.bark_normal_tex.id);
  glActiveTexture(GL_TEXTURE5);
  glBindTexture(GL_TEXTURE_2D_ARRAY, r.leaf_normal_tex.id);
  glActiveTexture(GL_TEXTURE6);
  glBindTexture(GL_TEXTURE_2D_ARRAY, r.leaf_thickness_tex.id);
  glActiveTexture(GL_TEXTURE7);
  glBindTexture(GL_TEXTURE_2D, r.bark_rough_tex.id);
  glActiveTexture(GL_TEXTURE0);
}

void draw_bark(renderer_gpu& r) {
  uint32_t n = r.index_end.empty() ? 0 : r.index_end[std::clamp(r.step, 0, int(r.index_end.size()) - 1)];
  if (!n) return;
  ++r.counts.draw_calls;
  glBindVertexArray(r.bark_vao.id);
  glDrawElements(GL_TRIANGLES, GLsizei(n), GL_UNSIGNED_INT, nullptr);
}

uint32_t leaf_count(const renderer_gpu& r) {
  return r.leaf_end.empty() ? 0 : r.leaf_end[std::clamp(r.step, 0, int(r.leaf_end.size()) - 1)];
}

// All leaf textures live in one array texture, so every leaf is drawn in a single instanced call.
// The season's leaf colours, fallen share and size (render/season.h), for the leaf vertex shader.
void set_season_uniforms(const gl_program& p, const season_look& s) {
  set_uniform(p, "u_leaf_color", s.evergreen_color);
  set_uniform(p, "u_autumn_a", s.deciduous_color_a);
  set_uniform(p, "u_autumn_b", s.deciduous_color_b);
  glUniform1ui(glGetUniformLocation(p.id, "u_deciduous"), s.deciduous_mask);
  set_uniform(p, "u_keep", s.deciduous_keep);
  set_uniform(p, "u_season_scale", s.deciduous_scale);
}

void draw_leaves(renderer_gpu& r) {
  uint32_t n = leaf_count(r);
  if (!n) return;
  ++r.counts.draw_calls;
  ++r.counts.leaf_draw_calls;
  glBindVertexArray(r.leaf_vao.id);
  glDrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, GLsizei(n));
}

// ---------------------------------------------------------------- passes of the frame

// Pass times for renderer_gpu::timings: each mark closes a pass with glFinish (benchmarks only).
struct pass_clock {
  bool on = false;
  double t0 = 0;
  void mark(double& slot) {
    if (!on) return;
    glFinish();
    const double t = now_ms();
    slot = t - t0;
    t0 = t;
  }
};

// What every pass of one frame shares: the camera, the sun and its shadow map, the fog.
struct frame_setup {
  glm::vec3 sun{0}, eye{0};
  float scene = 1, ground_extent = 30, far_plane = 100;
  glm::mat4 viewproj{1}, inv_viewproj{1}, light{1};
  float texel_world = 0;
  bool lit_ok = false;
  season_look season;
  float sky_distance = 0, fog_density = 0, haze = 0, fog_height = 1;
  int width = 0, height = 0, hw = 1, hh = 1;   // the frame, and the shafts' half resolution
  mutable pass_clock clock;
};

frame_setup setup_frame(renderer_gpu& r, const render_params& rp, const orbit_camera& cam, int width, int height) {
  frame_setup f;
  f.clock.on = r.measure_passes;
  f.clock.t0 = now_ms();
  f.width = width, f.height = height;
  f.sun = sun_direction(rp);
  f.eye = camera_eye(cam);
  f.scene = std::max(glm::length(r.bounds_max - r.bounds_min), 1.0f);
  f.ground_extent = std::max(30.0f, f.scene * 10.0f);
  const float near_plane = std::max(cam.distance * 0.01f, 0.005f);
  f.far_plane = cam.distance + f.ground_extent * 3.0f;
  const glm::mat4 proj = glm::perspective(glm::radians(cam.fov), float(width) / float(height), near_plane, f.far_plane);
  const glm::mat4 view = glm::lookAt(f.eye, cam.target, glm::vec3(0, 1, 0));
  f.viewproj = proj * view;
  f.inv_viewproj = glm::inverse(f.viewproj);
  r.wind_reach = wind_reach(r, rp);
  f.light = light_viewproj(r, f.sun, &f.texel_world);
  f.lit_ok = !r.bark.failed && !r.leaf.failed;
  f.season = with_card_seasons(season_leaf_look(rp), r.cards.get());   // baked cards fall with their leaves
  // Rays that meet no surface cross fog only to a little past the tree: the sky model already holds
  // the atmosphere beyond.
  f.sky_distance = cam.distance + f.scene;
  f.fog_density = std::clamp(rp.fog_density, 0.0f, 1.0f), f.haze = std::clamp(rp.haze, 0.0f, 0.1f);
  f.fog_height = std::clamp(rp.fog_height, 0.1f, 100.0f);
  f.hw = std::max(1, width / 2), f.hh = std::max(1, height / 2);
  return f;
}

// Which light shafts this frame draws, and where the sun is on screen for the radial ones.
struct shaft_choice {
  bool rays = false, volumetric = false;
  float ray_fade = 0;
  glm::vec4 sun_clip{0};
};

shaft_choice choose_shafts(const renderer_gpu& r, const render_params& rp, const orbit_camera& cam, const frame_setup& f) {
  shaft_choice sh;
  sh.sun_clip = f.viewproj * glm::vec4(f.eye + f.sun * f.far_plane * 0.5f, 1.0f);
  const glm::vec3 fwd = glm::normalize(cam.target - f.eye);
  // Rays fade out as the sun leaves the view or goes behind the camera.
  sh.ray_fade = std::clamp((glm::dot(fwd, f.sun) - 0.1f) / 0.4f, 0.0f, 1.0f);
  sh.ray_fade *= std::clamp((f.sun.y + 0.05f) / 0.1f, 0.0f, 1.0f);
  sh.rays = rp.shafts == light_shafts::radial && sh.ray_fade > 0 && sh.sun_clip.w > 0 && !r.occlusion.failed &&
            !r.radial.failed;
  sh.volumetric = rp.shafts == light_shafts::volumetric && !r.march.failed;
  return sh;
}

// 1. Shadow pass: depth from the sun, back faces, slope-scaled bias.
void draw_shadow_pass(renderer_gpu& r, const render_params& rp, const frame_setup& f) {
  const glm::mat4& light = f.light;
  const bool lit_ok = f.lit_ok;
  const season_look& season = f.season;
  glBindFramebuffer(GL_FRAMEBUFFER, r.shadow_fbo.id);
  glViewport(0, 0, r.shadow_size, r.shadow_size);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  glClear(GL_DEPTH_BUFFER_BIT);
  if (rp.shadows && r.has_tree && lit_ok) {
    glEnable(GL_POLYGON_OFFSET_FILL);
    glPolygonOffset(rp.shadow_slope_bias, 1.0f);
    glEnable(GL_CULL_FACE);
    glCullFace(GL_FRONT);
    glUseProgram(r.bark_depth.id);
    set_uniform(r.bark_depth, "u_viewproj", light);
    set_uniform(r.bark_depth, "u_radius", 2);
    set_wind_uniforms(r, r.bark_depth, rp);
    draw_bark(r);
    glDisable(GL_CULL_FACE);
    glUseProgram(r.leaf_depth.id);   // leaves cast alpha-tested shadows
    set_uniform(r.leaf_depth, "u_viewproj", light);
    set_uniform(r.leaf_depth, "u_step", r.step);
    set_uniform(r.leaf_depth, "u_radius", 2);
    set_uniform(r.leaf_depth, "u_leaf", 3);
    set_uniform(r.leaf_depth, "u_layers", r.leaf_layers);
    set_uniform(r.leaf_depth, "u_cutoff", rp.alpha_cutoff);
    set_uniform(r.leaf_depth, "u_shadow_pass", 1);   // the impostor's sun card casts (render/gl/impostor.h)
    set_wind_uniforms(r, r.leaf_depth, rp);
    set_season_uniforms(r.leaf_depth, season);
    draw_leaves(r);
    glDisable(GL_POLYGON_OFFSET_FILL);
  }
  f.clock.mark(r.timings.shadow);
}

// 2. Lit pass into the linear HDR target (multisampled, then resolved, when MSAA is on): sky, ground,
// tree and the growth-debug overlays.
void draw_lit_pass(renderer_gpu& r, const render_params& rp, const frame_setup& f, const overlay_view* overlays) {
  const glm::vec3& sun = f.sun;
  const glm::vec3& eye = f.eye;
  const float ground_extent = f.ground_extent;
  const glm::mat4& viewproj = f.viewproj;
  const glm::mat4& inv_viewproj = f.inv_viewproj;
  const glm::mat4& light = f.light;
  const float texel_world = f.texel_world;
  const bool lit_ok = f.lit_ok;
  const season_look& season = f.season;
  const int width = f.width;
  const int height = f.height;
  glBindFramebuffer(GL_FRAMEBUFFER, r.samples > 1 ? r.msaa_fbo.id : r.hdr_fbo.id);
  glViewport(0, 0, width, height);
  glClearColor(0, 0, 0, 1);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  if (!r.sky.failed) {   // sky first, without depth, so the depth buffer stays 1 where sky shows
    glDisable(GL_DEPTH_TEST);
    glDepthMask(GL_FALSE);
    glUseProgram(r.sky.id);
    set_uniform(r.sky, "u_inv_viewproj", inv_viewproj);
    set_uniform(r.sky, "u_eye", eye);
    set_uniform(r.sky, "u_sun_dir", sun);
    set_sky_uniforms(r, r.sky);
    set_uniform(r.sky, "u_sun_light", r.daylight.sun_light);
    glBindVertexArray(r.empty_vao.id);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    ++r.counts.draw_calls;
    glEnable(GL_DEPTH_TEST);
    glDepthMask(GL_TRUE);
  }
  if (rp.ground && !r.ground.failed) {
    glUseProgram(r.ground.id);
    set_lighting(r, r.ground, rp, sun, light, texel_world);
    set_uniform(r.ground, "u_viewproj", viewproj);
    glm::vec3 center = 0.5f * (r.bounds_min + r.bounds_max);
    set_uniform(r.ground, "u_center", center);
    set_uniform(r.ground, "u_extent", ground_extent);
    set_uniform(r.ground, "u_sky_horizon", r.daylight.horizon);
    set_uniform(r.ground, "u_ground_color", rp.ground_color);
    set_uniform(r.ground, "u_root", r.root);
    set_uniform(r.ground, "u_root_radius", r.has_tree ? r.root_radius : 0.0f);
    const glm::vec3 half = 0.5f * (r.bounds_max - r.bounds_min);
    set_uniform(r.ground, "u_crown_radius", r.has_tree ? glm::vec2(half.x, half.z) : glm::vec2(0.0f));
    glBindVertexArray(r.empty_vao.id);
    glEnable(GL_BLEND);
    glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
    glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
    glDisable(GL_BLEND);
    ++r.counts.draw_calls;
  }
  if (r.has_tree) {
    if (lit_ok) {
      glEnable(GL_CULL_FACE);
      glCullFace(GL_BACK);
      glUseProgram(r.bark.id);
      set_lighting(r, r.bark, rp, sun, light, texel_world);
      set_uniform(r.bark, "u_viewproj", viewproj);
      set_uniform(r.bark, "u_radius", 2);
      set_uniform(r.bark, "u_bark", 0);
      set_uniform(r.bark, "u_bark_normal", 4);
      set_uniform(r.bark, "u_bark_rough", 7);
      set_uniform(r.bark, "u_eye", eye);
      set_uniform(r.bark, "u_bark_color", rp.bark_color);
      set_wind_uniforms(r, r.bark, rp);
      draw_bark(r);
      glDisable(GL_CULL_FACE);
      glUseProgram(r.leaf.id);
      set_lighting(r, r.leaf, rp, sun, light, texel_world);
      set_uniform(r.leaf, "u_viewproj", viewproj);
      set_uniform(r.leaf, "u_step", r.step);
      set_uniform(r.leaf, "u_radius", 2);
      set_uniform(r.leaf, "u_variation", rp.leaf_color_variation);
      set_uniform(r.leaf, "u_leaf", 3);
      set_uniform(r.leaf, "u_layers", r.leaf_layers);
      set_uniform(r.leaf, "u_leaf_normal", 5);
      set_uniform(r.leaf, "u_leaf_thickness", 6);
      set_season_uniforms(r.leaf, season);
      set_uniform(r.leaf, "u_cutoff", rp.alpha_cutoff);
      set_uniform(r.leaf, "u_translucency", rp.leaf_translucency);
      set_wind_uniforms(r, r.leaf, rp);
      draw_leaves(r);
    } else if (!r.fallback.failed) {   // a lit shader failed: flat bark, still a tree
      glUseProgram(r.fallback.id);
      set_uniform(r.fallback, "u_viewproj", viewproj);
      set_uniform(r.fallback, "u_radius", 2);
      set_uniform(r.fallback, "u_color", rp.bark_color);
      set_wind_uniforms(r, r.fallback, rp);
      draw_bark(r);
    }
  }
  if (overlays) {   // the caller's choice of growth-debug layers
    if (sync_overlays(r.overlay)) ++r.uploads_total;
    r.counts.draw_calls += draw_overlays(r.overlay, *overlays, viewproj, r.step);
  }
  if (r.samples > 1) {   // resolve colour and depth: the occlusion pass reads the depth
    glBindFramebuffer(GL_READ_FRAMEBUFFER, r.msaa_fbo.id);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, r.hdr_fbo.id);
    glBlitFramebuffer(0, 0, width, height, 0, 0, width, height, GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT, GL_NEAREST);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
  }
  f.clock.mark(r.timings.lit);
}

// 3a. Radial shafts: occlusion at half resolution, then the blur toward the sun (only while the sun is
// in view).
void draw_radial_shafts(renderer_gpu& r, const render_params& rp, const frame_setup& f, const shaft_choice& sh) {
  const glm::vec3& sun = f.sun;
  const glm::vec3& eye = f.eye;
  const glm::mat4& inv_viewproj = f.inv_viewproj;
  const int hw = f.hw;
  const int hh = f.hh;
  const glm::vec2 light_uv = glm::vec2(sh.sun_clip.x, sh.sun_clip.y) / sh.sun_clip.w * 0.5f + 0.5f;
  glBindFramebuffer(GL_FRAMEBUFFER, r.occlusion_fbo.id);
  glViewport(0, 0, hw, hh);
  glUseProgram(r.occlusion.id);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, r.hdr_depth.id);
  set_uniform(r.occlusion, "u_depth", 0);
  set_uniform(r.occlusion, "u_inv_viewproj", inv_viewproj);
  set_uniform(r.occlusion, "u_eye", eye);
  set_uniform(r.occlusion, "u_sun_dir", sun);
  const float sun_max = std::max({r.daylight.sun_light.x, r.daylight.sun_light.y, r.daylight.sun_light.z, 1e-6f});
  set_uniform(r.occlusion, "u_sun_color", r.daylight.sun_light / sun_max);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  ++r.counts.draw_calls;
  f.clock.mark(r.timings.occlusion);

  glBindFramebuffer(GL_FRAMEBUFFER, r.rays_fbo.id);
  glUseProgram(r.radial.id);
  glBindTexture(GL_TEXTURE_2D, r.occlusion_tex.id);
  set_uniform(r.radial, "u_occlusion", 0);
  set_uniform(r.radial, "u_light_uv", light_uv);
  set_uniform(r.radial, "u_samples", std::clamp(rp.ray_samples, 1, 256));
  set_uniform(r.radial, "u_density", rp.ray_density);
  set_uniform(r.radial, "u_weight", rp.ray_weight);
  set_uniform(r.radial, "u_decay", rp.ray_decay);
  set_uniform(r.radial, "u_exposure", rp.ray_exposure);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  ++r.counts.draw_calls;
  f.clock.mark(r.timings.blur);
}

// 3b. Volumetric shafts: the fog's shadowed optical depth per half-resolution pixel.
void draw_volumetric_shafts(renderer_gpu& r, const render_params& rp, const frame_setup& f) {
  const glm::vec3& sun = f.sun;
  const glm::vec3& eye = f.eye;
  const glm::mat4& inv_viewproj = f.inv_viewproj;
  const glm::mat4& light = f.light;
  const float sky_distance = f.sky_distance;
  const float fog_density = f.fog_density;
  const float haze = f.haze;
  const float fog_height = f.fog_height;
  const int hw = f.hw;
  const int hh = f.hh;
  glBindFramebuffer(GL_FRAMEBUFFER, r.march_fbo.id);
  glViewport(0, 0, hw, hh);
  glUseProgram(r.march.id);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, r.hdr_depth.id);
  glActiveTexture(GL_TEXTURE1);
  glBindTexture(GL_TEXTURE_2D, r.shadow_tex.id);
  set_uniform(r.march, "u_depth", 0);
  set_uniform(r.march, "u_shadow", 1);
  set_uniform(r.march, "u_inv_viewproj", inv_viewproj);
  set_uniform(r.march, "u_eye", eye);
  set_uniform(r.march, "u_sun_dir", sun);
  set_uniform(r.march, "u_light_viewproj", light);
  // Without shadows nothing is shadowed: zero samples leave the fog uniformly lit.
  set_uniform(r.march, "u_samples", rp.shadows && r.has_tree ? std::clamp(rp.shaft_samples, 1, 256) : 0);
  set_uniform(r.march, "u_fog_density", fog_density);
  set_uniform(r.march, "u_fog_height", fog_height);
  set_uniform(r.march, "u_haze", haze);
  set_uniform(r.march, "u_sky_distance", sky_distance);
  set_uniform(r.march, "u_bias", rp.shadow_bias);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  ++r.counts.draw_calls;
  f.clock.mark(r.timings.march);
}

// 4. The frame's log-average luminance, 1 x 1, for auto exposure.
void draw_exposure_pass(renderer_gpu& r, const frame_setup& f) {
  glBindFramebuffer(GL_FRAMEBUFFER, r.average_fbo.id);
  glViewport(0, 0, 1, 1);
  glUseProgram(r.exposure.id);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, r.hdr_color.id);
  set_uniform(r.exposure, "u_hdr", 0);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  ++r.counts.draw_calls;
  f.clock.mark(r.timings.exposure);
}

// 5. Composite: fog and shafts, exposure, tonemap, into the target.
void draw_composite_pass(renderer_gpu& r, const render_params& rp, const frame_setup& f,
                         const shaft_choice& sh, gl_framebuffer target, glm::ivec2 origin) {
  const glm::vec3& sun = f.sun;
  const glm::vec3& eye = f.eye;
  const glm::mat4& inv_viewproj = f.inv_viewproj;
  const float sky_distance = f.sky_distance;
  const float fog_density = f.fog_density;
  const float haze = f.haze;
  const float fog_height = f.fog_height;
  const int width = f.width;
  const int height = f.height;
  glBindFramebuffer(GL_FRAMEBUFFER, target.id);
  glViewport(origin.x, origin.y, width, height);
  glUseProgram(r.composite.id);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, r.hdr_color.id);
  glActiveTexture(GL_TEXTURE1);
  glBindTexture(GL_TEXTURE_2D, r.rays_tex.id);
  glActiveTexture(GL_TEXTURE2);
  glBindTexture(GL_TEXTURE_2D, r.march_tex.id);
  glActiveTexture(GL_TEXTURE3);
  glBindTexture(GL_TEXTURE_2D, r.hdr_depth.id);
  glActiveTexture(GL_TEXTURE4);
  glBindTexture(GL_TEXTURE_2D, r.average_tex.id);
  set_uniform(r.composite, "u_hdr", 0);
  set_uniform(r.composite, "u_rays", 1);
  set_uniform(r.composite, "u_march", 2);
  set_uniform(r.composite, "u_depth", 3);
  set_uniform(r.composite, "u_average", 4);
  set_uniform(r.composite, "u_ray_strength", sh.rays ? sh.ray_fade : 0.0f);
  set_uniform(r.composite, "u_exposure", rp.exposure);
  set_uniform(r.composite, "u_auto_exposure", rp.auto_exposure && !r.exposure.failed ? 1 : 0);
  set_uniform(r.composite, "u_volumetric", sh.volumetric ? 1 : 0);
  set_uniform(r.composite, "u_inv_viewproj", inv_viewproj);
  set_uniform(r.composite, "u_eye", eye);
  set_uniform(r.composite, "u_sun_dir", sun);
  set_uniform(r.composite, "u_fog_density", fog_density);
  set_uniform(r.composite, "u_fog_height", fog_height);
  set_uniform(r.composite, "u_haze", haze);
  set_uniform(r.composite, "u_sky_distance", sky_distance);
  set_uniform(r.composite, "u_g", std::clamp(rp.scattering_g, -0.95f, 0.95f));
  set_uniform(r.composite, "u_sun_light", r.daylight.sun_light);
  set_uniform(r.composite, "u_fog_ambient", r.daylight.fog_ambient);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  ++r.counts.draw_calls;
  glActiveTexture(GL_TEXTURE0);
  glUseProgram(0);
  glBindVertexArray(0);
  f.clock.mark(r.timings.composite);
}

}  // namespace

// ---------------------------------------------------------------- camera

void orbit_camera_rotate(orbit_camera& c, float dx, float dy) {
  c.yaw -= dx * 0.3f;
  c.pitch = std::clamp(c.pitch + dy * 0.3f, -89.0f, 89.0f);
}

void orbit_camera_pan(orbit_camera& c, float dx, float dy, int viewport_height) {
  glm::vec3 eye = camera_eye(c);
  glm::vec3 fwd = glm::normalize(c.target - eye);
  glm::vec3 right = glm::normalize(glm::cross(fwd, glm::vec3(0, 1, 0)));
  glm::vec3 up = glm::cross(right, fwd);
  float per_pixel = 2.0f * c.distance * std::tan(glm::radians(c.fov) * 0.5f) / float(std::max(viewport_height, 1));
  c.target += (-dx * right + dy * up) * per_pixel;
}

void orbit_camera_zoom(orbit_camera& c, float wheel) {
  c.distance = std::clamp(c.distance * std::pow(0.88f, wheel), 0.01f, 1e5f);
}

void frame_camera(orbit_camera& c, const glm::vec3& lo, const glm::vec3& hi, float aspect) {
  // Keeps the direction; moves the target and the distance until the box's projection spans 75% of
  // the view height (or 90% of its width, if that is tighter) and sits in the middle (issue 13).
  aspect = std::isfinite(aspect) && aspect > 0.05f ? std::min(aspect, 20.0f) : 1.6f;
  const glm::vec3 center = 0.5f * (lo + hi);
  const float radius = std::max(glm::length(hi - lo) * 0.5f, 0.05f);
  c.target = center;
  c.distance = radius / std::sin(glm::radians(c.fov) * 0.5f) * 1.05f;
  const float tan_half = std::tan(glm::radians(c.fov) * 0.5f);
  for (int it = 0; it < 12; ++it) {
    const glm::vec3 eye = camera_eye(c);
    const glm::vec3 fwd = glm::normalize(c.target - eye);
    const glm::vec3 right = glm::normalize(glm::cross(fwd, glm::vec3(0, 1, 0)));
    const glm::vec3 up = glm::cross(right, fwd);
    glm::vec2 a(1e30f), b(-1e30f);
    bool behind = false;
    for (int i = 0; i < 8; ++i) {
      const glm::vec3 p((i & 1) ? hi.x : lo.x, (i & 2) ? hi.y : lo.y, (i & 4) ? hi.z : lo.z);
      const float z = glm::dot(p - eye, fwd);
      if (z < 1e-3f * radius) { behind = true; break; }
      const glm::vec2 ndc(glm::dot(p - eye, right) / (z * tan_half * aspect), glm::dot(p - eye, up) / (z * tan_half));
      a = glm::min(a, ndc), b = glm::max(b, ndc);
    }
    if (behind) { c.distance *= 1.5f; continue; }
    const glm::vec2 mid = 0.5f * (a + b);
    c.target += right * (mid.x * tan_half * aspect * c.distance) + up * (mid.y * tan_half * c.distance);
    const float scale = std::max((b.y - a.y) / 1.7f, (b.x - a.x) / 1.9f);
    c.distance = std::clamp(c.distance * std::clamp(scale, 0.5f, 2.0f), 0.01f, 1e5f);
  }
}

glm::vec3 camera_eye(const orbit_camera& c) {
  float y = glm::radians(c.yaw), p = glm::radians(c.pitch);
  return c.target + c.distance * glm::vec3(std::sin(y) * std::cos(p), std::sin(p), std::cos(y) * std::cos(p));
}

glm::vec3 sun_direction(const render_params& p) {
  float a = glm::radians(p.sun_azimuth), e = glm::radians(p.sun_elevation);
  return glm::vec3(std::sin(a) * std::cos(e), std::sin(e), std::cos(a) * std::cos(e));
}

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

bool init_renderer(renderer_gpu& r) {
  const std::string bark_fs = lit_source(bark_fs_body), leaf_fs = lit_source(leaf_fs_body),
                    ground_fs = lit_source(ground_fs_body), sky_fs = sky_source(sky_fs_body),
                    occ_fs = sky_source(occlusion_fs_body);
  const std::string bark_vs_wind = with_wind_glsl(bark_vs), leaf_vs_wind = with_wind_glsl(leaf_vs);
  r.bark = compile_program("bark", bark_vs_wind.c_str(), bark_fs.c_str());
  r.bark_depth = compile_program("bark depth", bark_vs_wind.c_str(), depth_fs);
  r.leaf = compile_program("leaf", leaf_vs_wind.c_str(), leaf_fs.c_str());
  r.leaf_depth = compile_program("leaf depth", leaf_vs_wind.c_str(), leaf_depth_fs);
  r.sky = compile_program("sky", fullscreen_vs, sky_fs.c_str());
  r.ground = compile_program("ground", ground_vs, ground_fs.c_str());
  r.occlusion = compile_program("occlusion", fullscreen_vs, occ_fs.c_str());
  r.radial = compile_program("radial blur", fullscreen_vs, radial_fs);
  r.march = compile_program("light shafts", fullscreen_vs, march_source().c_str());
  r.exposure = compile_program("auto exposure", fullscreen_vs, exposure_fs);
  r.composite = compile_program("composite", fullscreen_vs, sky_source(composite_fs_body).c_str());
  init_overlays(r.overlay);
  r.fallback = compile_program("fallback", bark_vs_wind.c_str(), fallback_fs);
  if (r.composite.failed || r.fallback.failed) {
    r.error = "renderer: " + gl_last_message();
    r.ok = false;
  } else {
    r.ok = true;
  }

  glGenVertexArrays(1, &r.empty_vao.id);
  glGenVertexArrays(1, &r.bark_vao.id);
  glGenVertexArrays(1, &r.leaf_vao.id);
  for (gl_buffer* b : {&r.bark_position, &r.bark_normal, &r.bark_uv, &r.bark_node, &r.bark_ao, &r.bark_index,
                       &r.leaf_corner, &r.leaf_instances, &r.node_radius})
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

  // Leaves: a unit quad plus one leaf_instance per instance.
  const float corners[8] = {-0.5f, 0, 0.5f, 0, -0.5f, 1, 0.5f, 1};
  glBindVertexArray(r.leaf_vao.id);
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

  // Procedural textures (render/textures.h): the app needs no asset files. All archetype sets are
  // made once per process, on two threads.
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
  for (gl_program* p : {&r.bark, &r.bark_depth, &r.leaf, &r.leaf_depth, &r.sky, &r.ground, &r.occlusion, &r.radial,
                        &r.march, &r.exposure, &r.composite, &r.fallback})
    delete_gl(*p);
  for (gl_vertex_array* v : {&r.bark_vao, &r.leaf_vao, &r.empty_vao}) delete_gl(*v);
  for (gl_buffer* b : {&r.bark_position, &r.bark_normal, &r.bark_uv, &r.bark_node, &r.bark_ao, &r.bark_index,
                       &r.leaf_corner, &r.leaf_instances, &r.node_radius, &r.wind_nodes})
    delete_gl(*b);
  delete_gl(r.wind_tex);
  r.wind_node_count = 0;
  for (gl_texture* t : {&r.node_radius_tex, &r.bark_tex, &r.bark_normal_tex, &r.bark_rough_tex, &r.leaf_tex, &r.leaf_normal_tex,
                        &r.leaf_thickness_tex, &r.shadow_tex, &r.hdr_color, &r.hdr_depth, &r.occlusion_tex, &r.rays_tex, &r.march_tex,
                        &r.average_tex})
    delete_gl(*t);
  for (gl_framebuffer* f : {&r.shadow_fbo, &r.hdr_fbo, &r.occlusion_fbo, &r.rays_fbo, &r.march_fbo, &r.average_fbo, &r.msaa_fbo})
    delete_gl(*f);
  delete_gl(r.msaa_color);
  delete_gl(r.msaa_depth);
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

// ---------------------------------------------------------------- the frame

void draw_frame(renderer_gpu& r, const render_params& rp, const orbit_camera& cam, int width, int height,
                gl_framebuffer target, const overlay_view* overlays, glm::ivec2 origin) {
  if (width <= 0 || height <= 0) return;
  r.counts = {};
  const uint64_t uploads_before = r.uploads_total;
  resize_targets(r, width, height, rp.msaa);
  update_user_textures(r, rp);
  resize_shadow(r, std::clamp(rp.shadow_resolution, 256, 8192));
  update_sky(r, rp);
  const frame_setup f = setup_frame(r, rp, cam, width, height);
  r.triangles_drawn = r.index_end.empty() ? 0 : r.index_end[std::clamp(r.step, 0, int(r.index_end.size()) - 1)] / 3;
  r.leaves_drawn = leaf_count(r);
  glBindVertexArray(r.empty_vao.id);
  bind_tree_textures(r);
  draw_shadow_pass(r, rp, f);
  draw_lit_pass(r, rp, f, overlays);
  glDisable(GL_DEPTH_TEST);   // the passes from here on draw full-screen triangles
  glBindVertexArray(r.empty_vao.id);
  const shaft_choice sh = choose_shafts(r, rp, cam, f);
  r.timings.occlusion = r.timings.blur = r.timings.march = r.timings.exposure = 0;
  if (sh.rays) draw_radial_shafts(r, rp, f, sh);
  if (sh.volumetric) draw_volumetric_shafts(r, rp, f);
  if (rp.auto_exposure && !r.exposure.failed) draw_exposure_pass(r, f);
  draw_composite_pass(r, rp, f, sh, target, origin);
  r.counts.uploads = int(r.uploads_total - uploads_before);
  check_gl("draw frame");
}

}  // namespace sylva
