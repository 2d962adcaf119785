// The season control: looks per season, fallen leaves with scrubbing intact, no regrow,
// out-of-range values clamped, exports without winter's leaves, and the viewport's pixels.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <sys/wait.h>
#include <unistd.h>

#include <epoxy/gl.h>

#include "render/io/export.h"
#include "render/io/preset.h"
#include "render/gl/renderer.h"
#include "render/mesh/season.h"
#include "render/mesh/lod_cards.h"
#include "tests/gl/gl_test_context.h"

using namespace sylva;
using RenderSeason = sylva_test::renderer_test;

namespace {

// A grid of n x n leaf cards of one archetype facing +Z, spread over [-1, 1] x [0, 2]; leaves are
// born at step i % 3 so that the mesh has a scrub table.
tree_mesh card_grid(uint8_t archetype, int n = 6) {
  tree_mesh m;
  for (int born = 0; born < 3; ++born)
    for (int k = 0; k < n * n; ++k) {
      if (k % 3 != born) continue;
      leaf_instance l{};
      l.position = glm::vec3(-1 + (k % n + 0.5f) * 2.0f / n, (k / n) * 2.0f / n, 0);
      l.orientation = glm::vec4(0, 0, 0, 1);
      l.size = 1.8f / n;
      l.born = uint16_t(born);
      l.died = 0xffff;
      l.texture = archetype;
      m.leaves.push_back(l);
    }
  for (int s = 0; s < 3; ++s)
    m.leaf_end.push_back(uint32_t(std::count_if(m.leaves.begin(), m.leaves.end(), [&](const leaf_instance& l) { return l.born <= s; })));
  m.index_end = {0, 0, 0};
  m.steps = 2;
  m.bounds_min = glm::vec3(-1, 0, -0.1f);
  m.bounds_max = glm::vec3(1, 2, 0.1f);
  return m;
}

render_params with_season(leaf_season s) {
  render_params rp;
  rp.season = s;
  return rp;
}

}  // namespace

TEST(Season, SummerIsTheLeafColourAndChangesNothing) {
  render_params rp;
  rp.leaf_color = glm::vec3(0.2f, 0.5f, 0.1f);
  const season_look s = season_leaf_look(rp);
  EXPECT_EQ(s.evergreen_color, rp.leaf_color);
  EXPECT_EQ(s.deciduous_color_a, rp.leaf_color);
  EXPECT_EQ(s.deciduous_color_b, rp.leaf_color);
  EXPECT_FALSE(season_changes_leaves(s));
  const tree_mesh m = card_grid(uint8_t(leaf_archetype::lobed));
  EXPECT_EQ(apply_season(m, s).leaves.size(), m.leaves.size());
}

TEST(Season, HabitFollowsTheArchetypeUnlessThePresetSaysOtherwise) {
  render_params rp;
  const season_look by_archetype = season_leaf_look(rp);
  for (int k = 0; k < leaf_archetype_count; ++k)
    EXPECT_EQ(bool((by_archetype.deciduous_mask >> k) & 1u),
              !archetype_is_evergreen(leaf_archetype(k)) && !archetype_is_fruit(leaf_archetype(k))) << k;
  EXPECT_FALSE((by_archetype.deciduous_mask >> int(leaf_archetype::needles)) & 1u);
  EXPECT_TRUE((by_archetype.deciduous_mask >> int(leaf_archetype::lobed)) & 1u);
  rp.habit = leaf_habit::evergreen;
  EXPECT_EQ(season_leaf_look(rp).deciduous_mask, 0u);
  rp.habit = leaf_habit::deciduous;
  // Every archetype but the cones' and fruit's (generators/fruits.h), which keep their colours.
  uint64_t leaves = 0;
  for (int k = 0; k < leaf_archetype_count; ++k)
    if (!archetype_is_fruit(leaf_archetype(k))) leaves |= uint64_t(1) << k;
  EXPECT_EQ(season_leaf_look(rp).deciduous_mask, leaves);
}

