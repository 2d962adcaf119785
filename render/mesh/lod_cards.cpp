// Cluster cards baked from the tree's own leaves.
#include "render/mesh/lod_cards.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>

#include <glm/geometric.hpp>

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

leaf_texture_set bake_card(const leaf_instance* leaves, size_t n, const card_fit& c, int size) {
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
  for (size_t k = 0; k < n; ++k) {
    const leaf_instance& l = leaves[k];
    const leaf_texture_set& t = leaf_archetype_textures(leaf_archetype(std::clamp(int(l.texture), 0, leaf_archetype_count - 1)), 512);
    if (t.color.channels != 4 || t.color.width <= 0) continue;
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
        const size_t o = size_t(j) * size_t(size) + size_t(i);
        if (s <= depth[o]) continue;   // the leaf nearest the viewer on the card's front side shows
        depth[o] = s;
        for (int q = 0; q < 3; ++q) out.color.pixels[o * 4 + size_t(q)] = t.color.pixels[ti * 4 + size_t(q)];
        out.color.pixels[o * 4 + 3] = 255;
        // The leaf's normal (its map, in its frame; the side facing the card's front) in the card's frame.
        glm::vec3 m(128, 128, 255);
        if (t.normal.width == tw && t.normal.height == th && t.normal.channels >= 3)
          m = glm::vec3(t.normal.pixels[ti * size_t(t.normal.channels)], t.normal.pixels[ti * size_t(t.normal.channels) + 1],
                        t.normal.pixels[ti * size_t(t.normal.channels) + 2]);
        m = m / 127.5f - 1.0f;
        glm::vec3 w = g.x * m.x + g.y * m.y + g.z * m.z;
        if (facing < 0) w = -w;
        const glm::vec3 cn = glm::normalize(glm::vec3(glm::dot(w, f.x), glm::dot(w, f.y), std::max(glm::dot(w, f.z), 0.05f)));
        for (int q = 0; q < 3; ++q) out.normal.pixels[o * 3 + size_t(q)] = uint8_t(std::clamp((cn[q] + 1.0f) * 127.5f, 0.0f, 255.0f));
        const uint8_t thin = t.thickness.width == tw && t.thickness.channels >= 1 ? t.thickness.pixels[ti * size_t(t.thickness.channels)] : 128;
        for (int q = 0; q < 3; ++q) out.thickness.pixels[o * 3 + size_t(q)] = thin;
        mean_rgb += glm::vec3(t.color.pixels[ti * 4], t.color.pixels[ti * 4 + 1], t.color.pixels[ti * 4 + 2]);
        mean_n += 1;
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
