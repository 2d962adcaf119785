// Needle shoots as geometry (render/mesh/leaf_shoot.h): every prototype the same spike topology,
// each spike closed and facing out, the needles' texels opaque in every picture a reader gets,
// and the needle spread parting a fir's needles into two ranks.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "render/assets/textures.h"
#include "render/mesh/leaf_shoot.h"

using namespace sylva;

namespace {

constexpr leaf_archetype shoots[] = {leaf_archetype::needles, leaf_archetype::flat_spray, leaf_archetype::needle_tufts, leaf_archetype::lanceolate};

bool degenerate(const leaf_mesh& m, size_t piece) {
  const glm::vec3 a = m.vertex[piece * 4].position;
  for (size_t k = 1; k < 4; ++k)
    if (glm::length(m.vertex[piece * 4 + k].position - a) > 1e-7f) return false;
  return true;
}

// The directions of the needles (every live spike but the shoot axes, which sample the twig).
std::vector<glm::vec3> needle_directions(const leaf_mesh& m, const shoot_swatches& sw) {
  std::vector<glm::vec3> out;
  for (size_t p = 0; p < m.vertex.size() / 4; ++p) {
    if (degenerate(m, p) || m.vertex[p * 4].uv == sw.twig) continue;
    const glm::vec3 root = (m.vertex[p * 4].position + m.vertex[p * 4 + 1].position + m.vertex[p * 4 + 2].position) / 3.0f;
    out.push_back(glm::normalize(m.vertex[p * 4 + 3].position - root));
  }
  return out;
}

}  // namespace

TEST(LeafShoot, EveryPrototypeSharesOneSpikeTopology) {
  EXPECT_EQ(shoot_archetype_mask(), (1u << int(leaf_archetype::needles)) | (1u << int(leaf_archetype::flat_spray)) |
                                        (1u << int(leaf_archetype::needle_tufts)) | (1u << int(leaf_archetype::lanceolate)));
  EXPECT_FALSE(archetype_is_shoot(leaf_archetype::lobed));
  EXPECT_FALSE(archetype_is_shoot(leaf_archetype::scale_spray));
  for (leaf_archetype a : shoots)
    for (int pieces : {shoot_pieces_coarse, shoot_pieces_fine}) {
      const leaf_mesh m = shoot_prototype(a, leaf_blade_shape{true, 10, 15}, pieces, archetype_swatches(a));
      ASSERT_EQ(m.vertex.size(), size_t(pieces * shoot_piece_vertices)) << int(a);
      EXPECT_EQ(m.index, shoot_indices(pieces));
      EXPECT_EQ(m.index.size(), size_t(pieces * shoot_piece_triangles * 3));
      size_t live = 0;
      for (size_t p = 0; p < size_t(pieces); ++p) live += !degenerate(m, p);
      // The needle builders fill their budget: at most a few spikes left over; the willow's shoot
      // has its axis and 18 leaves whatever the budget.
      if (a == leaf_archetype::lanceolate) EXPECT_EQ(live, size_t(19)) << pieces;
      else EXPECT_GE(live, size_t(pieces) - 3) << int(a) << " " << pieces;
      for (const blade_vertex& v : m.vertex) {   // within about a card of the petiole
        EXPECT_LE(std::abs(v.position.x), 0.75f);
        EXPECT_GE(v.position.y, -0.3f);
        EXPECT_LE(v.position.y, 1.2f);
        EXPECT_LE(std::abs(v.position.z), 0.75f);
        EXPECT_NEAR(glm::length(v.normal), 1.0f, 1e-4f);
      }
    }
}

TEST(LeafShoot, SpikesAreClosedAndFaceOut) {
  for (leaf_archetype a : shoots) {
    const leaf_mesh m = shoot_prototype(a, leaf_blade_shape{true, 0, 0}, shoot_pieces_fine, archetype_swatches(a));
    size_t faces = 0, outward = 0;
    for (size_t p = 0; p < m.vertex.size() / 4; ++p) {
      if (degenerate(m, p)) continue;
      const glm::vec3 root = (m.vertex[p * 4].position + m.vertex[p * 4 + 1].position + m.vertex[p * 4 + 2].position) / 3.0f;
      const glm::vec3 tip = m.vertex[p * 4 + 3].position;
      for (size_t t = 0; t < 3; ++t) {
        const uint16_t* i = &m.index[(p * 3 + t) * 3];
        const glm::vec3 A = m.vertex[i[0]].position, B = m.vertex[i[1]].position, C = m.vertex[i[2]].position;
        const glm::vec3 n = glm::cross(B - A, C - A);
        // The face's centre lies off the spike's axis (root to tip); its normal must point away from it.
        const glm::vec3 centre = (A + B + C) / 3.0f, axis = glm::normalize(tip - root);
        const glm::vec3 off = centre - root - axis * glm::dot(centre - root, axis);
        ++faces;
        outward += glm::dot(n, off) > 0;
      }
    }
    EXPECT_GT(faces, size_t(50));   // the willow: 19 pieces; the needle shoots: 90 and more
    EXPECT_EQ(outward, faces) << int(a);
  }
}

