// Archetype texture sets: determinism, the cache, plausible leaf cut-outs, seamless bark,
// valid normal maps, the tint formula, and the checks on users' texture files.
#include <iterator>
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "render/assets/textures.h"
#include "render/mesh/season.h"
#include "tests/run_sylva.h"
#include "tests/scratch_dir.h"

using namespace sylva;

namespace {

constexpr int kSize = 256;  // big enough for the shapes, small enough to keep the tests quick

float srgb_to_linear(uint8_t b) {
  const float c = float(b) / 255.0f;
  return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

double coverage(const image& rgba) {  // share of the card at least half opaque
  size_t n = 0;
  for (size_t k = 0; k < size_t(rgba.width) * rgba.height; ++k) n += rgba.pixels[k * 4 + 3] >= 128;
  return double(n) / double(size_t(rgba.width) * rgba.height);
}

std::vector<bool> mask(const image& rgba) {
  std::vector<bool> m(size_t(rgba.width) * rgba.height);
  for (size_t k = 0; k < m.size(); ++k) m[k] = rgba.pixels[k * 4 + 3] >= 128;
  return m;
}

// Mean absolute difference per channel between rows (or columns) a and b of an image.
double line_difference(const image& img, bool rows, int a, int b) {
  const int n = rows ? img.width : img.height;
  double sum = 0;
  for (int i = 0; i < n; ++i)
    for (int c = 0; c < img.channels; ++c) {
      const size_t pa = rows ? (size_t(a) * img.width + i) : (size_t(i) * img.width + a);
      const size_t pb = rows ? (size_t(b) * img.width + i) : (size_t(i) * img.width + b);
      sum += std::abs(int(img.pixels[pa * img.channels + c]) - int(img.pixels[pb * img.channels + c]));
    }
  return sum / double(n * img.channels);
}

// The seam (last line against the first) compared with the mean difference of neighbouring
// interior lines; a tiling image has a seam no worse than its interior.
double seam_ratio(const image& img, bool rows) {
  const int n = rows ? img.height : img.width;
  double interior = 0;
  for (int i = 0; i + 1 < n; ++i) interior += line_difference(img, rows, i, i + 1);
  interior /= double(n - 1);
  return line_difference(img, rows, n - 1, 0) / std::max(interior, 1e-9);
}

image crop(const image& img, int w, int h) {  // the top-left w x h corner
  image out{w, h, img.channels, {}};
  for (int y = 0; y < h; ++y)
    out.pixels.insert(out.pixels.end(), img.pixels.begin() + ptrdiff_t(size_t(y) * img.width * img.channels),
                      img.pixels.begin() + ptrdiff_t((size_t(y) * img.width + w) * img.channels));
  return out;
}

void expect_unit_normals(const image& nm, const std::string& what) {
  ASSERT_EQ(nm.channels, 3) << what;
  double worst = 0;
  size_t tilted = 0;
  for (size_t k = 0; k < size_t(nm.width) * nm.height; ++k) {
    const float x = nm.pixels[k * 3] / 127.5f - 1, y = nm.pixels[k * 3 + 1] / 127.5f - 1, z = nm.pixels[k * 3 + 2] / 127.5f - 1;
    worst = std::max(worst, double(std::abs(std::sqrt(x * x + y * y + z * z) - 1)));
    ASSERT_GT(z, 0.0f) << what << ": a normal pointing into the surface at texel " << k;
    tilted += z < 0.98f;
  }
  EXPECT_LT(worst, 0.03) << what;
  EXPECT_GT(tilted, size_t(nm.width) * nm.height / 50) << what << ": almost flat, no relief";
}

// A file in this process's scratch folder (tests/scratch_dir.h), removed when the process exits.
std::string temp_file(const std::string& name) {
  static const std::filesystem::path dir = [] {
    const std::filesystem::path d = sylva_test::scratch_path("sylva_textures_test");
    std::filesystem::create_directories(d);
    return d;
  }();
  return (dir / name).string();
}

}  // namespace

TEST(ArchetypeTextures, SameKeyGivesTheSameTexelsAndAnotherSeedDiffers) {
  for (int i = 0; i < leaf_archetype_count; ++i) {
    const leaf_texture_set a = make_leaf_archetype_textures(leaf_archetype(i), 64, 7);
    const leaf_texture_set b = make_leaf_archetype_textures(leaf_archetype(i), 64, 7);
    EXPECT_EQ(a.color.pixels, b.color.pixels) << leaf_archetype_names[i];
    EXPECT_EQ(a.normal.pixels, b.normal.pixels) << leaf_archetype_names[i];
    EXPECT_EQ(a.thickness.pixels, b.thickness.pixels) << leaf_archetype_names[i];
    EXPECT_NE(make_leaf_archetype_textures(leaf_archetype(i), 64, 8).color.pixels, a.color.pixels) << leaf_archetype_names[i];
  }
  for (int i = 0; i < bark_archetype_count; ++i) {
    const bark_texture_set a = make_bark_archetype_textures(bark_archetype(i), 64, 7);
    const bark_texture_set b = make_bark_archetype_textures(bark_archetype(i), 64, 7);
    EXPECT_EQ(a.color.pixels, b.color.pixels) << bark_archetype_names[i];
    EXPECT_EQ(a.normal.pixels, b.normal.pixels) << bark_archetype_names[i];
    EXPECT_EQ(a.roughness.pixels, b.roughness.pixels) << bark_archetype_names[i];
    EXPECT_NE(make_bark_archetype_textures(bark_archetype(i), 64, 8).color.pixels, a.color.pixels) << bark_archetype_names[i];
  }
}

TEST(ArchetypeTextures, CacheReturnsOneObjectPerKeyEqualToAFreshSet) {
  const leaf_texture_set& a = leaf_archetype_textures(leaf_archetype::lobed, 64, 3);
  EXPECT_EQ(&a, &leaf_archetype_textures(leaf_archetype::lobed, 64, 3));
  EXPECT_NE(&a, &leaf_archetype_textures(leaf_archetype::lobed, 64, 4));
  EXPECT_NE(&a, &leaf_archetype_textures(leaf_archetype::ovate, 64, 3));
  EXPECT_EQ(a.color.pixels, make_leaf_archetype_textures(leaf_archetype::lobed, 64, 3).color.pixels);
  const bark_texture_set& b = bark_archetype_textures(bark_archetype::ringed, 64, 3);
  EXPECT_EQ(&b, &bark_archetype_textures(bark_archetype::ringed, 64, 3));
  EXPECT_EQ(b.normal.pixels, make_bark_archetype_textures(bark_archetype::ringed, 64, 3).normal.pixels);
  // Filling the cache on two threads gives the sets a single thread makes.
  prepare_archetype_textures(64, 11, 2);
  EXPECT_EQ(leaf_archetype_textures(leaf_archetype::needles, 64, 11).color.pixels,
            make_leaf_archetype_textures(leaf_archetype::needles, 64, 11).color.pixels);
}

TEST(ArchetypeTextures, MapsHaveTheDocumentedSizesAndChannels) {
  for (int i = 0; i < leaf_archetype_count; ++i) {
    const leaf_texture_set& s = leaf_archetype_textures(leaf_archetype(i), 512);
    EXPECT_EQ(s.color.width, 512);
    EXPECT_EQ(s.color.height, 512);
    EXPECT_EQ(s.color.channels, 4);
    EXPECT_EQ(s.normal.channels, 3);
    EXPECT_EQ(s.thickness.channels, 3);
    EXPECT_EQ(s.color.pixels.size(), size_t(512) * 512 * 4);
    EXPECT_EQ(s.thickness.pixels.size(), size_t(512) * 512 * 3);
  }
  for (int i = 0; i < bark_archetype_count; ++i) {
    const bark_texture_set& s = bark_archetype_textures(bark_archetype(i), 512);
    EXPECT_EQ(s.color.width, 512);
    EXPECT_EQ(s.color.channels, 3);
    EXPECT_EQ(s.roughness.pixels.size(), size_t(512) * 512 * 3);
    for (size_t k = 0; k < s.roughness.pixels.size(); k += 3) ASSERT_EQ(s.roughness.pixels[k + 2], 0) << "metalness";
  }
}

TEST(ArchetypeTextures, LeafCardsCoverAPlausibleShareOfTheCard) {
  struct range { double lo, hi; };
  const range expected[] = {
      {0.30, 0.75},  // ovate
      {0.30, 0.75},  // lobed
      {0.30, 0.75},  // palmate
      {0.15, 0.60},  // pinnate: leaflets and the gaps between them
      {0.06, 0.45},  // needles: 22 open V-shaped pairs, much sky between them
      {0.12, 0.50},  // flat spray
      {0.15, 0.60},  // scale spray
      {0.04, 0.30},  // palm frond: three narrow leaflets
      {0.25, 0.75},  // twig cluster
      {0.08, 0.45},  // needle tufts
      {0.10, 0.45},  // lanceolate: narrow blades on a shoot
      {0.20, 0.70},  // beech spray
      {0.25, 0.75},  // hazel spray
      {0.15, 0.65},  // poplar spray
      {0.12, 0.30},  // cone_hanging: a slim cylinder on a stalk
      {0.15, 0.40},  // cone_upright: a broader barrel
      {0.10, 0.45},  // samaras: wings with sky between the pairs
      {0.10, 0.45},  // hazelnuts: three nuts in husks
      {0.10, 0.35},  // cone_ovoid: a short egg on a stalk
      {0.08, 0.35},  // beechnuts: two bristly cupules
      {0.15, 0.50},  // coconuts: a bunch of big nuts
      {0.15, 0.60},  // maple spray: three opposite pairs on a shoot, sky between the pairs
      {0.08, 0.40},  // ash keys: a bunch of narrow keys, sky between them
      {0.12, 0.35},  // cone_barrel: a squat barrel on a short stalk
      {0.06, 0.30},  // acorns: three acorns on a long stalk
      {0.25, 0.60},  // horse chestnut: seven leaflets fanned on a long petiole, sky between them
      {0.15, 0.45},  // cypress cones: three balls on a short twig
      {0.18, 0.55},  // birch: a triangular blade on a long petiole
  };
  static_assert(std::size(expected) == size_t(leaf_archetype_count), "a range per archetype");
  for (int i = 0; i < leaf_archetype_count; ++i) {
    const image& c = leaf_archetype_textures(leaf_archetype(i), kSize).color;
    const double cov = coverage(c);
    EXPECT_GE(cov, expected[i].lo) << leaf_archetype_names[i];
    EXPECT_LE(cov, expected[i].hi) << leaf_archetype_names[i];
    // The petiole (or stem) enters at the bottom edge's centre; the top-left corner is empty.
    bool stem = false;
    for (int x = kSize / 2 - kSize / 8; x < kSize / 2 + kSize / 8; ++x) stem |= c.pixels[(size_t(kSize - 2) * kSize + x) * 4 + 3] >= 128;
    EXPECT_TRUE(stem) << leaf_archetype_names[i] << ": nothing at the bottom edge's centre";
    EXPECT_EQ(c.pixels[3], 0) << leaf_archetype_names[i];
  }
}

// Needle cards are fine structure: most of their opaque texels lie within 2 texels of the sky,
// where a blade's lie deep inside it.
TEST(ArchetypeTextures, NeedleCardsAreFineWithSkyBetweenTheNeedles) {
  auto near_sky = [](const image& c) {
    const int n = c.width;
    auto opaque = [&](int x, int y) { return x < 0 || y < 0 || x >= n || y >= n ? false : c.pixels[(size_t(y) * n + x) * 4 + 3] >= 128; };
    size_t solid = 0, edge = 0;
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) {
        if (!opaque(x, y)) continue;
        ++solid;
        bool sky = false;
        for (int dy = -2; dy <= 2 && !sky; ++dy)
          for (int dx = -2; dx <= 2 && !sky; ++dx) sky = !opaque(x + dx, y + dy);
        edge += sky;
      }
    return solid ? double(edge) / double(solid) : 0.0;
  };
  for (leaf_archetype a : {leaf_archetype::needles, leaf_archetype::flat_spray, leaf_archetype::needle_tufts})
    EXPECT_GT(near_sky(leaf_archetype_textures(a, 512).color), 0.6) << leaf_archetype_names[int(a)];
  for (leaf_archetype a : {leaf_archetype::ovate, leaf_archetype::lobed})
    EXPECT_LT(near_sky(leaf_archetype_textures(a, 512).color), 0.2) << leaf_archetype_names[int(a)];
}