// Baked LOD cards take texture leaf_archetype_count + k, past bit 31 for the last of them: the
// mask is 64 bits wide, so each still follows the season of the leaves it was baked from.
TEST(Season, EveryBakedCardKeepsItsSeasonBitPastBit31) {
  render_params rp;
  rp.habit = leaf_habit::deciduous;
  const season_look s = season_leaf_look(rp);
  baked_card_textures cards;
  for (int k = 0; k < max_baked_cards; ++k)
    cards.source.push_back(uint8_t(k % 2 ? leaf_archetype::lobed : leaf_archetype::cone_hanging));
  cards.sets.resize(cards.source.size());
  ASSERT_GT(leaf_archetype_count + max_baked_cards, 32);
  const season_look with = with_card_seasons(s, &cards);
  for (int k = 0; k < max_baked_cards; ++k)
    EXPECT_EQ(season_deciduous(with, leaf_archetype_count + k), k % 2 == 1) << "card " << k;
  // apply_season drops the deciduous cards in winter, the ones past bit 31 too.
  tree_mesh m;
  m.steps = 0;
  m.leaf_end = {uint32_t(max_baked_cards)};
  for (int k = 0; k < max_baked_cards; ++k)
    m.leaves.push_back({{0, 1, 0}, {0, 0, 0, 1}, 0.1f, 0, never_died, 0, uint8_t(leaf_archetype_count + k)});
  m.cards = std::make_shared<baked_card_textures>(cards);
  season_look winter = s;
  winter.deciduous_keep = 0;
  EXPECT_EQ(apply_season(m, winter).leaves.size(), size_t(max_baked_cards / 2));
}

TEST(Season, WinterDropsDeciduousLeavesAndKeepsConifersWithScrubbingIntact) {
  const season_look winter = season_leaf_look(with_season(leaf_season::winter));
  const tree_mesh oak = apply_season(card_grid(uint8_t(leaf_archetype::lobed)), winter);
  EXPECT_TRUE(oak.leaves.empty());
  EXPECT_EQ(oak.leaf_end, (std::vector<uint32_t>{0, 0, 0}));
  const tree_mesh pine = apply_season(card_grid(uint8_t(leaf_archetype::needles)), winter);
  EXPECT_EQ(pine.leaves.size(), 36u);

  // Autumn: about a quarter fall; leaf_end still counts the kept leaves born up to each step.
  const season_look autumn = season_leaf_look(with_season(leaf_season::autumn));
  const tree_mesh full = card_grid(uint8_t(leaf_archetype::palmate), 20);
  const tree_mesh fall = apply_season(full, autumn);
  EXPECT_LT(fall.leaves.size(), full.leaves.size() * 9 / 10);
  EXPECT_GT(fall.leaves.size(), full.leaves.size() / 2);
  EXPECT_EQ(fall.leaf_end.back(), fall.leaves.size());
  for (size_t s = 0; s < fall.leaf_end.size(); ++s)
    for (uint32_t i = 0; i < fall.leaf_end[s]; ++i) EXPECT_LE(int(fall.leaves[i].born), int(s));
  EXPECT_EQ(validate_mesh(fall), "");

  // Spring: smaller leaves.
  const tree_mesh spring = apply_season(full, season_leaf_look(with_season(leaf_season::spring)));
  ASSERT_FALSE(spring.leaves.empty());
  EXPECT_LT(spring.leaves[0].size, full.leaves[0].size);
}

TEST(Season, ChangingTheSeasonLeavesTheGrowthRequestAlone) {
  preset p;
  ASSERT_TRUE(load_preset_file(SYLVA_SOURCE_DIR "/presets/species_oak.json", p).ok);
  for (const char* s : {"season=autumn", "render.season=winter", "season=spring", "leaf_habit=evergreen",
                        "autumn_color=0.9,0.1,0.1"}) {
    preset q = p;
    ASSERT_EQ(set_preset_param(q, s), "") << s;
    EXPECT_EQ(q.spec, p.spec) << s;   // the worker's request is (spec, mesh): unchanged, so no regrow
    EXPECT_EQ(q.mesh, p.mesh) << s;
    EXPECT_NE(q.render, p.render) << s;
  }
  EXPECT_NE(set_preset_param(p, "season=monsoon"), "");
}

