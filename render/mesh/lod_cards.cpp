// Cluster cards baked from the tree's own leaves.
#include "render/mesh/lod_cards.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>

#include <glm/geometric.hpp>

#include "render/mesh/leaf_shoot.h"
#include "render/mesh/season.h"

namespace sylva {
namespace {

glm::vec3 rotate(const glm::vec4& q, const glm::vec3& v) {
  const glm::vec3 u(q.x, q.y, q.z);
  return v + 2.0f * glm::cross(u, glm::cross(u, v) + q.w * v);
}

struct frame {
  glm::vec3 x, y, z;
  explicit frame(const glm::vec4& q) : x(rotate(q, {1, 0, 0})), y(rotate(q, {0, 1, 0})), z(rotate(q, {0, 0, 1})) {}
};

// The leaf prototypes a card is baked from when the leaves are geometry: per archetype, its coarse
// blade (render/mesh/leaf_blade.h) or needle shoot (render/mesh/leaf_shoot.h), as the viewport
// draws them; empty for fruit, which keeps the flat card.
struct card_prototypes {
  leaf_blade_shape shape;
  std::array<leaf_mesh, leaf_archetype_count> mesh;
  std::array<bool, leaf_archetype_count> made{};
  const leaf_mesh& of(int k) {
    if (!made[size_t(k)]) {
      made[size_t(k)] = true;
      const leaf_archetype a = leaf_archetype(k);
      if (archetype_is_fruit(a)) {
      } else if (archetype_is_shoot(a)) {
        mesh[size_t(k)] = shoot_prototype(a, shape, shoot_pieces_coarse, archetype_swatches(a));
      } else {
        const auto grid = coarse_blade(archetype_outline(a), shape);
        mesh[size_t(k)].vertex.assign(grid.begin(), grid.end());
        mesh[size_t(k)].index.assign(coarse_blade_indices().begin(), coarse_blade_indices().end());
      }
    }
    return mesh[size_t(k)];
  }
};

// The texel a leaf wins on the card: colour from its picture, its normal (world) turned into the
// card's frame, facing the card's front, and its thickness.
struct card_target {
  leaf_texture_set& out;
  std::vector<float>& depth;
  glm::vec3& mean_rgb;
  float& mean_n;
  const frame& f;
  void put(size_t o, float s, const leaf_texture_set& t, size_t ti, glm::vec3 w) {
    if (s <= depth[o]) return;   // the leaf nearest the viewer on the card's front side shows
    depth[o] = s;
    for (int q = 0; q < 3; ++q) out.color.pixels[o * 4 + size_t(q)] = t.color.pixels[ti * 4 + size_t(q)];
    out.color.pixels[o * 4 + 3] = 255;
    const glm::vec3 cn = glm::normalize(glm::vec3(glm::dot(w, f.x), glm::dot(w, f.y), std::max(glm::dot(w, f.z), 0.05f)));
    for (int q = 0; q < 3; ++q) out.normal.pixels[o * 3 + size_t(q)] = uint8_t(std::clamp((cn[q] + 1.0f) * 127.5f, 0.0f, 255.0f));
    const uint8_t thin = t.thickness.width == t.color.width && t.thickness.channels >= 1 ? t.thickness.pixels[ti * size_t(t.thickness.channels)] : 128;
    for (int q = 0; q < 3; ++q) out.thickness.pixels[o * 3 + size_t(q)] = thin;
    mean_rgb += glm::vec3(t.color.pixels[ti * 4], t.color.pixels[ti * 4 + 1], t.color.pixels[ti * 4 + 2]);
    mean_n += 1;
  }
};

// The picture's normal map at texel ti, in the frame (x across, y up the picture, n out of it).
glm::vec3 mapped_normal(const leaf_texture_set& t, size_t ti, glm::vec3 x, glm::vec3 y, glm::vec3 n) {
  glm::vec3 m(128, 128, 255);
  if (t.normal.width == t.color.width && t.normal.height == t.color.height && t.normal.channels >= 3)
    m = glm::vec3(t.normal.pixels[ti * size_t(t.normal.channels)], t.normal.pixels[ti * size_t(t.normal.channels) + 1],
                  t.normal.pixels[ti * size_t(t.normal.channels) + 2]);
  m = m / 127.5f - 1.0f;
  return x * m.x + y * m.y + n * m.z;
}

// Rasterises one leaf's prototype mesh orthographically onto the card (texel centres inside each
// triangle, its picture sampled at the interpolated coordinates, cut out at alpha 128).
void bake_leaf_mesh(card_target& c, const leaf_instance& l, const leaf_mesh& m, const leaf_texture_set& t, const card_fit& fit, int size) {
  const frame g(l.orientation);
  const float side = std::max(fit.size, 1e-6f);
  struct projected {
    glm::vec2 at;   // texel units: i across, j down
    float s;        // along the card's normal
    glm::vec3 normal;
    glm::vec2 uv;
  };
  std::vector<projected> v(m.vertex.size());
  for (size_t k = 0; k < v.size(); ++k) {
    const blade_vertex& b = m.vertex[k];
    const glm::vec3 p = l.position + rotate(l.orientation, b.position * l.size) - fit.position;
    v[k] = {glm::vec2((glm::dot(p, c.f.x) / side + 0.5f) * float(size), (1.0f - glm::dot(p, c.f.y) / side) * float(size)),
            glm::dot(p, c.f.z), rotate(l.orientation, b.normal), b.uv};
  }
  const int tw = t.color.width, th = t.color.height;
  for (size_t k = 0; k + 2 < m.index.size(); k += 3) {
    const projected &A = v[m.index[k]], &B = v[m.index[k + 1]], &C = v[m.index[k + 2]];
    const float area = (B.at.x - A.at.x) * (C.at.y - A.at.y) - (B.at.y - A.at.y) * (C.at.x - A.at.x);
    if (!(std::abs(area) > 1e-9f)) continue;   // edge-on or collapsed (a shoot's unused spikes)
    const int i0 = std::max(0, int(std::floor(std::min({A.at.x, B.at.x, C.at.x}) - 0.5f)));
    const int i1 = std::min(size - 1, int(std::ceil(std::max({A.at.x, B.at.x, C.at.x}) + 0.5f)));
    const int j0 = std::max(0, int(std::floor(std::min({A.at.y, B.at.y, C.at.y}) - 0.5f)));
    const int j1 = std::min(size - 1, int(std::ceil(std::max({A.at.y, B.at.y, C.at.y}) + 0.5f)));
    // A texel counts when its centre lies within half a texel of the triangle: a needle thinner than
    // a texel still leaves its line on the card, as the viewport's multisampled needle does.
    const float reach[3] = {0.5f * glm::length(C.at - B.at) / std::abs(area), 0.5f * glm::length(A.at - C.at) / std::abs(area),
                            0.5f * glm::length(B.at - A.at) / std::abs(area)};
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i) {
        const glm::vec2 q(float(i) + 0.5f, float(j) + 0.5f);
        float wa = ((B.at.x - q.x) * (C.at.y - q.y) - (B.at.y - q.y) * (C.at.x - q.x)) / area;
        float wb = ((C.at.x - q.x) * (A.at.y - q.y) - (C.at.y - q.y) * (A.at.x - q.x)) / area;
        float wc = 1.0f - wa - wb;
        if (wa < -reach[0] || wb < -reach[1] || wc < -reach[2]) continue;
        wa = std::max(wa, 0.0f), wb = std::max(wb, 0.0f), wc = std::max(wc, 0.0f);
        const float sum = std::max(wa + wb + wc, 1e-6f);
        wa /= sum, wb /= sum, wc /= sum;
        const glm::vec2 uv = wa * A.uv + wb * B.uv + wc * C.uv;
        const int tx = std::clamp(int(uv.x * float(tw)), 0, tw - 1), ty = std::clamp(int(uv.y * float(th)), 0, th - 1);
        const size_t ti = size_t(ty) * size_t(tw) + size_t(tx);
        if (t.color.pixels[ti * 4 + 3] < 128) continue;
        glm::vec3 n = wa * A.normal + wb * B.normal + wc * C.normal;
        n = glm::length(n) > 1e-6f ? glm::normalize(n) : g.z;
        if (glm::dot(n, c.f.z) < 0) n = -n;   // the side facing the card's front
        glm::vec3 x = g.x - n * glm::dot(n, g.x);
        x = glm::length(x) > 1e-6f ? glm::normalize(x) : g.x;
        c.put(size_t(j) * size_t(size) + size_t(i), wa * A.s + wb * B.s + wc * C.s, t, ti, mapped_normal(t, ti, x, glm::cross(n, x), n));
      }
  }
}

}  // namespace