// Beech's mottled bark has no lenticel dashes: almost no texel is far darker than the tile's mean,
// where birch's smooth bark has many.
TEST(ArchetypeTextures, MottledBarkHasNoDarkDashesWhereSmoothHasThem) {
  auto dark_share = [](const image& c) {
    double mean = 0;
    const size_t count = size_t(c.width) * size_t(c.height);
    for (size_t k = 0; k < count; ++k) mean += c.pixels[k * 3 + 1];
    mean /= double(count);
    size_t dark = 0;
    for (size_t k = 0; k < count; ++k) dark += c.pixels[k * 3 + 1] < 0.6 * mean;
    return double(dark) / double(count);
  };
  EXPECT_LT(dark_share(bark_archetype_textures(bark_archetype::mottled, kSize).color), 0.01);
  EXPECT_GT(dark_share(bark_archetype_textures(bark_archetype::smooth, kSize).color), 0.03);
}

TEST(ArchetypeTextures, LeafArchetypesDifferFromEachOther) {
  std::vector<std::vector<bool>> masks;
  for (int i = 0; i < leaf_archetype_count; ++i) masks.push_back(mask(leaf_archetype_textures(leaf_archetype(i), kSize).color));
  for (int i = 0; i < leaf_archetype_count; ++i)
    for (int j = i + 1; j < leaf_archetype_count; ++j) {
      size_t both = 0, either = 0;
      for (size_t k = 0; k < masks[i].size(); ++k) both += masks[i][k] && masks[j][k], either += masks[i][k] || masks[j][k];
      const double iou = double(both) / double(std::max<size_t>(either, 1));
      EXPECT_LT(iou, 0.8) << leaf_archetype_names[i] << " vs " << leaf_archetype_names[j] << ": outlines overlap too much";
    }
  for (int i = 0; i < bark_archetype_count; ++i)
    for (int j = i + 1; j < bark_archetype_count; ++j) {
      const image& a = bark_archetype_textures(bark_archetype(i), kSize).normal;
      const image& b = bark_archetype_textures(bark_archetype(j), kSize).normal;
      double diff = 0;
      for (size_t k = 0; k < a.pixels.size(); ++k) diff += std::abs(int(a.pixels[k]) - int(b.pixels[k]));
      EXPECT_GT(diff / double(a.pixels.size()), 3.0) << bark_archetype_names[i] << " vs " << bark_archetype_names[j];
    }
}