TEST(Season, OutOfRangeIsClampedWithAWarningAndRoundTrips) {
  preset p;
  load_result r = load_preset_json(R"({"sylva_preset": 1, "generator": "lsystem", "render": {"season": 7}})", p);
  ASSERT_TRUE(r.ok) << r.error;
  // The loader's rule for every enum (clamp_param): an index outside the options becomes the
  // first option, with the "clamped" warning.
  EXPECT_EQ(p.render.season, leaf_season::spring);
  ASSERT_FALSE(r.warnings.empty());
  EXPECT_NE(r.warnings[0].find("clamped"), std::string::npos) << r.warnings[0];
  r = load_preset_json(R"({"sylva_preset": 1, "generator": "lsystem", "render": {"season": "monsoon"}})", p);
  ASSERT_TRUE(r.ok);
  EXPECT_EQ(p.render.season, leaf_season::summer);
  EXPECT_FALSE(r.warnings.empty());
  // A corrupt in-memory value still gives a valid look.
  render_params rp;
  rp.season = leaf_season(42);
  EXPECT_EQ(season_leaf_look(rp), season_leaf_look(with_season(leaf_season::winter)));
  // Saved by name, loaded back equal.
  p.render.season = leaf_season::autumn;
  preset q;
  ASSERT_TRUE(load_preset_json(save_preset_json(p), q).ok);
  EXPECT_EQ(q.render.season, leaf_season::autumn);
  EXPECT_NE(save_preset_json(p).find("\"autumn\""), std::string::npos);
}

TEST(Season, ObjExportHasNoWinterLeavesAndAnAutumnMaterial) {
  const tree_mesh m = card_grid(uint8_t(leaf_archetype::lobed));
  tree_skeleton t;
  t.position = {glm::vec3(0)};
  t.parent = {-1};
  t.radius = {0.01f};
  t.born = {0};
  t.died = {never_died};
  t.order = {0};
  t.steps = 2;
  auto leaf_faces = [&](leaf_season s, std::string* mtl) {
    export_options o;
    apply_render_params(o, with_season(s));
    const std::string path = (std::filesystem::temp_directory_path() / "sylva_season_test.obj").string();
    const export_result r = export_tree(t, m, export_info{}, path, o);
    EXPECT_EQ(r.error, "");
    std::ifstream in(path);
    std::string line;
    bool leaves = false;
    int faces = 0;
    while (std::getline(in, line)) {
      if (line.rfind("g ", 0) == 0) leaves = line.find("lea") != std::string::npos;
      if (leaves && line.rfind("f ", 0) == 0) ++faces;
    }
    if (mtl) {
      std::ifstream mi(path.substr(0, path.size() - 4) + ".mtl");
      std::stringstream ss;
      ss << mi.rdbuf();
      *mtl = ss.str();
    }
    return faces;
  };
  std::string summer_mtl, autumn_mtl;
  const int summer = leaf_faces(leaf_season::summer, &summer_mtl);
  EXPECT_GE(summer, 36);
  EXPECT_EQ(leaf_faces(leaf_season::winter, nullptr), 0);
  const int autumn = leaf_faces(leaf_season::autumn, &autumn_mtl);
  EXPECT_GT(autumn, 0);
  EXPECT_LT(autumn, summer);
}

