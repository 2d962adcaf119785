// Parameter schema, preset JSON round trips, tolerant loading, --set parsing and atomic writes.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <set>

#include <nlohmann/json.hpp>

#include "render/io/preset.h"
#include "tests/scratch_dir.h"

using namespace sylva;
namespace fs = std::filesystem;

namespace {

// Checks one params struct's schema; `shared` collects keys of structs saved into one JSON object.
template <class P>
void check_schema(const P& defaults, const std::string& where, std::set<std::string>& shared) {
  std::set<std::string> own;
  visit_params(defaults, [&](const auto& value, const param_info& info) {
    const std::string key = info.key ? info.key : "";
    SCOPED_TRACE(where + "." + key);
    ASSERT_FALSE(key.empty());
    // Keys are JSON keys and `--set key=value` names: no separators that --set would split on.
    EXPECT_EQ(key.find_first_of(".=: "), std::string::npos);
    EXPECT_TRUE(own.insert(key).second) << "duplicate key within " << where;
    EXPECT_TRUE(shared.insert(key).second) << "key shared with another struct in the same JSON object";
    ASSERT_NE(info.label, nullptr);
    EXPECT_STRNE(info.label, "");
    ASSERT_NE(info.help, nullptr);
    EXPECT_STRNE(info.help, "");
    EXPECT_NE(info.symbol, nullptr);
    EXPECT_LE(info.min, info.max);
    using T = std::decay_t<decltype(value)>;
    if constexpr (std::is_enum_v<T>) {
      EXPECT_GE(option_count(info), 2);
    }
    auto copy = value;
    EXPECT_TRUE(clamp_param(copy, info)) << "default outside [min, max]";  // min <= default <= max
  });
}

// An in-range value different from typical defaults, with fractions that are not exact in binary.
template <class T>
void perturb(T& v, const param_info& info) {
  auto at = [&](float t) { return info.min + t * (info.max - info.min); };
  if constexpr (std::is_same_v<T, float>) v = at(0.37f);
  else if constexpr (std::is_same_v<T, int>) v = int(info.min) + int((info.max - info.min) / 3);
  else if constexpr (std::is_same_v<T, bool>) v = !v;
  else if constexpr (std::is_enum_v<T>) v = T(option_count(info) - 1);
  else if constexpr (std::is_same_v<T, glm::vec3>) v = glm::vec3(at(0.1f), at(0.23f), at(0.9f));
  else if constexpr (std::is_same_v<T, std::string>) v = "A(1) : * -> F\n\"quoted\" ü";
  else if constexpr (std::is_same_v<T, std::vector<float>>) v = {at(0), at(0.3f), at(1)};
  else if constexpr (std::is_same_v<T, std::vector<glm::vec3>>) v = {glm::vec3(at(0.7f)), glm::vec3(at(0.01f))};
}

template <class P>
void perturb_all(P& p) {
  visit_params(p, [](auto& value, const param_info& info) { perturb(value, info); });
}

preset sentinel() {
  preset p;
  p.name = "sentinel";
  lsystem_params l;
  l.r1 = 0.5f;
  p.spec.params = l;
  p.spec.seed = 77;
  return p;
}

const lsystem_params& honda(const preset& p) { return std::get<lsystem_params>(p.spec.params); }

}  // namespace

TEST(PresetSchema, EveryParamsStruct) {
  for (int g = 0; g < generator_count; ++g) {
    std::set<std::string> params_keys;  // the "params" object holds one generator's keys
    std::visit([&](const auto& p) { check_schema(p, generator_names[g], params_keys); }, default_params(g));
    EXPECT_FALSE(params_keys.empty()) << generator_names[g];
  }
  std::set<std::string> mesh_keys;  // mesh_params and its leaf_params share the "mesh" object
  check_schema(mesh_params{}, "mesh", mesh_keys);
  std::set<std::string> render_keys;
  check_schema(render_params{}, "render", render_keys);
  EXPECT_TRUE(mesh_keys.count("leaf_density"));  // the nested leaf_params are part of it
}