TEST(ArchetypeTextures, LeafColourIsNearAMidGreenWithVeinsEdgesAndNoDarkFringe) {
  for (int i = 0; i < leaf_archetype_count; ++i) {
    if (archetype_is_fruit(leaf_archetype(i))) continue;   // final colours: FruitCardsAreInTheirOwnColours
    const image& c = leaf_archetype_textures(leaf_archetype(i), kSize).color;
    double sum[3] = {0, 0, 0}, count = 0, sq = 0;
    double outside_min = 1e9;
    for (size_t k = 0; k < size_t(kSize) * kSize; ++k) {
      const uint8_t* p = &c.pixels[k * 4];
      if (p[3] == 255) {
        for (int ch = 0; ch < 3; ++ch) sum[ch] += srgb_to_linear(p[ch]);
        sq += double(srgb_to_linear(p[1])) * srgb_to_linear(p[1]);
        ++count;
      } else if (p[3] == 0) {
        outside_min = std::min(outside_min, double(srgb_to_linear(p[1])));
      }
    }
    ASSERT_GT(count, 0) << leaf_archetype_names[i];
    const double r = sum[0] / count, g = sum[1] / count, b = sum[2] / count;
    EXPECT_GT(g, r) << leaf_archetype_names[i] << ": green leads";
    EXPECT_GT(g, b) << leaf_archetype_names[i];
    EXPECT_GT(g, 0.25) << leaf_archetype_names[i] << ": a mid level: the tint sets the albedo";
    EXPECT_LT(g, 0.65) << leaf_archetype_names[i];
    // Per-texel variation (veins, edges, blotches) but not noise that swamps the tint.
    const double sd = std::sqrt(std::max(0.0, sq / count - g * g));
    EXPECT_GT(sd, 0.01) << leaf_archetype_names[i];
    EXPECT_LT(sd, 0.15) << leaf_archetype_names[i];
    // Outside the cut-out the colour stays that of the leaf, so filtering adds no dark fringe.
    EXPECT_GT(outside_min, 0.6 * g) << leaf_archetype_names[i];
  }
}