// The viewport: autumn turns the lobed cards from green to orange-red, winter removes them, and a
// conifer's needle cards stay in winter.
TEST_F(RenderSeason, AutumnRecoloursAndWinterRemovesDeciduousLeaves) {
  render_params rp;
  rp.msaa = 0;
  rp.shadows = false;
  rp.shafts = light_shafts::off;
  rp.ground = false;
  rp.physical_sky = false;
  rp.sky_zenith = rp.sky_horizon = glm::vec3(0, 0, 0.5f);   // blue: leaf texels have more red or green
  rp.sun_azimuth = 0, rp.sun_elevation = 30;
  orbit_camera cam;
  cam.target = glm::vec3(0, 1, 0);
  cam.yaw = 0, cam.pitch = 0, cam.distance = 2.6f;
  const int w = 96, h = 96;
  GLuint tex = 0, fbo = 0;
  glGenTextures(1, &tex);
  glBindTexture(GL_TEXTURE_2D, tex);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, w, h, 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
  glGenFramebuffers(1, &fbo);
  glBindFramebuffer(GL_FRAMEBUFFER, fbo);
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, tex, 0);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  struct stats { size_t leaf = 0; double red = 0, green = 0; };
  auto render = [&](uint8_t archetype, leaf_season s) {
    upload_tree(r, card_grid(archetype));
    rp.season = s;
    draw_frame(r, rp, cam, w, h, gl_framebuffer{fbo});
    std::vector<uint8_t> px(size_t(w) * h * 4);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, px.data());
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    stats st;
    for (size_t k = 0; k < size_t(w) * h; ++k) {
      const int R = px[k * 4], G = px[k * 4 + 1], B = px[k * 4 + 2];
      if (std::max(R, G) > B + 10) ++st.leaf, st.red += R, st.green += G;
    }
    return st;
  };
  const uint8_t lobed = uint8_t(leaf_archetype::lobed), needles = uint8_t(leaf_archetype::needles);
  const stats summer = render(lobed, leaf_season::summer), autumn = render(lobed, leaf_season::autumn),
              winter = render(lobed, leaf_season::winter);
  ASSERT_GT(summer.leaf, size_t(w * h / 10)) << "the cards hardly show";
  EXPECT_LT(summer.red, summer.green);   // green in summer
  ASSERT_GT(autumn.leaf, 0u);
  EXPECT_GT(autumn.red, autumn.green);   // orange to red in autumn
  EXPECT_LT(autumn.leaf, summer.leaf);   // some have fallen
  EXPECT_EQ(winter.leaf, 0u);            // bare
  const stats pine_summer = render(needles, leaf_season::summer), pine_winter = render(needles, leaf_season::winter);
  ASSERT_GT(pine_summer.leaf, 0u);
  EXPECT_NEAR(double(pine_winter.leaf), double(pine_summer.leaf), 0.02 * double(pine_summer.leaf));
  EXPECT_LT(pine_winter.red, pine_winter.green);
  glDeleteFramebuffers(1, &fbo);
  glDeleteTextures(1, &tex);
  EXPECT_EQ(check_gl("season test"), 0);
}

// The real editor: a season change redraws the same tree (the worker is not asked to regrow).
TEST(EditorSeason, ChangingTheSeasonKeepsTheSameTree) {
  if (!sylva_test::have_display()) GTEST_SKIP() << "no DISPLAY";
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("sylva_editor_season_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir / "home");
  std::ofstream(dir / "script.txt") << "wait_tree\nremember\nset season=winter\nframes 3\nexpect_same_tree\n"
                                       "set season=autumn\nframes 3\nexpect_same_tree\nexpect_modified 1\n";
  const std::string log = (dir / "log.txt").string();
  const std::string cmd = "SYLVA_HOME='" + (dir / "home").string() + "' SYLVA_SCRIPT='" + (dir / "script.txt").string() +
                          "' SYLVA_WINDOW=640x400 '" SYLVA_BINARY "' '" SYLVA_SOURCE_DIR "/presets/species_sapling.json' > '" +
                          log + "' 2>&1";
  const int status = std::system(cmd.c_str());
  std::ifstream in(log);
  std::stringstream ss;
  ss << in.rdbuf();
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << ss.str();
  EXPECT_EQ(ss.str().find("FAIL"), std::string::npos) << ss.str();
  EXPECT_NE(ss.str().find("ok expect_same_tree"), std::string::npos) << ss.str();
  fs::remove_all(dir);
}
