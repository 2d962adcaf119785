// `sylva textures`: writes the archetype texture sets (render/assets/textures.h) for people to look at,
// composes the contact sheet docs/archetypes.png, and times their generation.
#include "app/cli/cli_textures.h"

#include <algorithm>
#include <iterator>
#include <chrono>
#include <cstdlib>
#include <ctime>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "generators/timing.h"
#include "render/assets/textures.h"

namespace sylva {
namespace {

// Box-filtered copy of `src` scaled down by an integer factor (sRGB bytes averaged: a preview).
image shrink(const image& src, int factor) {
  factor = std::max(factor, 1);
  image out{src.width / factor, src.height / factor, src.channels, {}};
  out.pixels.assign(size_t(out.width) * out.height * out.channels, 0);
  for (int y = 0; y < out.height; ++y)
    for (int x = 0; x < out.width; ++x)
      for (int c = 0; c < src.channels; ++c) {
        int sum = 0;
        for (int j = 0; j < factor; ++j)
          for (int i = 0; i < factor; ++i)
            sum += src.pixels[(size_t(y * factor + j) * src.width + size_t(x * factor + i)) * src.channels + c];
        out.pixels[(size_t(y) * out.width + x) * out.channels + c] = uint8_t(sum / (factor * factor));
      }
  return out;
}

// Draws `tile` (RGB or RGBA, composited over what is there) into `sheet` (RGB) at (ox, oy).
void paste(image& sheet, const image& tile, int ox, int oy) {
  for (int y = 0; y < tile.height; ++y)
    for (int x = 0; x < tile.width; ++x) {
      const uint8_t* s = &tile.pixels[(size_t(y) * tile.width + x) * tile.channels];
      uint8_t* d = &sheet.pixels[(size_t(oy + y) * sheet.width + size_t(ox + x)) * 3];
      const int a = tile.channels == 4 ? s[3] : 255;
      for (int c = 0; c < 3; ++c) d[c] = uint8_t((s[c] * a + d[c] * (255 - a) + 127) / 255);
    }
}

// Species tints (linear RGB) used on the sheet, one per archetype in the order of
// generators/archetypes.h: the species presets' colours. Unsized, with a static_assert, so a new
// archetype without its row fails to compile.
const glm::vec3 leaf_tints[] = {
    {0.32f, 0.55f, 0.16f},  // ovate: birch
    {0.22f, 0.42f, 0.12f},  // lobed: oak
    {0.26f, 0.50f, 0.12f},  // palmate: maple
    {0.24f, 0.46f, 0.12f},  // pinnate: ash
    {0.10f, 0.26f, 0.12f},  // needles: Scots pine
    {0.08f, 0.22f, 0.12f},  // flat spray: spruce
    {0.07f, 0.20f, 0.09f},  // scale spray: cypress
    {0.26f, 0.45f, 0.14f},  // palm frond
    {0.26f, 0.50f, 0.12f},  // twig cluster: maple cluster cards
    {0.09f, 0.22f, 0.16f},  // needle tufts: cedar of Lebanon
    {0.30f, 0.50f, 0.18f},  // lanceolate: weeping willow
    {0.22f, 0.44f, 0.12f},  // beech spray
    {0.26f, 0.46f, 0.14f},  // hazel spray
    {0.20f, 0.42f, 0.12f},  // poplar spray
    {1, 1, 1},              // cone_hanging: fruit cards keep their own colours
    {1, 1, 1},              // cone_upright
    {1, 1, 1},              // samaras
    {1, 1, 1},              // hazelnuts
    {1, 1, 1},              // cone_ovoid
    {1, 1, 1},              // beechnuts
    {1, 1, 1},              // coconuts
    {0.26f, 0.50f, 0.12f},  // maple spray: maple cluster cards
    {1, 1, 1},              // ash_keys
    {1, 1, 1},              // cone_barrel
    {1, 1, 1},              // acorns
    {0.24f, 0.46f, 0.12f},  // horse chestnut: the sapling
    {1, 1, 1},              // cypress_cones
    {0.30f, 0.54f, 0.15f},  // birch: silver birch
};
static_assert(std::size(leaf_tints) == size_t(leaf_archetype_count));
const glm::vec3 bark_tints[] = {
    {0.36f, 0.31f, 0.26f},  // furrowed: oak
    {0.40f, 0.28f, 0.20f},  // plated: Scots pine
    {0.82f, 0.80f, 0.76f},  // smooth: birch (white)
    {0.50f, 0.32f, 0.24f},  // peeling
    {0.50f, 0.44f, 0.36f},  // ringed: palm
    {0.46f, 0.46f, 0.44f},  // mottled: beech
    {0.40f, 0.40f, 0.38f},  // fissured: ash
    {0.42f, 0.32f, 0.26f},  // fibrous: cypress
    {0.46f, 0.46f, 0.44f},  // silver: beech
};
static_assert(std::size(bark_tints) == size_t(bark_archetype_count));

// A 5x7 pixel font for the sheet's labels: each glyph is 7 rows of 5 bits, most significant left.
struct glyph { char c; uint8_t rows[7]; };
const glyph font[] = {
    {'a', {0x00, 0x00, 0x0E, 0x01, 0x0F, 0x11, 0x0F}}, {'b', {0x10, 0x10, 0x16, 0x19, 0x11, 0x11, 0x1E}},
    {'c', {0x00, 0x00, 0x0E, 0x10, 0x10, 0x11, 0x0E}}, {'d', {0x01, 0x01, 0x0D, 0x13, 0x11, 0x11, 0x0F}},
    {'e', {0x00, 0x00, 0x0E, 0x11, 0x1F, 0x10, 0x0E}}, {'f', {0x06, 0x09, 0x08, 0x1C, 0x08, 0x08, 0x08}},
    {'g', {0x00, 0x0F, 0x11, 0x11, 0x0F, 0x01, 0x0E}}, {'h', {0x10, 0x10, 0x16, 0x19, 0x11, 0x11, 0x11}},
    {'i', {0x04, 0x00, 0x0C, 0x04, 0x04, 0x04, 0x0E}}, {'k', {0x10, 0x10, 0x12, 0x14, 0x18, 0x14, 0x12}},
    {'l', {0x0C, 0x04, 0x04, 0x04, 0x04, 0x04, 0x0E}}, {'m', {0x00, 0x00, 0x1A, 0x15, 0x15, 0x11, 0x11}},
    {'n', {0x00, 0x00, 0x16, 0x19, 0x11, 0x11, 0x11}}, {'o', {0x00, 0x00, 0x0E, 0x11, 0x11, 0x11, 0x0E}},
    {'p', {0x00, 0x1E, 0x11, 0x11, 0x1E, 0x10, 0x10}}, {'r', {0x00, 0x00, 0x16, 0x19, 0x10, 0x10, 0x10}},
    {'s', {0x00, 0x00, 0x0E, 0x10, 0x0E, 0x01, 0x1E}}, {'t', {0x08, 0x08, 0x1C, 0x08, 0x08, 0x09, 0x06}},
    {'u', {0x00, 0x00, 0x11, 0x11, 0x11, 0x13, 0x0D}}, {'v', {0x00, 0x00, 0x11, 0x11, 0x11, 0x0A, 0x04}},
    {'w', {0x00, 0x00, 0x11, 0x11, 0x15, 0x15, 0x0A}}, {'y', {0x00, 0x11, 0x11, 0x11, 0x0F, 0x01, 0x0E}},
    {'z', {0x00, 0x00, 0x1F, 0x02, 0x04, 0x08, 0x1F}}, {'_', {0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x1F}},
    {'(', {0x02, 0x04, 0x08, 0x08, 0x08, 0x04, 0x02}}, {')', {0x08, 0x04, 0x02, 0x02, 0x02, 0x04, 0x08}},
};

// Writes `text` at (x, y) in `sheet` (RGB), each font pixel a scale x scale block, in grey `shade`.
void label(image& sheet, const std::string& text, int x, int y, int scale, uint8_t shade) {
  for (char ch : text) {
    for (const glyph& g : font) {
      if (g.c != ch) continue;
      for (int row = 0; row < 7; ++row)
        for (int col = 0; col < 5; ++col) {
          if (!(g.rows[row] & (0x10 >> col))) continue;
          for (int j = 0; j < scale; ++j)
            for (int i = 0; i < scale; ++i) {
              const int px = x + col * scale + i, py = y + row * scale + j;
              if (px < 0 || py < 0 || px >= sheet.width || py >= sheet.height) continue;
              std::fill_n(&sheet.pixels[(size_t(py) * sheet.width + px) * 3], 3, shade);
            }
        }
    }
    x += 6 * scale;  // unknown characters leave a space
  }
}

const char* const leaf_labels[] = {"ovate (birch)",       "lobed (oak)",        "palmate (maple)",
                                   "pinnate (ash)",       "needles (pine)",     "flat_spray (spruce)",
                                   "scale_spray (cypress)", "palm_frond (palm)", "twig_cluster (maple)",
                                   "needle_tufts (cedar)", "lanceolate (willow)", "beech_spray (beech)",
                                   "hazel_spray (hazel)", "poplar_spray (poplar)", "cone_hanging (spruce)",
                                   "cone_upright (fir)",  "samaras (maple)",    "hazelnuts (hazel)",
                                   "cone_ovoid (pine)",   "beechnuts (beech)",  "coconuts (palm)",
                                   "maple_spray (maple)", "ash_keys (ash)", "cone_barrel (cedar)",
                                   "acorns (oak)", "horse_chestnut (sapling)",
                                   "cypress_cones (cypress)", "birch (birch)"};
static_assert(std::size(leaf_labels) == size_t(leaf_archetype_count));
const char* const bark_labels[] = {"furrowed (oak)", "plated (pine)",  "smooth (birch)",  "peeling",
                                   "ringed (palm)",  "mottled (fir)", "fissured (ash)", "fibrous (cypress)",
                                   "silver (beech)"};
static_assert(std::size(bark_labels) == size_t(bark_archetype_count));

image contact_sheet(int size) {
  const int cell = 256, pad = 12, text = 26, cols = 5;
  const int factor = std::max(size / cell, 1);
  const int leaf_rows = (leaf_archetype_count + cols - 1) / cols;
  const int rows = leaf_rows + (bark_archetype_count + cols - 1) / cols;
  const int w = cols * cell + (cols + 1) * pad, h = rows * (cell + text) + (rows + 1) * pad;
  image sheet{w, h, 3, std::vector<uint8_t>(size_t(w) * h * 3, 118)};  // neutral grey
  auto place = [&](const image& tile, const std::string& name, int col, int row) {
    const int x = pad + col * (cell + pad), y = pad + row * (cell + text + pad);
    paste(sheet, shrink(tile, factor), x, y);
    label(sheet, name, x + 2, y + cell + 6, 2, 240);
  };
  // The leaves, then the barks from a fresh row.
  for (int i = 0; i < leaf_archetype_count; ++i)
    place(tinted_texture(leaf_archetype_textures(leaf_archetype(i), size).color, leaf_tints[i]), leaf_labels[i], i % cols, i / cols);
  for (int i = 0; i < bark_archetype_count; ++i)
    place(tinted_texture(bark_archetype_textures(bark_archetype(i), size).color, bark_tints[i]), bark_labels[i], i % cols,
          leaf_rows + i / cols);
  return sheet;
}

std::string write_sets(const std::string& dir, int size) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) return dir + ": " + ec.message();
  for (int i = 0; i < leaf_archetype_count; ++i) {
    const leaf_texture_set& t = leaf_archetype_textures(leaf_archetype(i), size);
    const std::string base = dir + "/leaf_" + leaf_archetype_names[i];
    for (auto [img, suffix] : {std::pair{&t.color, "_color.png"}, {&t.normal, "_normal.png"}, {&t.thickness, "_thickness.png"}})
      if (std::string e = save_png(*img, base + suffix); !e.empty()) return e;
  }
  for (int i = 0; i < bark_archetype_count; ++i) {
    const bark_texture_set& t = bark_archetype_textures(bark_archetype(i), size);
    const std::string base = dir + "/bark_" + bark_archetype_names[i];
    for (auto [img, suffix] : {std::pair{&t.color, "_color.png"}, {&t.normal, "_normal.png"}, {&t.roughness, "_roughness.png"}})
      if (std::string e = save_png(*img, base + suffix); !e.empty()) return e;
  }
  return "";
}

}  // namespace