TEST(ArchetypeTextures, ThicknessIsDarkerOnTheMidribThanOnTheBlade) {
  const leaf_texture_set& s = leaf_archetype_textures(leaf_archetype::ovate, kSize);
  const int y = kSize / 2;
  int midrib = 255;
  for (int x = kSize / 2 - 2; x <= kSize / 2 + 2; ++x) midrib = std::min(midrib, int(s.thickness.pixels[(size_t(y) * kSize + x) * 3]));
  const int blade = s.thickness.pixels[(size_t(y) * kSize + kSize / 2 + kSize / 7) * 3];
  EXPECT_LT(midrib + 60, blade) << "midrib " << midrib << " blade " << blade;
  EXPECT_GT(blade, 180) << "a thin blade lets light through";
}

TEST(ArchetypeTextures, NormalMapsDecodeToUnitVectors) {
  for (int i = 0; i < leaf_archetype_count; ++i)
    expect_unit_normals(leaf_archetype_textures(leaf_archetype(i), kSize).normal, leaf_archetype_names[i]);
  for (int i = 0; i < bark_archetype_count; ++i)
    expect_unit_normals(bark_archetype_textures(bark_archetype(i), kSize).normal, bark_archetype_names[i]);
}

TEST(ArchetypeTextures, LeafNormalMapHasTheMidribAsARidge) {
  // +X right, +Y up the image: left of a ridge the normal leans left (x < 0), right of it right.
  const image& nm = leaf_archetype_textures(leaf_archetype::ovate, kSize).normal;
  const int y = kSize / 2;
  double left = 0, right = 0;
  for (int d = 1; d <= 3; ++d) {
    left += nm.pixels[(size_t(y) * kSize + kSize / 2 - d) * 3] / 127.5 - 1;
    right += nm.pixels[(size_t(y) * kSize + kSize / 2 + d) * 3] / 127.5 - 1;
  }
  EXPECT_LT(left, -0.1);
  EXPECT_GT(right, 0.1);
}