float opaque_share(const image& im) {
  const size_t all = size_t(im.width) * size_t(im.height);
  if (im.channels != 4 || all == 0) return 1.0f;
  size_t n = 0;
  for (size_t i = 0; i < all; ++i) n += im.pixels[i * 4 + 3] >= 128;
  return std::max(float(n) / float(all), 0.01f);
}

float archetype_opaque_share(int archetype) {
  // Thread-safe: the worker and the export jobs may both ask; a race only measures twice.
  static std::array<std::atomic<float>, leaf_archetype_count> cache{};
  const int a = std::clamp(archetype, 0, leaf_archetype_count - 1);
  if (const float c = cache[size_t(a)].load(std::memory_order_relaxed); c > 0) return c;
  const float c = opaque_share(leaf_archetype_textures(leaf_archetype(a), 512).color);
  cache[size_t(a)].store(c, std::memory_order_relaxed);
  return c;
}

card_fit fit_card(const leaf_instance* leaves, size_t n, const glm::vec4& orientation) {
  card_fit c;
  if (n == 0) return c;
  c.orientation = orientation;
  const frame f(c.orientation);
  const glm::vec3 ref = leaves[0].position;
  float lo_x = 1e30f, hi_x = -1e30f, lo_y = 1e30f, hi_y = -1e30f, projected = 0;
  for (size_t k = 0; k < n; ++k) {
    const leaf_instance& l = leaves[k];
    const frame g(l.orientation);
    for (float cx : {-0.5f, 0.5f})
      for (float cy : {0.0f, 1.0f}) {
        const glm::vec3 p = l.position + (g.x * cx + g.y * cy) * l.size - ref;
        const float px = glm::dot(p, f.x), py = glm::dot(p, f.y);
        lo_x = std::min(lo_x, px), hi_x = std::max(hi_x, px), lo_y = std::min(lo_y, py), hi_y = std::max(hi_y, py);
      }
    // The leaf's opaque area as seen along the card's normal.
    projected += l.size * l.size * archetype_opaque_share(l.texture) * std::abs(glm::dot(g.z, f.z));
  }
  c.size = std::max({hi_x - lo_x, hi_y - lo_y, 1e-6f});
  if (!std::isfinite(c.size) || !std::isfinite(projected)) return card_fit{orientation, ref, 1e-6f, 0.0f};   // bad leaves
  const float mx = 0.5f * (lo_x + hi_x), my = 0.5f * (lo_y + hi_y);
  c.position = ref + f.x * mx + f.y * (my - 0.5f * c.size);
  // Leaves scattered at random over the square overlap as a Poisson process: the covered share of
  // the square is 1 - exp(-(opaque area) / (square's area)).
  c.coverage = 1.0f - std::exp(-projected / (c.size * c.size));
  return c;
}