TEST(PresetJson, SaveLoadRoundTripEveryGenerator) {
  for (int g = 0; g < generator_count; ++g) {
    SCOPED_TRACE(generator_names[g]);
    preset p;
    p.name = "Round trip \"ß\"";
    p.description = "line one\nline two";
    p.tags = {"a", "b c"};
    p.spec.params = default_params(g);
    std::visit([](auto& gp) { perturb_all(gp); }, p.spec.params);
    p.spec.seed = (uint64_t(1) << 63) + 5;  // needs the full unsigned range
    perturb_all(p.mesh);
    perturb_all(p.render);
    preset q;
    load_result r = load_preset_json(save_preset_json(p), q);
    ASSERT_TRUE(r.ok) << r.error;
    EXPECT_TRUE(r.warnings.empty()) << r.warnings.front();
    EXPECT_EQ(p, q);
    // Defaults survive too.
    preset d;
    d.spec.params = default_params(g);
    preset e = sentinel();
    ASSERT_TRUE(load_preset_json(save_preset_json(d), e).ok);
    EXPECT_EQ(d, e);
  }
}

TEST(PresetJson, SavedFormat) {
  const std::string text = save_preset_json(default_preset());
  EXPECT_NE(text.find("\"sylva_preset\": 1"), std::string::npos);
  EXPECT_NE(text.find("\"generator\": \"lsystem\""), std::string::npos);
  EXPECT_NE(text.find("\"mode\": \"honda\""), std::string::npos);            // enums by name
  EXPECT_NE(text.find("\"r2\": 0.77"), std::string::npos);                    // shortest float form
  EXPECT_NE(text.find("\"sun_color\": [\n"), std::string::npos);              // vec3 as an array
}

TEST(PresetFiles, LibraryAndBenchLoadCleanly) {
  int count = 0;
  for (const char* folder : {"presets", "bench"}) {
    const fs::path dir = fs::path(SYLVA_SOURCE_DIR) / folder;
    ASSERT_TRUE(fs::is_directory(dir)) << dir;
    for (const auto& entry : fs::directory_iterator(dir)) {
      if (entry.path().extension() != ".json") continue;
      SCOPED_TRACE(entry.path().string());
      preset p;
      load_result r = load_preset_file(entry.path().string(), p);
      EXPECT_TRUE(r.ok) << r.error;
      EXPECT_TRUE(r.warnings.empty()) << r.warnings.front();
      EXPECT_FALSE(p.name.empty());
      EXPECT_FALSE(p.description.empty());
      EXPECT_FALSE(p.tags.empty());
      ++count;
    }
  }
  EXPECT_GE(count, 9 + 1);  // the nine Honda trees and at least one bench workload
}

TEST(PresetFiles, HondaTreesMatchTheTables) {
  const fs::path dir = fs::path(SYLVA_SOURCE_DIR) / "presets";
  preset a, e, h;
  ASSERT_TRUE(load_preset_file((dir / "lsystem_honda_a.json").string(), a).ok);
  ASSERT_TRUE(load_preset_file((dir / "lsystem_honda_e.json").string(), e).ok);
  ASSERT_TRUE(load_preset_file((dir / "lsystem_honda_h.json").string(), h).ok);
  // Tree a is the built-in default (lsystem_params defaults).
  const preset d = default_preset();
  EXPECT_EQ(a.spec, d.spec);
  EXPECT_EQ(a.mesh, d.mesh);
  EXPECT_EQ(a.render, d.render);
  EXPECT_EQ(a.name, d.name);
  // Row e: min is 1.0 at s0 = 100 (the seed's 0.001 at s0 = 1 is the transcription error).
  EXPECT_EQ(honda(e).min_length, 1.0f);
  EXPECT_EQ(honda(e).alpha2, 15.0f);
  EXPECT_EQ(honda(e).phi2, 180.0f);
  EXPECT_EQ(honda(e).derivations, 11);
  // Row h: w0 40, q .60, e .45, min 25; angles 5, -30, -90, 90; r .95, .75; count 12.
  const lsystem_params& ph = honda(h);
  EXPECT_EQ(ph.w0, 40.0f);
  EXPECT_EQ(ph.q, 0.6f);
  EXPECT_EQ(ph.e, 0.45f);
  EXPECT_EQ(ph.min_length, 25.0f);
  EXPECT_EQ(ph.alpha1, 5.0f);
  EXPECT_EQ(ph.phi1, -90.0f);
  EXPECT_EQ(ph.phi2, 90.0f);
  EXPECT_EQ(ph.r1, 0.95f);
  EXPECT_EQ(ph.derivations, 12);
  EXPECT_TRUE(h.mesh.leaves_enabled);
}