TEST(ArchetypeTextures, BarkTilesSeamlesslyInBothDirections) {
  for (int i = 0; i < bark_archetype_count; ++i) {
    const bark_texture_set& s = bark_archetype_textures(bark_archetype(i), kSize);
    for (const image* img : {&s.color, &s.normal, &s.roughness}) {
      EXPECT_LT(seam_ratio(*img, true), 2.0) << bark_archetype_names[i] << ": seam across the rows";
      EXPECT_LT(seam_ratio(*img, false), 2.0) << bark_archetype_names[i] << ": seam across the columns";
    }
    // The same measure sees the seam of a crop that does not tile.
    const image part = crop(s.color, kSize * 5 / 8, kSize * 5 / 8);
    EXPECT_GT(std::max(seam_ratio(part, true), seam_ratio(part, false)), 2.0) << bark_archetype_names[i];
  }
}

TEST(ArchetypeTextures, BarkColoursHaveTheirSpeciesCharacter) {
  auto mean = [](const image& img) {
    double m[3] = {0, 0, 0};
    for (size_t k = 0; k < size_t(img.width) * img.height; ++k)
      for (int c = 0; c < 3; ++c) m[c] += srgb_to_linear(img.pixels[k * 3 + c]);
    const double n = double(img.width) * img.height;
    return std::array<double, 3>{m[0] / n, m[1] / n, m[2] / n};
  };
  const auto smooth = mean(bark_archetype_textures(bark_archetype::smooth, kSize).color);
  EXPECT_GT(smooth[1], 0.5) << "smooth bark is light: the tint makes it birch white or beech grey";
  EXPECT_LT(smooth[0] - smooth[2], 0.06) << "and neutral";
  const auto plated = mean(bark_archetype_textures(bark_archetype::plated, kSize).color);
  EXPECT_GT(plated[0], plated[2] * 1.6) << "pine plates are reddish";
  for (int i = 0; i < bark_archetype_count; ++i) {
    const auto m = mean(bark_archetype_textures(bark_archetype(i), kSize).color);
    EXPECT_GT(m[1], 0.2) << bark_archetype_names[i] << ": light enough that the tint sets the albedo";
    EXPECT_LT(m[1], 0.9) << bark_archetype_names[i];
  }
}