// The spikes sample single texels: each must be opaque in the pictures the viewport (512 px) and the
// exports (other sizes and seeds) use, with opaque neighbours from 512 px up, the needles green.
TEST(LeafShoot, SwatchesAreOpaqueTexelsOfTheirColours) {
  for (leaf_archetype a : shoots)
    for (int size : {256, 512, 1024})
      for (uint64_t seed : {uint64_t(1), uint64_t(7)}) {
        const image& im = leaf_archetype_textures(a, size, seed).color;
        const shoot_swatches& sw = archetype_swatches(a, size, seed);
        auto texel = [&](glm::vec2 uv, int dx, int dy) {
          const int x = int(uv.x * float(im.width)) + dx, y = int(uv.y * float(im.height)) + dy;
          return &im.pixels[(size_t(y) * size_t(im.width) + size_t(x)) * 4];
        };
        for (glm::vec2 uv : {sw.needle[0], sw.needle[1], sw.needle[2], sw.twig}) {
          EXPECT_EQ(texel(uv, 0, 0)[3], 255) << int(a) << " " << size << " " << seed;
          // From the viewport's 512 px up, the needles are wide enough for opaque neighbours too.
          if (size >= 512)
            for (int dy = -1; dy <= 1; ++dy)
              for (int dx = -1; dx <= 1; ++dx) EXPECT_EQ(texel(uv, dx, dy)[3], 255) << int(a) << " " << size << " " << seed;
          // At the texel's centre, so bilinear filtering reads it alone.
          EXPECT_NEAR(std::fmod(uv.x * float(im.width), 1.0f), 0.5f, 1e-3f);
        }
        const uint8_t* needle = texel(sw.needle[1], 0, 0);
        EXPECT_GT(int(needle[1]), int(needle[0])) << "needles are green";
        // The three tones run light to dark.
        auto luminance = [&](glm::vec2 uv) { const uint8_t* p = texel(uv, 0, 0); return 2 * p[0] + 5 * p[1] + p[2]; };
        EXPECT_GE(luminance(sw.needle[0]), luminance(sw.needle[1]));
        EXPECT_GE(luminance(sw.needle[1]), luminance(sw.needle[2]));
      }
  // A picture with nothing opaque samples its centre.
  image empty{8, 8, 4, std::vector<uint8_t>(8 * 8 * 4, 0)};
  EXPECT_EQ(swatches_of(empty).twig, glm::vec2(0.5f));
}

// Spread 360 stands the spray's needles all round each shoot (some point up, some down out of the
// card's plane); a fir's 160 parts them into two ranks to the sides, raised, none hanging below.
TEST(LeafShoot, NeedleSpreadPartsTheNeedlesIntoTwoRanks) {
  const shoot_swatches& sw = archetype_swatches(leaf_archetype::flat_spray);
  auto share_below = [&](float spread) {
    leaf_blade_shape s{true, 0, 0};
    s.needle_spread = spread;
    const std::vector<glm::vec3> d = needle_directions(shoot_prototype(leaf_archetype::flat_spray, s, shoot_pieces_fine, sw), sw);
    size_t below = 0;
    for (const glm::vec3& v : d) below += v.z < -0.3f;
    return std::pair(d.size(), below);
  };
  const auto [round_count, round_below] = share_below(360);
  const auto [ranked_count, ranked_below] = share_below(160);
  ASSERT_GT(round_count, size_t(60));
  EXPECT_GT(round_below * 6, round_count) << "all round: more than a sixth point down";
  EXPECT_EQ(ranked_below, size_t(0)) << "two raised ranks: none point down";
  // A NaN spread is all round, not a crash or an empty shoot.
  leaf_blade_shape nan_shape{true, 0, 0};
  nan_shape.needle_spread = std::nanf("");
  EXPECT_EQ(needle_directions(shoot_prototype(leaf_archetype::flat_spray, nan_shape, shoot_pieces_fine, sw), sw).size(), round_count);
}

// The curl droops the shoot: the main axis' tip goes down (-Z) and stays about as far away.
TEST(LeafShoot, CurlDroopsTheShoot) {
  const shoot_swatches& sw = archetype_swatches(leaf_archetype::needles);
  const leaf_mesh straight = shoot_prototype(leaf_archetype::needles, leaf_blade_shape{true, 0, 0}, shoot_pieces_coarse, sw);
  const leaf_mesh bent = shoot_prototype(leaf_archetype::needles, leaf_blade_shape{true, 0, 40}, shoot_pieces_coarse, sw);
  const glm::vec3 a = straight.vertex[3].position, b = bent.vertex[3].position;   // spike 0 is the shoot axis
  EXPECT_NEAR(a.z, 0.0f, 1e-5f);
  EXPECT_LT(b.z, -0.05f);
  EXPECT_NEAR(glm::length(b), glm::length(a), 1e-4f);
}