TEST(PresetLoad, MalformedJsonNamesLineAndColumnAndKeepsOutput) {
  preset out = sentinel();
  load_result r = load_preset_json("{\n  \"name\": \"x\",\n  \"seed\": ,\n}", out);
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.error.find("line 3, column 11"), std::string::npos) << r.error;
  EXPECT_EQ(out, sentinel());

  r = load_preset_json("{\"sylva_preset\": 1, \"name\": \"trunc", out);
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.error.find("line 1"), std::string::npos) << r.error;
  EXPECT_NE(r.error.find("ends too early"), std::string::npos) << r.error;
  EXPECT_EQ(out, sentinel());

  for (const char* bad : {"", "[1, 2]", "42", "{\"params\": {\"r1\": 0.5}"}) {
    SCOPED_TRACE(bad);
    r = load_preset_json(bad, out);
    EXPECT_FALSE(r.ok);
    EXPECT_FALSE(r.error.empty());
    EXPECT_EQ(out, sentinel());
  }
}

TEST(PresetLoad, WrongTypesAreErrorsNamingTheKey) {
  struct bad_case { const char* json; const char* key; };
  const bad_case cases[] = {
      {R"({"sylva_preset":1,"params":{"r1":"0.5"}})", "params.r1"},
      {R"({"sylva_preset":1,"params":{"r1":"nan"}})", "params.r1"},  // JSON has no NaN: a string is a type error
      {R"({"sylva_preset":1,"params":{"derivations":true}})", "params.derivations"},
      {R"({"sylva_preset":1,"mesh":{"leaves":1}})", "mesh.leaves"},
      {R"({"sylva_preset":1,"render":{"sun_color":[1,2]}})", "render.sun_color"},
      {R"({"sylva_preset":1,"render":{"sun_color":[1,"a",2]}})", "render.sun_color"},
      {R"({"sylva_preset":1,"params":{"mode":null}})", "params.mode"},
      {R"({"sylva_preset":1,"params":{"source":5}})", "params.source"},
      {R"({"sylva_preset":1,"params":[]})", "params"},
      {R"({"sylva_preset":1,"seed":"one"})", "seed"},
      {R"({"sylva_preset":1,"seed":1.5})", "seed"},
      {R"({"sylva_preset":1,"name":3})", "name"},
      {R"({"sylva_preset":1,"tags":"tree"})", "tags"},
      {R"({"sylva_preset":"1"})", "sylva_preset"},
      {R"({"sylva_preset":1,"generator":"baobab"})", "baobab"},  // unknown generator: an error
      {R"({"sylva_preset":1,"generator":7})", "generator"},
  };
  for (const bad_case& c : cases) {
    SCOPED_TRACE(c.json);
    preset out = sentinel();
    load_result r = load_preset_json(c.json, out);
    EXPECT_FALSE(r.ok);
    EXPECT_NE(r.error.find(c.key), std::string::npos) << r.error;
    EXPECT_EQ(out, sentinel());
  }
}

