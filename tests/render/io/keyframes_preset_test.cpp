// Growth phases in presets and on the CLI: round trips, older presets, `--set key@k=value`, bad input.
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "tests/run_sylva.h"

#include "render/io/preset.h"
#include "tests/scratch_dir.h"

using namespace sylva;
using nlohmann::json;

namespace {

preset so_preset() {
  preset p;
  self_organizing_params so;
  so.steps = 12;
  p.spec.params = so;
  return p;
}

}  // namespace

TEST(KeyframePresets, SaveAndLoadGiveAnEqualSpecWithTypedValues) {
  preset p = so_preset();
  ASSERT_EQ(set_preset_param(p, "lambda@5=0.7"), "");
  ASSERT_EQ(set_preset_param(p, "params.allocation@3=priority"), "");
  ASSERT_EQ(set_preset_param(p, "tropism@8=0,-1,0"), "");
  ASSERT_EQ(set_preset_param(p, "shed_min_buds@8=5"), "");
  ASSERT_EQ(p.spec.keyframes.size(), 4u);
  const std::string text = save_preset_json(p);
  const json doc = json::parse(text);
  ASSERT_TRUE(doc.contains("keyframes"));
  // Typed as their parameters: an enum by name, a vec3 as an array, an int as an integer.
  EXPECT_EQ(doc["keyframes"][0]["key"], "allocation");
  EXPECT_EQ(doc["keyframes"][0]["value"], "priority");
  EXPECT_TRUE(doc["keyframes"][3]["value"].is_array());
  EXPECT_TRUE(doc["keyframes"][2]["value"].is_number_integer());
  preset back;
  const load_result r = load_preset_json(text, back);
  ASSERT_TRUE(r.ok) << r.error;
  EXPECT_TRUE(r.warnings.empty()) << r.warnings.front();
  EXPECT_EQ(back, p);
}

TEST(KeyframePresets, OlderPresetsWithoutKeyframesLoadWithNone) {
  preset p;
  const load_result r =
      load_preset_json(R"({"sylva_preset":1,"generator":"self_organizing","params":{"steps":9}})", p);
  ASSERT_TRUE(r.ok) << r.error;
  EXPECT_TRUE(r.warnings.empty());
  EXPECT_TRUE(p.spec.keyframes.empty());
  // And a preset without keyframes is saved without the key, as before.
  EXPECT_FALSE(json::parse(save_preset_json(p)).contains("keyframes"));
}

TEST(KeyframePresets, BadKeyframesFailTheLoadWithAMessage) {
  const char* head = R"({"sylva_preset":1,"generator":"self_organizing","params":{"steps":9},"keyframes":)";
  const struct { const char* list; const char* words; } bad[] = {
      {R"([{"step":201,"key":"lambda","value":0.7}])", "beyond the most steps a growth can have (200)"},
      {R"([{"step":3,"key":"lambda","value":0.7},{"step":3,"key":"lambda","value":0.8}])", "already keyed"},
      {R"([{"step":3,"key":"lambdaa","value":0.7}])", "not a parameter"},
      {R"([{"step":3,"key":"lambda","value":"x"}])", "expected a number"},
      {R"([{"step":3,"key":"lambda"}])", "\"value\" is missing"},
      {R"({"step":3})", "expected an array"},
      {R"([{"step":3,"key":"voxel_size","value":2}])", "cannot change from a step on"},
  };
  for (const auto& b : bad) {
    preset p = so_preset();
    const preset before = p;
    const load_result r = load_preset_json(std::string(head) + b.list + "}", p);
    EXPECT_FALSE(r.ok) << b.list;
    EXPECT_NE(r.error.find(b.words), std::string::npos) << r.error;
    EXPECT_EQ(p, before);
  }
}

TEST(KeyframePresets, SetWithAStepRefusesBadInputAndLeavesThePresetAsItWas) {
  preset p = so_preset();
  ASSERT_EQ(set_preset_param(p, "lambda@5=0.7"), "");
  const preset before = p;
  EXPECT_NE(set_preset_param(p, "lambda@201=0.7").find("beyond the most steps a growth can have (200)"), std::string::npos);
  EXPECT_NE(set_preset_param(p, "lambda@x=0.7").find("whole number"), std::string::npos);
  EXPECT_NE(set_preset_param(p, "lambda@5=abc").find("not a finite number"), std::string::npos);
  EXPECT_NE(set_preset_param(p, "lambda@5=3").find("outside"), std::string::npos);
  EXPECT_NE(set_preset_param(p, "steps@5=3").find("cannot change"), std::string::npos);
  EXPECT_NE(set_preset_param(p, "leaf_size@5=3").find("not a parameter of self_organizing"), std::string::npos);
  EXPECT_EQ(p, before);
  // On a preset that already keys it, the new value replaces the old, as key=value does (the CLI
  // refuses the same key@step twice on one command line).
  ASSERT_EQ(set_preset_param(p, "lambda@5=0.6"), "");
  ASSERT_EQ(p.spec.keyframes.size(), 1u);
  EXPECT_EQ(p.spec.keyframes[0].value.x, 0.6f);
  std::vector<std::string> out;
  EXPECT_EQ(expand_param_sweep(p, "lambda@6=0.5", out), "");
  EXPECT_EQ(out, std::vector<std::string>{"lambda@6=0.5"});
}