int run_textures_cli(int argc, char** argv) {
  const std::string about = "Archetype textures: the " + std::to_string(leaf_archetype_count) + " leaf cards and " +
                            std::to_string(bark_archetype_count) + " barks species choose from";
  CLI::App app{about, "sylva textures"};
  std::string sheet, dir;
  int size = 512, repeat = 9, threads = 2;
  bool bench = false;
  app.add_option("--sheet", sheet, "Write a contact sheet PNG: leaf cards (species tints) and barks");
  app.add_option("--dir", dir, "Write every map of every set as PNGs into this folder");
  app.add_option("--size", size, "Texture size in pixels")->check(CLI::Range(8, 4096));
  app.add_flag("--bench", bench, "Time making every leaf and bark set afresh; prints the median");
  app.add_option("--repeat", repeat, "--bench: runs")->check(CLI::Range(1, 1000));
  app.add_option("--threads", threads, "--bench: threads")->check(CLI::Range(1, 64));
  try {
    app.parse(argc - 1, argv + 1);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);
    std::fprintf(stderr, "sylva textures: %s (see sylva textures --help)\n", e.what());
    return 2;
  }
  if (sheet.empty() && dir.empty() && !bench) {
    std::fprintf(stderr, "sylva textures: give --sheet, --dir or --bench (see sylva textures --help)\n");
    return 2;
  }
  if (bench) {
    // Wall time, and the process's CPU time (all threads) which a machine shared with other
    // work inflates less.
    std::vector<double> wall, cpu;
    size_t bytes = 0;
    for (int i = 0; i < repeat; ++i) {
      const auto t0 = clock_type::now();
      const std::clock_t c0 = std::clock();
      bytes = make_all_archetype_textures(size, 1, threads);
      cpu.push_back(1000.0 * double(std::clock() - c0) / CLOCKS_PER_SEC);
      wall.push_back(ms_since(t0));
    }
    double load[3] = {0, 0, 0};
    if (getloadavg(load, 3) != 3) load[0] = load[1] = load[2] = -1;
    std::printf("all 9 leaf + 5 bark sets at %d px on %d threads, %d runs: median %.1f ms wall (min %.1f, max %.1f), "
                "median %.1f ms CPU; %.1f MB; load average %.2f %.2f %.2f\n",
                size, threads, repeat, median(wall), *std::min_element(wall.begin(), wall.end()),
                *std::max_element(wall.begin(), wall.end()), median(cpu), double(bytes) / 1048576.0, load[0], load[1], load[2]);
  }
  if (!dir.empty() || !sheet.empty()) prepare_archetype_textures(size, 1, threads);
  if (!dir.empty())
    if (std::string e = write_sets(dir, size); !e.empty()) {
      std::fprintf(stderr, "sylva textures: %s\n", e.c_str());
      return 1;
    }
  if (!sheet.empty())
    if (std::string e = save_png(contact_sheet(size), sheet); !e.empty()) {
      std::fprintf(stderr, "sylva textures: %s\n", e.c_str());
      return 1;
    }
  return 0;
}

}  // namespace sylva