TEST(PresetLoad, OutOfRangeValuesClampWithWarnings) {
  preset out;
  load_result r = load_preset_json(R"({"sylva_preset":1,"generator":"lsystem","params":{
      "r1": 5, "w0": -3, "derivations": 1e12, "alpha1": 1e300, "q": 0.25, "mode": "spiral", "e": -1e-3},
      "mesh": {"radial_segments": 2}, "render": {"sun_color": [2, 0.5, -1]}, "seed": -4})",
                                   out);
  ASSERT_TRUE(r.ok) << r.error;
  const lsystem_params& p = honda(out);
  EXPECT_EQ(p.r1, 1.2f);            // range [0.05, 1.2]
  EXPECT_EQ(p.w0, 0.1f);            // range [0.1, 200]
  EXPECT_EQ(p.derivations, 24);     // range [0, 24]
  EXPECT_EQ(p.alpha1, 180.0f);      // 1e300 overflows a float to +infinity: clamped to the max
  EXPECT_EQ(p.e, 0.0f);
  EXPECT_EQ(p.q, 0.25f);            // in range: untouched, no warning
  EXPECT_EQ(p.mode, lsystem_mode::honda);  // unknown option keeps the default
  EXPECT_EQ(out.mesh.radial_segments, 3);
  EXPECT_EQ(out.render.sun_color, glm::vec3(1, 0.5f, 0));
  EXPECT_EQ(out.spec.seed, 0u);
  // One warning each: r1, w0, derivations, alpha1, mode, e, radial_segments, sun_color, seed.
  EXPECT_EQ(r.warnings.size(), 9u);
  for (const char* key : {"params.r1", "params.w0", "params.derivations", "params.alpha1", "params.mode",
                          "params.e", "mesh.radial_segments", "render.sun_color", "seed"}) {
    bool found = false;
    for (const std::string& w : r.warnings) found |= w.rfind(key, 0) == 0;
    EXPECT_TRUE(found) << key;
  }
  // Beyond even a double, JSON's number cannot be read: an error that quotes it.
  preset keep = sentinel();
  r = load_preset_json(R"({"params":{"r1":1e999}})", keep);
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.error.find("1e999"), std::string::npos) << r.error;
  EXPECT_EQ(keep, sentinel());
}

TEST(PresetLoad, OlderSchemaAndNewerVersion) {
  // An older schema: "e" did not exist yet (missing: default), and "trunk_taper" was dropped
  // since (extra: warned about and ignored), plus an unknown top-level key.
  preset out;
  load_result r = load_preset_json(R"({"sylva_preset":1,"name":"old","generator":"lsystem",
      "params":{"r1":0.6,"trunk_taper":0.9},"thumbnail":"old.png"})", out);
  ASSERT_TRUE(r.ok) << r.error;
  EXPECT_EQ(honda(out).r1, 0.6f);
  EXPECT_EQ(honda(out).e, lsystem_params{}.e);
  EXPECT_EQ(out.mesh, mesh_params{});  // missing sections are defaults
  ASSERT_EQ(r.warnings.size(), 2u);
  EXPECT_NE(r.warnings[0].find("params.trunk_taper"), std::string::npos);
  EXPECT_NE(r.warnings[1].find("thumbnail"), std::string::npos);

  r = load_preset_json(R"({"sylva_preset":2,"params":{"r1":0.6}})", out);
  ASSERT_TRUE(r.ok) << r.error;
  ASSERT_EQ(r.warnings.size(), 1u);
  EXPECT_NE(r.warnings[0].find("written by a newer Sylva"), std::string::npos);

  r = load_preset_json(R"({"params":{"r1":0.6}})", out);  // no version at all: read as 1, warned
  ASSERT_TRUE(r.ok) << r.error;
  EXPECT_EQ(r.warnings.size(), 1u);

  preset keep = sentinel();
  r = load_preset_json(R"({"sylva_preset":0})", keep);
  EXPECT_FALSE(r.ok);
  EXPECT_EQ(keep, sentinel());
}