TEST(TintedTexture, AlbedoIsTintTimesTexelAndBrighterTintsNeverDarken) {
  const image white = tinted_texture(image{1, 1, 3, {255, 255, 255}}, {0.2f, 0.4f, 0.1f});
  EXPECT_NEAR(srgb_to_linear(white.pixels[0]), 0.2, 0.01);   // a white texel shows the tint
  EXPECT_NEAR(srgb_to_linear(white.pixels[1]), 0.4, 0.01);
  EXPECT_NEAR(srgb_to_linear(white.pixels[2]), 0.1, 0.01);
  const image grey = tinted_texture(image{1, 1, 3, {188, 188, 188}}, {0.8f, 0.4f, 1.0f});   // sRGB 188: linear 0.503
  EXPECT_NEAR(srgb_to_linear(grey.pixels[0]), 0.8 * 0.503, 0.01);
  EXPECT_NEAR(srgb_to_linear(grey.pixels[1]), 0.4 * 0.503, 0.01);
  EXPECT_NEAR(srgb_to_linear(grey.pixels[2]), 0.503, 0.01);

  const image& leaf = leaf_archetype_textures(leaf_archetype::ovate, 64).color;
  image previous = tinted_texture(leaf, {0.0f, 0.3f, 0.2f});
  for (int step = 1; step <= 10; ++step) {
    const image next = tinted_texture(leaf, {0.1f * float(step), 0.3f, 0.2f});
    size_t rose = 0;
    for (size_t k = 0; k < size_t(64) * 64; ++k) {
      ASSERT_GE(next.pixels[k * 4], previous.pixels[k * 4]) << "red fell at texel " << k;
      rose += next.pixels[k * 4] > previous.pixels[k * 4];
      ASSERT_EQ(next.pixels[k * 4 + 1], previous.pixels[k * 4 + 1]) << "green moved with the red tint";
      ASSERT_EQ(next.pixels[k * 4 + 3], leaf.pixels[k * 4 + 3]) << "alpha is kept";
    }
    if (step <= 4) {
      EXPECT_GT(rose, size_t(64) * 64 / 2) << "step " << step;
    }
    previous = next;
  }
  // Saturation at 1: a tint over 1 on a light texel stays white, not wrapped around.
  const image over = tinted_texture(image{1, 1, 3, {250, 250, 250}}, {3, 3, 3});
  EXPECT_EQ(over.pixels[0], 255);
}

TEST(UserTextures, BadFilesAreRejectedWithAReasonAndGoodOnesLoad) {
  image out;
  std::string e = load_user_texture(temp_file("missing.png"), out);
  EXPECT_NE(e.find("missing.png"), std::string::npos) << e;

  const std::string corrupt = temp_file("corrupt.png");
  std::ofstream(corrupt, std::ios::binary) << "\x89PNG\r\n\x1a\nthis is not a png";
  e = load_user_texture(corrupt, out);
  EXPECT_NE(e.find("not a readable image"), std::string::npos) << e;

  const std::string wide = temp_file("wide.png");
  ASSERT_EQ(save_png(image{8200, 1, 3, std::vector<uint8_t>(8200 * 3, 90)}, wide), "");
  e = load_user_texture(wide, out);
  EXPECT_NE(e.find("8200x1 pixels, over the limit of 8192"), std::string::npos) << e;

  const std::string huge = temp_file("huge.png");
  ASSERT_EQ(save_png(image{4, 4, 3, std::vector<uint8_t>(48, 90)}, huge), "");
  std::filesystem::resize_file(huge, (size_t(64) << 20) + 1);   // sparse: quick to make
  e = load_user_texture(huge, out);
  EXPECT_NE(e.find("64 MB"), std::string::npos) << e;

  const std::string npot = temp_file("npot.png");   // non-power-of-two sizes are fine
  ASSERT_EQ(save_png(image{3, 5, 3, std::vector<uint8_t>(45, 90)}, npot), "");
  EXPECT_EQ(load_user_texture(npot, out), "");
  EXPECT_EQ(out.width, 3);
  EXPECT_EQ(out.height, 5);
  EXPECT_EQ(out.channels, 4);
  for (const std::string& f : {corrupt, wide, huge, npot}) std::filesystem::remove(f);
}