leaf_texture_set bake_card(const leaf_instance* leaves, size_t n, const card_fit& c, int size, const leaf_blade_shape& shape) {
  size = std::clamp(size, 8, 4096);
  leaf_texture_set out;
  for (image* im : {&out.color, &out.normal, &out.thickness}) {
    im->width = im->height = size;
    im->channels = im == &out.color ? 4 : 3;
    im->pixels.assign(size_t(size) * size_t(size) * size_t(im->channels), 0);
  }
  std::vector<float> depth(size_t(size) * size_t(size), -1e30f);
  const frame f(c.orientation);
  const float side = std::max(c.size, 1e-6f);
  // Texel (i, j), row j from the top: card point a = (i + 0.5) / size - 0.5 across, b = 1 - (j + 0.5)
  // / size up (the leaf shader's v_uv = (x + 0.5, 1 - y)).
  glm::vec3 mean_rgb(0);
  float mean_n = 0;
  card_target target{out, depth, mean_rgb, mean_n, f};
  card_prototypes protos{shape, {}, {}};
  for (size_t k = 0; k < n; ++k) {
    const leaf_instance& l = leaves[k];
    const int archetype = std::clamp(int(l.texture), 0, leaf_archetype_count - 1);
    const leaf_texture_set& t = leaf_archetype_textures(leaf_archetype(archetype), 512);
    if (t.color.channels != 4 || t.color.width <= 0) continue;
    if (shape.on && !protos.of(archetype).vertex.empty()) {   // the leaf as the viewport draws it
      if (l.size > 0) bake_leaf_mesh(target, l, protos.of(archetype), t, c, size);
      continue;
    }
    const frame g(l.orientation);
    const float facing = glm::dot(g.z, f.z);
    if (std::abs(facing) < 0.05f || !(l.size > 0)) continue;   // edge-on: a sliver the card cannot hold
    // The leaf's projected corners bound the texels to test.
    float lo_i = 1e30f, hi_i = -1e30f, lo_j = 1e30f, hi_j = -1e30f;
    for (float cx : {-0.5f, 0.5f})
      for (float cy : {0.0f, 1.0f}) {
        const glm::vec3 p = l.position + (g.x * cx + g.y * cy) * l.size - c.position;
        const float a = glm::dot(p, f.x) / side + 0.5f, b = glm::dot(p, f.y) / side;
        lo_i = std::min(lo_i, a * float(size)), hi_i = std::max(hi_i, a * float(size));
        lo_j = std::min(lo_j, (1 - b) * float(size)), hi_j = std::max(hi_j, (1 - b) * float(size));
      }
    if (!(std::isfinite(lo_i) && std::isfinite(hi_i) && std::isfinite(lo_j) && std::isfinite(hi_j))) continue;
    lo_i = std::max(lo_i, -1.0f), lo_j = std::max(lo_j, -1.0f);
    hi_i = std::min(hi_i, float(size)), hi_j = std::min(hi_j, float(size));
    const int i0 = std::max(0, int(std::floor(lo_i))), i1 = std::min(size - 1, int(std::ceil(hi_i)));
    const int j0 = std::max(0, int(std::floor(lo_j))), j1 = std::min(size - 1, int(std::ceil(hi_j)));
    const int tw = t.color.width, th = t.color.height;
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i) {
        const float a = (float(i) + 0.5f) / float(size) - 0.5f, b = 1.0f - (float(j) + 0.5f) / float(size);
        const glm::vec3 p = c.position + (f.x * a + f.y * b) * side;
        // Along the card's normal onto the leaf's plane: p + s z.
        const float s = glm::dot(l.position - p, g.z) / facing;
        const glm::vec3 h = p + f.z * s - l.position;
        const float la = glm::dot(h, g.x) / l.size + 0.5f, lb = glm::dot(h, g.y) / l.size;
        if (la < 0 || la >= 1 || lb < 0 || lb >= 1) continue;
        const int tx = std::min(tw - 1, int(la * float(tw))), ty = std::min(th - 1, int((1 - lb) * float(th)));
        const size_t ti = size_t(ty) * size_t(tw) + size_t(tx);
        if (t.color.pixels[ti * 4 + 3] < 128) continue;
        // The leaf's normal (its map, in its frame; the side facing the card's front) in the card's frame.
        glm::vec3 w = mapped_normal(t, ti, g.x, g.y, g.z);
        if (facing < 0) w = -w;
        target.put(size_t(j) * size_t(size) + size_t(i), s, t, ti, w);
      }
  }
  // Uncovered texels take the mean leaf colour and a flat normal, so that filtering at the cut-out's
  // edge blends toward leaf colour, not black.
  const glm::vec3 fill = mean_n > 0 ? mean_rgb / mean_n : glm::vec3(90, 120, 60);
  for (size_t o = 0; o < depth.size(); ++o) {
    if (depth[o] > -1e29f) continue;
    for (int q = 0; q < 3; ++q) out.color.pixels[o * 4 + size_t(q)] = uint8_t(fill[q]);
    out.normal.pixels[o * 3] = out.normal.pixels[o * 3 + 1] = 128, out.normal.pixels[o * 3 + 2] = 255;
    for (int q = 0; q < 3; ++q) out.thickness.pixels[o * 3 + size_t(q)] = 128;
  }
  return out;
}

}  // namespace sylva