TEST(PresetSet, AssignmentsParseByType) {
  preset p = default_preset();
  EXPECT_EQ(set_preset_param(p, "r1=0.6"), "");
  EXPECT_EQ(honda(p).r1, 0.6f);
  EXPECT_EQ(set_preset_param(p, "params.derivations=7"), "");
  EXPECT_EQ(honda(p).derivations, 7);
  EXPECT_EQ(set_preset_param(p, "mesh.radial_segments=12"), "");
  EXPECT_EQ(p.mesh.radial_segments, 12);
  EXPECT_EQ(set_preset_param(p, "leaf_size=0.25"), "");
  EXPECT_EQ(p.mesh.leaves.size, 0.25f);
  EXPECT_EQ(set_preset_param(p, "render.sun_color=1,0.5,0.25"), "");
  EXPECT_EQ(p.render.sun_color, glm::vec3(1, 0.5f, 0.25f));
  EXPECT_EQ(set_preset_param(p, "leaves=false"), "");
  EXPECT_FALSE(p.mesh.leaves_enabled);
  EXPECT_EQ(set_preset_param(p, "mode=text"), "");
  EXPECT_EQ(honda(p).mode, lsystem_mode::text);
  EXPECT_EQ(set_preset_param(p, "source=A : * -> F[+A]"), "");  // '=' only splits once
  EXPECT_EQ(honda(p).source, "A : * -> F[+A]");

  const preset before = p;
  for (const char* bad : {"r1=abc", "r1=nan", "r1=inf", "r1=5", "r1=", "nokey=1", "r1", "=3", "derivations=2.5",
                          "mode=spiral", "leaves=maybe", "sun_color=1,2", "render.r1=0.5"}) {
    SCOPED_TRACE(bad);
    EXPECT_NE(set_preset_param(p, bad), "");
    EXPECT_EQ(p, before);
  }
  EXPECT_NE(set_preset_param(p, "r1=5").find("[0.05, 1.2]"), std::string::npos);
}

// NaN passes a range check (every comparison with it is false): documents are checked for it and
// for infinity apart, by name, wherever the number sits (the editor reverts such an edit).
TEST(PresetSet, NonFiniteNumbersAreRefusedByName) {
  EXPECT_EQ(finite_refusal("x", 1.5), "");
  EXPECT_EQ(finite_refusal("x", std::nan("")), "x: nan is not a finite number");
  EXPECT_EQ(finite_refusal("x", -HUGE_VAL), "x: -inf is not a finite number");
  const preset clean = default_preset();
  EXPECT_EQ(non_finite_refusal(clean), "");
  EXPECT_EQ(document_refusal(clean), "");
  preset p = clean;
  p.mesh.leaves.size = std::nanf("");
  std::string why = non_finite_refusal(p);
  EXPECT_NE(why.find(": nan is not a finite number"), std::string::npos) << why;
  EXPECT_EQ(document_refusal(p), why);
  p = clean;
  p.render.sun_color.y = HUGE_VALF;   // a vec3's component
  why = non_finite_refusal(p);
  EXPECT_NE(why.find(": inf is not a finite number"), std::string::npos) << why;
  p = clean;
  std::get<lsystem_params>(p.spec.params).r1 = -HUGE_VALF;   // the generator's own parameters
  EXPECT_NE(non_finite_refusal(p).find("-inf is not a finite number"), std::string::npos);
  p = clean;
  p.spec.keyframes.push_back({2, "r1", glm::vec3(std::nanf(""), 0, 0)});
  EXPECT_EQ(non_finite_refusal(p), "r1 at step 2: nan is not a finite number");
}

TEST(PresetSet, SweepsExpand) {
  const preset p = default_preset();
  std::vector<std::string> out;
  EXPECT_EQ(expand_param_sweep(p, "r1=0.25:0.75:3", out), "");
  EXPECT_EQ(out, (std::vector<std::string>{"r1=0.25", "r1=0.5", "r1=0.75"}));
  out.clear();
  EXPECT_EQ(expand_param_sweep(p, "derivations=4:9:3", out), "");  // 4, 6.5 -> 7, 9
  EXPECT_EQ(out, (std::vector<std::string>{"derivations=4", "derivations=7", "derivations=9"}));
  out.clear();
  EXPECT_EQ(expand_param_sweep(p, "r1=0.5", out), "");
  EXPECT_EQ(out, (std::vector<std::string>{"r1=0.5"}));
  out.clear();
  EXPECT_EQ(expand_param_sweep(p, "source=A:B:C", out), "");  // strings are never sweeps
  EXPECT_EQ(out, (std::vector<std::string>{"source=A:B:C"}));
  out.clear();
  EXPECT_NE(expand_param_sweep(p, "r1=0.2:0.3:0", out), "");
  EXPECT_NE(expand_param_sweep(p, "r1=0.2:0.3:x", out), "");
  EXPECT_NE(expand_param_sweep(p, "nokey=1:2:3", out), "");
  EXPECT_TRUE(out.empty());
}