TEST(TexturesCli, SheetDirAndBenchWriteWhatTheySay) {
  const std::string dir = temp_file("cli_dir"), sheet = temp_file("sheet.png");
  std::filesystem::remove_all(dir);
  sylva_run r = run_sylva("env", "textures --size 64 --sheet '" + sheet + "' --dir '" + dir + "' --bench --repeat 1");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("all 9 leaf + 5 bark sets at 64 px"), std::string::npos) << r.out;
  image img;
  ASSERT_EQ(load_png(sheet, img), "");
  EXPECT_GT(img.width, 5 * 256);
  EXPECT_GT(img.height, 3 * 256);
  size_t files = 0;
  for (const auto& e : std::filesystem::directory_iterator(dir)) files += e.path().extension() == ".png";
  EXPECT_EQ(files, size_t(3 * (leaf_archetype_count + bark_archetype_count)));
  ASSERT_EQ(load_png(dir + "/leaf_needles_color.png", img), "");
  EXPECT_EQ(img.width, 64);
  std::filesystem::remove_all(dir);
  std::filesystem::remove(sheet);

  r = run_sylva("env", "textures");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--sheet"), std::string::npos) << r.err;
  r = run_sylva("env", "textures --size 3 --bench");
  EXPECT_EQ(r.code, 2) << r.err;
}

// Cones and fruit are drawn in their own colours (no tint follows): brown cones, a pale nut or
// wing beside a green husk, and they stand in the card's middle with sky around them.
TEST(ArchetypeTextures, FruitCardsAreInTheirOwnColours) {
  int fruits = 0;
  for (int i = 0; i < leaf_archetype_count; ++i) {
    if (!archetype_is_fruit(leaf_archetype(i))) continue;
    ++fruits;
    const image& c = leaf_archetype_textures(leaf_archetype(i), kSize).color;
    double sum[3] = {0, 0, 0}, count = 0;
    for (size_t k = 0; k < size_t(kSize) * kSize; ++k) {
      const uint8_t* p = &c.pixels[k * 4];
      if (p[3] < 255) continue;
      for (int ch = 0; ch < 3; ++ch) sum[ch] += srgb_to_linear(p[ch]);
      ++count;
    }
    ASSERT_GT(count, 0) << leaf_archetype_names[i];
    const double r = sum[0] / count, g = sum[1] / count, b = sum[2] / count;
    EXPECT_GT(r, b) << leaf_archetype_names[i] << ": warm, woody or ripening colours";
    EXPECT_GT(r, 0.6 * g) << leaf_archetype_names[i] << ": not a leaf's green";
    EXPECT_GT(g, 0.04) << leaf_archetype_names[i] << ": not black";
  }
  EXPECT_EQ(fruits, 11);   // the X-macro's fruit entries: cones, samaras, nuts, keys, coconuts, cypress cones
  // The two cones differ in colour (a ripe spruce cone is brown, a fir or cedar cone grey-green).
  auto mean_rg = [](leaf_archetype a) {
    const image& c = leaf_archetype_textures(a, kSize).color;
    double r = 0, g = 0;
    for (size_t k = 0; k < size_t(kSize) * kSize; ++k)
      if (c.pixels[k * 4 + 3] == 255) r += c.pixels[k * 4], g += c.pixels[k * 4 + 1];
    return r / g;
  };
  EXPECT_GT(mean_rg(leaf_archetype::cone_hanging), mean_rg(leaf_archetype::cone_upright) + 0.1);
}