// The CLI: `--set key@k=value` grows the keyed tree; the same key@step twice, or a step beyond the
// last, is a usage error that writes nothing.
TEST(KeyframePresets, CliSetsKeyframesAndRefusesContradictions) {
  namespace fs = std::filesystem;
  const sylva_test::scratch_dir scratch("sylva_keyframes");
  const fs::path& dir = scratch.dir;
  const std::string preset = std::string(SYLVA_SOURCE_DIR) + "/presets/lsystem_honda_a.json";
  const std::string plain = (dir / "plain.json").string(), keyed = (dir / "keyed.json").string();
  ASSERT_EQ(run_sylva("", "export '" + preset + "' -o '" + plain + "'").code, 0);
  const sylva_run ok = run_sylva("", "export '" + preset + "' -o '" + keyed + "' --set alpha1@3=60");
  ASSERT_EQ(ok.code, 0) << ok.err;
  const json a = json::parse(std::ifstream(plain)), b = json::parse(std::ifstream(keyed));
  EXPECT_EQ(a["nodes"]["position"].size(), b["nodes"]["position"].size());  // Honda: same count, other angles
  EXPECT_NE(a["nodes"]["position"], b["nodes"]["position"]);
  const std::string twice = (dir / "twice.json").string();
  const sylva_run r = run_sylva("", "export '" + preset + "' -o '" + twice + "' --set alpha1@3=60 --set alpha1@3=50");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("given twice"), std::string::npos) << r.err;
  const sylva_run beyond = run_sylva("", "export '" + preset + "' -o '" + twice + "' --set alpha1@99=60");
  EXPECT_EQ(beyond.code, 2);
  EXPECT_NE(beyond.err.find("beyond the most steps a growth can have (24)"), std::string::npos) << beyond.err;
  EXPECT_FALSE(fs::exists(twice));
}

TEST(KeyframePresets, CutsSaveLoadAndRefuseBadInput) {
  preset p = so_preset();
  ASSERT_EQ(add_cut(p.spec, {4, prune_shape::branch, glm::vec3(0.1f, 1.2f, -0.3f), glm::vec3(1), 0.2f}), "");
  ASSERT_EQ(add_cut(p.spec, {6, prune_shape::outside_ellipsoid, glm::vec3(0, 2, 0), glm::vec3(1, 1.5f, 1), 0.25f}), "");
  const std::string text = save_preset_json(p);
  preset back;
  const load_result r = load_preset_json(text, back);
  ASSERT_TRUE(r.ok) << r.error;
  EXPECT_TRUE(r.warnings.empty());
  EXPECT_EQ(back, p);
  const char* head = R"({"sylva_preset":1,"generator":"self_organizing","params":{"steps":9},"cuts":)";
  const struct { const char* list; const char* words; } bad[] = {
      {R"([{"step":201,"point":[0,1,0]}])", "beyond the most steps a growth can have (200)"},
      {R"([{"step":3,"point":[0,1]}])", "\"point\" must be [x, y, z]"},
      {R"([{"step":3,"point":[0,1,0],"shape":"hedge"}])", "\"shape\" must be one of"},
      {R"([{"step":3,"point":[0,1,0],"reach":-1}])", "reach"},
  };
  for (const auto& b : bad) {
    preset q = so_preset();
    const preset before = q;
    const load_result e = load_preset_json(std::string(head) + b.list + "}", q);
    EXPECT_FALSE(e.ok) << b.list;
    EXPECT_NE(e.error.find(b.words), std::string::npos) << e.error;
    EXPECT_EQ(q, before);
  }
}

// The history presets (presets/history_*.json) are made with the timeline's own cuts: each cut
// takes wood at its step, and the tree regrows after it, so the final tree is mostly new wood.
TEST(KeyframePresets, HistoryPresetsRegrowAfterTheirCuts) {
  int presets = 0;
  for (const auto& entry : std::filesystem::directory_iterator(std::filesystem::path(SYLVA_SOURCE_DIR) / "presets")) {
    const std::string name = entry.path().filename().string();
    if (name.rfind("history_", 0) != 0) continue;
    SCOPED_TRACE(name);
    ++presets;
    preset p;
    const load_result r = load_preset_file(entry.path().string(), p);
    ASSERT_TRUE(r.ok) << r.error;
    ASSERT_FALSE(p.spec.cuts.empty());
    grow_report rep;
    const tree_skeleton t = grow(p.spec, grow_options{}, &rep);
    EXPECT_TRUE(rep.missed_cuts.empty()) << rep.message;
    int first_cut = 1 << 30;
    for (const prune_cut& c : p.spec.cuts) {
      first_cut = std::min(first_cut, c.step);
      size_t taken = 0;
      for (size_t i = 0; i < t.size(); ++i) taken += t.died[i] == c.step;
      EXPECT_GT(taken, 50u) << "cut at step " << c.step;
    }
    size_t alive = 0, regrown = 0;
    for (size_t i = 0; i < t.size(); ++i)
      if (t.alive(i, t.steps)) ++alive, regrown += t.born[i] >= first_cut;
    EXPECT_GT(regrown, alive / 2) << regrown << " of " << alive << " nodes grew after the first cut";
  }
  EXPECT_GE(presets, 2);
}