TEST(Files, AtomicWriteAndRead) {
  const sylva_test::scratch_dir scratch("sylva_preset_test");
  const fs::path& dir = scratch.dir;
  const std::string path = (dir / "p.json").string();
  EXPECT_EQ(write_file_atomic(path, "first"), "");
  EXPECT_EQ(write_file_atomic(path, "second, longer"), "");
  std::string text;
  EXPECT_EQ(read_file(path, text), "");
  EXPECT_EQ(text, "second, longer");
  int entries = 0;
  for (const auto& e : fs::directory_iterator(dir)) entries += e.is_regular_file();
  EXPECT_EQ(entries, 1);  // no temporary file left behind

  const std::string bad = "/nonexistent-sylva-dir/p.json";
  const std::string e = write_file_atomic(bad, "x");
  EXPECT_NE(e.find(bad), std::string::npos) << e;
  EXPECT_NE(write_file_atomic(dir.string(), "x"), "");  // a folder is not a file
  EXPECT_NE(read_file((dir / "missing.json").string(), text).find("missing.json"), std::string::npos);
  EXPECT_EQ(text, "second, longer");

  preset p = default_preset(), q;
  EXPECT_EQ(save_preset_file(p, path), "");
  ASSERT_TRUE(load_preset_file(path, q).ok);
  EXPECT_EQ(p, q);
}

TEST(Preset, UnknownArchetypeLoadsWithAWarningAndTheDefault) {
  preset p;
  const load_result r = load_preset_json(R"({"sylva_preset": 1, "generator": "lsystem",
    "mesh": {"leaf_archetype": "fern", "leaf_mode": "shoots"}, "render": {"bark_archetype": "marble"}})", p);
  EXPECT_TRUE(r.error.empty()) << r.error;
  ASSERT_EQ(r.warnings.size(), 2u);
  EXPECT_NE(r.warnings[0].find("fern"), std::string::npos) << r.warnings[0];
  EXPECT_NE(r.warnings[1].find("marble"), std::string::npos) << r.warnings[1];
  EXPECT_EQ(p.mesh.leaves.archetype, leaf_archetype::ovate);
  EXPECT_EQ(p.render.bark, bark_archetype::furrowed);
  // A known name round-trips through save and load.
  p.mesh.leaves.archetype = leaf_archetype::needles;
  p.render.bark = bark_archetype::plated;
  preset q;
  ASSERT_TRUE(load_preset_json(save_preset_json(p), q).error.empty());
  EXPECT_EQ(q.mesh.leaves.archetype, leaf_archetype::needles);
  EXPECT_EQ(q.render.bark, bark_archetype::plated);
}

TEST(Preset, EverySpeciesPresetNamesItsArchetypes) {
  // Issue 11: every species preset chooses its leaf archetype and bark; the library has at least
  // one preset per leaf archetype (as its leaf, cluster or fruit card).
  std::set<int> leaf_used;
  int species = 0;
  for (const auto& entry : fs::directory_iterator(fs::path(SYLVA_SOURCE_DIR) / "presets")) {
    const std::string name = entry.path().filename().string();
    if (name.rfind("species_", 0) != 0) continue;
    ++species;
    std::string text;
    ASSERT_EQ(read_file(entry.path().string(), text), "");
    const auto j = nlohmann::json::parse(text);
    EXPECT_TRUE(j["mesh"].contains("leaf_archetype")) << name;
    EXPECT_TRUE(j["render"].contains("bark_archetype")) << name;
    preset p;
    ASSERT_TRUE(load_preset_json(text, p).warnings.empty()) << name;
    leaf_used.insert(int(p.mesh.leaves.archetype));
    if (p.mesh.leaves.clusters) leaf_used.insert(int(p.mesh.leaves.cluster_archetype));
    if (p.mesh.fruits.count > 0) leaf_used.insert(int(p.mesh.fruits.archetype));   // cone and fruit cards
  }
  EXPECT_GE(species, 13);
  EXPECT_EQ(leaf_used.size(), size_t(leaf_archetype_count));
}
