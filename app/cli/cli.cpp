// The headless commands: `sylva params`, `sylva export` (with batch variants) and `sylva bench`.
#include "generators/job_pool.h"
#include "app/cli/cli.h"
#include "app/bench/bench.h"
#include "app/bench/bench_set.h"
#include "app/cli/cli_batch.h"
#include "app/cli/cli_lods.h"
#include "app/cli/cli_options.h"
#include "app/bench/editor_bench.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <set>
#include <map>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "app/cli/cli_textures.h"
#include "app/common/gl_window.h"
#include "generators/timing.h"
#include "generators/lsystem_engine.h"
#include "generators/memory_bound.h"
#include "render/io/export.h"
#include "render/io/mesh_bound.h"
#include "render/io/preset.h"

namespace sylva {

namespace {

namespace fs = std::filesystem;
using json = nlohmann::ordered_json;

// ---------------------------------------------------------------------------------------------
// sylva params

template <class T>
const char* type_name(const T&) {
  if constexpr (std::is_same_v<T, float>) return "float";
  else if constexpr (std::is_same_v<T, int>) return "int";
  else if constexpr (std::is_same_v<T, bool>) return "bool";
  else if constexpr (std::is_enum_v<T>) return "enum";
  else if constexpr (std::is_same_v<T, glm::vec3>) return "vec3";
  else if constexpr (std::is_same_v<T, std::string>) return "string";
  else if constexpr (std::is_same_v<T, std::vector<float>>) return "float list";
  else return "vec3 list";
}

json flag_names(unsigned flags) {
  static const std::pair<unsigned, const char*> names[] = {
      {param_log, "log"},           {param_degrees, "degrees"}, {param_on_release, "on_release"},
      {param_advanced, "advanced"}, {param_multiline, "multiline"}, {param_path, "path"},
      {param_direction, "direction"}};
  json a = json::array();
  for (const auto& [bit, name] : names)
    if (flags & bit) a.push_back(name);
  return a;
}

// One record per parameter. Defaults come from the preset writer, so they are spelled exactly
// as in preset files (enums by name, vec3 as arrays) without a second formatter here.
template <class P>
void list_params(const P& p, const json& defaults, const char* section, const char* generator, json& out) {
  visit_params(p, [&](const auto& value, const param_info& info) {
    json r;
    r["section"] = section;
    r["generator"] = generator ? json(generator) : json(nullptr);
    r["key"] = info.key;
    r["label"] = info.label;
    r["symbol"] = info.symbol;
    r["type"] = type_name(value);
    r["min"] = info.min;
    r["max"] = info.max;
    r["default"] = defaults.contains(info.key) ? defaults[info.key] : json(nullptr);
    r["help"] = info.help;
    r["flags"] = flag_names(info.flags);
    if (info.options) {
      r["options"] = json::array();
      for (int i = 0; info.options[i]; ++i) r["options"].push_back(info.options[i]);
    }
    out.push_back(std::move(r));
  });
}

// With --preset: that preset's parameters (its values as "default") and, for a text-mode
// L-system, one "define" record per #define constant, settable as --set define.NAME=value.
int list_preset_params(const std::string& path, json& all) {
  preset p;
  const load_result loaded = load_preset_file(path, p);
  if (!loaded.ok) {
    std::fprintf(stderr, "sylva params: %s\n", loaded.error.c_str());
    return 1;
  }
  const json saved = json::parse(save_preset_json(p));
  const char* gen = generator_names[p.spec.params.index()];
  std::visit([&](const auto& gp) { list_params(gp, saved["params"], "params", gen, all); }, p.spec.params);
  list_params(p.mesh, saved["mesh"], "mesh", nullptr, all);
  list_params(p.render, saved["render"], "render", nullptr, all);
  if (const auto* lp = std::get_if<lsystem_params>(&p.spec.params); lp && lp->mode == lsystem_mode::text)
    for (const lsystem_constant& k : lsystem_constants(lp->source)) {
      json r;
      r["section"] = "define";
      r["generator"] = gen;
      r["key"] = "define." + k.name;
      r["label"] = k.name;
      r["symbol"] = k.name;
      r["type"] = "float";
      r["min"] = k.min;
      r["max"] = k.max;
      r["default"] = k.value;
      r["help"] = k.help.empty() ? "#define constant of the L-system text" : k.help;
      r["flags"] = json::array();
      all.push_back(std::move(r));
    }
  return 0;
}

int run_params(bool as_json, const std::string& preset_path) {
  json all = json::array();
  if (!preset_path.empty()) {
    if (int rc = list_preset_params(preset_path, all)) return rc;
  } else
  for (int g = 0; g < generator_count; ++g) {
    preset p;
    p.spec.params = default_params(g);
    const json saved = json::parse(save_preset_json(p));
    std::visit([&](const auto& gp) { list_params(gp, saved["params"], "params", generator_names[g], all); },
               p.spec.params);
    // Growth phases: whether `--set key@STEP=value` can key it, and why not.
    for (json& r : all)
      if (r["generator"] == generator_names[g] && r["section"] == "params") {
        const std::string why = keyframe_refusal(p.spec, r["key"].get<std::string>());
        r["keyable"] = why.empty();
        if (!why.empty()) r["keyframe_refusal"] = why;
      }
    if (g == 0) {
      list_params(p.mesh, saved["mesh"], "mesh", nullptr, all);
      list_params(p.render, saved["render"], "render", nullptr, all);
      list_params(p.spec.wood, saved["wood"], "wood", nullptr, all);
    }
  }
  if (as_json) {
    std::printf("%s\n", all.dump(2).c_str());
    return 0;
  }
  std::string heading;
  for (const json& r : all) {
    const std::string h = r["generator"].is_null() ? r["section"].get<std::string>()
                          : r["section"] == "define" ? "#define constants (--set define.NAME=value)"
                                                     : "params of generator " + r["generator"].get<std::string>();
    if (h != heading) {
      std::printf("%s%s\n", heading.empty() ? "" : "\n", h.c_str());
      if (r["section"] == "params" && !r["generator"].is_null())  // the documented bounds (memory_bound.h, mesh_bound.h)
        std::printf("  (%s)\n  (%s)\n", memory_bound_text(generator_index(r["generator"].get<std::string>())).c_str(),
                    mesh_bound_text().c_str());
      if (r["section"] == "mesh") std::printf("  (%s)\n", mesh_bound_text().c_str());
      heading = h;
    }
    const std::string sym = r["symbol"].get<std::string>();
    std::printf("  %-22s %-6s %-6s [%g, %g]  default %s\n      %s\n", r["key"].get<std::string>().c_str(),
                sym.empty() ? "-" : sym.c_str(), r["type"].get<std::string>().c_str(), r["min"].get<double>(),
                r["max"].get<double>(), r["default"].dump().c_str(), r["help"].get<std::string>().c_str());
  }
  std::printf("\n--set takes any key above as key=value (vec3 as x,y,z); prefix params., mesh., render. or wood. "
              "when a key is ambiguous.\n"
              "--set key@STEP=value keys a generator parameter from growth step STEP on (a growth phase); "
              "`sylva params --json` says which keys can be keyed (\"keyable\") and why not.\n");
  return 0;
}

// ---------------------------------------------------------------------------------------------
// sylva export

struct export_args {
  std::string preset_path, output, seeds, shard;
  uint64_t seed = 1;
  int step = -1, width = 1280, height = 720;
  std::vector<std::string> sets;
  bool instancing = false, animation = false, lods = false, compact = false;
  std::string profile = "plain";   // --profile: plain, hero, hero-baked or game
  float seconds_per_step = 0.5f;
  float wind = 0;                  // --wind SECONDS: glTF loop length, or the .png's moment
  CLI::Option* seed_opt = nullptr;
  CLI::Option* wind_opt = nullptr;
};

struct variant {
  uint64_t seed;
  std::vector<std::string> sets;  // one value per --set, sweeps expanded
};

// A batch writes at most this many files (the product of --seeds and the --set sweeps).
constexpr uint64_t max_batch_variants = 100000;

// "" and the range, or why "A-B" is not one, the batch limit named when it is too long.
std::string parse_seed_range(const std::string& s, uint64_t& a, uint64_t& b) {
  const std::string form = "--seeds expects A-B with A <= B, got \"" + s + "\"";
  const size_t dash = s.find('-');
  if (dash == std::string::npos || dash == 0 || dash + 1 >= s.size()) return form;
  try {
    size_t used = 0;
    a = std::stoull(s.substr(0, dash), &used);
    if (used != dash) return form;
    b = std::stoull(s.substr(dash + 1), &used);
    if (used != s.size() - dash - 1) return form;
  } catch (const std::exception&) {
    return form;
  }
  if (a > b) return form;
  if (b - a >= max_batch_variants) {
    const std::string n = b - a == UINT64_MAX ? "18446744073709551616" : std::to_string(b - a + 1);
    return "--seeds " + s + " is " + n + " seeds; a batch writes at most " + std::to_string(max_batch_variants) +
           " files, so split it into ranges of at most that many";
  }
  return "";
}

// The batch's variants: the product of the seed range and every --set's values, each variant's
// values applied once before anything is written (a keyframe may be past the last step of a later
// variant only), so that a sweep is refused whole, never half-written. "" or the usage error.
std::string expand_variants(const export_args& a, const preset& base, std::vector<variant>& variants, bool& swept) {
  std::vector<uint64_t> seeds;
  if (!a.seeds.empty()) {
    uint64_t s0, s1;
    if (std::string e = parse_seed_range(a.seeds, s0, s1); !e.empty()) return e;
    for (uint64_t s = s0; s <= s1; ++s) seeds.push_back(s);
  } else {
    seeds.push_back(a.seed_opt->count() ? a.seed : base.spec.seed);
  }
  for (uint64_t s : seeds) variants.push_back({s, {}});
  swept = false;
  std::vector<std::string> keyed;   // key@step of each keyframe --set: twice is a contradiction
  for (const std::string& set : a.sets) {
    if (const size_t at = set.find('@'), eq = set.find('='); at != std::string::npos && at < eq) {
      std::string key_at = set.substr(0, eq);
      if (key_at.rfind("params.", 0) == 0) key_at.erase(0, 7);
      if (std::find(keyed.begin(), keyed.end(), key_at) != keyed.end())
        return "--set " + key_at + " is given twice: two values for one key at one step contradict each other";
      keyed.push_back(key_at);
    }
    std::vector<std::string> values;
    if (std::string e = expand_param_sweep(base, set, values); !e.empty()) return e;
    swept |= values.size() > 1;
    std::vector<variant> next;
    for (const variant& v : variants)
      for (const std::string& value : values) {
        next.push_back(v);
        next.back().sets.push_back(value);
      }
    variants = std::move(next);
    if (variants.size() > max_batch_variants)
      return std::to_string(variants.size()) + " variants; a batch writes at most " + std::to_string(max_batch_variants) +
             " files (the seeds times every --set sweep's count)";
  }
  std::set<std::vector<std::string>> checked;
  for (const variant& v : variants) {
    if (!checked.insert(v.sets).second) continue;   // the same values under another seed
    preset p = base;
    for (const std::string& set : v.sets)
      if (std::string e = set_preset_param(p, set); !e.empty()) return e;
  }
  return "";
}

// One file of the export: p grown and written to path, or rendered (.png); `what` names the
// variant. Returns the exit code on failure, else -1 with the file's counts in `counts` (a mesh
// file's; a .png's are left alone).
int export_one(const export_args& a, const export_format* format, const std::string& ext, preset& p, const std::string& path,
               const std::string& what, manifest_entry& counts) {
  const char* cmd = "export";
  if (a.wind_opt && a.wind_opt->count() && !(a.wind > 0))   // finite already: add_float_option
    return usage_error(cmd, "--wind needs a loop length (glTF) or a moment (.png) in seconds > 0");
  const bool wind = a.wind_opt && a.wind_opt->count();
  if (wind) {
    p.render.wind.enabled = true;
    if (std::string msg = clamp_wind(p.render.wind); !msg.empty()) warn(path, msg);
  }
  if (format->render) {
    headless_stats stats;
    stats.wind_time = wind ? a.wind : 0.0f;
    const auto t0 = clock_type::now();
    if (std::string e = render_preset_png(p, a.step, path, a.width, a.height, &stats); !e.empty())
      return fail(cmd, path + ": " + e);
    std::printf("%s: %zu triangles, %zu leaves, %dx%d; grow %.1f ms, mesh %.1f ms, total %.1f ms (%s)\n",
                path.c_str(), stats.triangles, stats.leaves, a.width, a.height, stats.grow_ms, stats.mesh_ms,
                ms_since(t0), what.c_str());
    return -1;
  }
  auto t0 = clock_type::now();
  // A mesh over the mesh budget is refused before meshing, on a trial's estimate before growth
  // when it can be (render/io/mesh_bound.h); the skeleton JSON is never meshed.
  budgeted_growth g;
  if (format->mesh) g = grow_for_mesh(p.spec, p.mesh, format);
  else g.tree = grow(p.spec, grow_options{}, &g.report);
  const tree_skeleton& t = g.tree;
  const grow_report& report = g.report;
  const double grow_ms = ms_since(t0);
  if (report.error) return fail(cmd, path + ": growth failed: " + report.message);
  if (!g.refusal.empty()) return fail(cmd, path + ": " + g.refusal);
  if (!report.message.empty()) warn(path, report.message);
  if (a.step > t.steps) warn(path, "--step " + std::to_string(a.step) + " is past the last step (" +
                                       std::to_string(t.steps) + "); exporting the final tree");
  t0 = clock_type::now();
  const tree_mesh m = format->mesh ? mesh_tree(t, p.mesh, p.spec.seed) : tree_mesh{};
  const double mesh_ms = ms_since(t0);

  export_options o;
  o.step = a.step > t.steps ? -1 : a.step;
  const bool gltf = ext == ".glb" || ext == ".gltf";
  // Profiles (docs/design/03-foliage.md): hero = blade leaves, instanced where glTF can carry
  // them; hero-baked = blade leaves baked into the mesh; game = the LOD chain with its cards.
  o.gltf_instancing = a.instancing;
  int profile = 0;   // --profile is checked against export_profile_names
  while (export_profile_names[profile + 1] && a.profile != export_profile_names[profile]) ++profile;
  apply_export_profile(o, export_profile(profile), gltf);
  o.compact = a.compact && (ext == ".glb" || ext == ".gltf");
  if (a.compact && !o.compact) warn(path, "--compact applies to .glb and .gltf; ignored");
  o.growth_animation = a.animation;
  o.seconds_per_step = a.seconds_per_step;
  o.mesh = p.mesh;
  apply_render_params(o, p.render);  // bark archetype, tints, alpha cutoff, the user's textures
  lod_export_data lods;   // --lods (app/cli/cli_lods.h): LOD1-3 and the impostor
  if (a.lods || export_profile(profile) == export_profile::game)
    for (const std::string& w : prepare_lod_export(t, m, p, ext == ".glb" || ext == ".gltf", o, lods)) warn(path, w);
  if (wind && format->wind && !format->render) o.wind_seconds = a.wind;
  else if (wind && !format->wind) warn(path, "--wind applies to " + export_format_list(&export_format::wind) + "; ignored");
  t0 = clock_type::now();
  const export_result r = export_tree(t, m, export_info{generator_name(p.spec), p.spec.seed}, path, o);
  const double export_ms = ms_since(t0);
  if (!r.error.empty()) return fail(cmd, r.error);
  // Warnings (a user texture that could not be used) do not fail the export: it was written.
  for (size_t at = 0; at < r.warning.size();) {
    const size_t end = std::min(r.warning.find('\n', at), r.warning.size());
    warn(path, r.warning.substr(at, end - at));
    at = end + 1;
  }
  std::printf("%s: %zu nodes, %zu leaves, %zu triangles, %.1f KB; grow %.1f ms, mesh %.1f ms, export %.1f ms (%s)\n",
              path.c_str(), t.size(), m.leaves.size(), m.triangles() + 2 * m.leaves.size(),
              double(r.bytes) / 1024.0, grow_ms, mesh_ms, export_ms, what.c_str());
  if (!o.lods.empty()) {
    std::printf("%s: %s\n", path.c_str(), lod_summary(lods.chain).c_str());
    // Blades (--profile hero-baked) or a season's fallen leaves change LOD0 in the file, not the
    // flat-card LOD0 the budgets are shares of: say so rather than print shares that do not hold.
    if (r.triangles != lods.chain.triangles[0])
      warn(path, "LOD0 in the file holds " + std::to_string(r.triangles) + " triangles where the levels' budgets count " +
                     std::to_string(lods.chain.triangles[0]) + " (flat cards, every live leaf): the levels' shares of it differ from their budgets");
  }
  counts.nodes = t.size(), counts.leaves = m.leaves.size(), counts.triangles = m.triangles() + 2 * m.leaves.size();
  counts.bytes = r.bytes;
  return -1;
}

int run_export(const export_args& a) {
  const char* cmd = "export";
  std::string ext = fs::path(a.output).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  const export_format* format = find_export_format(ext);
  if (!format) return usage_error(cmd, "cannot tell the format of \"" + a.output + "\": use " + export_format_list());
  if (a.step < -1) return usage_error(cmd, "--step must be -1 (final tree) or a step number");
  if (a.seed_opt->count() && !a.seeds.empty()) return usage_error(cmd, "--seed and --seeds exclude each other");
  if (a.lods && !format->lods) return usage_error(cmd, "--lods writes " + export_format_list(&export_format::lods));
  if (a.lods && (a.animation || a.step >= 0)) return usage_error(cmd, "--lods exports the final tree; drop --animation and --step");

  preset base;
  load_result loaded = load_preset_file(a.preset_path, base);
  if (!loaded.ok) return fail(cmd, loaded.error);
  for (const std::string& w : loaded.warnings) warn(a.preset_path, w);

  std::vector<variant> variants;
  bool swept = false;
  if (std::string e = expand_variants(a, base, variants, swept); !e.empty()) return usage_error(cmd, e);
  const bool batch = variants.size() > 1;
  // --shard I/N: this job's share of the batch; the manifest records every file written and lets
  // a rerun skip those still complete (app/cli/cli_batch.h).
  int shard_index = 1, shard_count = 1;
  if (!a.shard.empty() && !parse_shard(a.shard, shard_index, shard_count))
    return usage_error(cmd, "--shard expects I/N with 1 <= I <= N, got \"" + a.shard + "\"");
  if (!a.shard.empty() && !batch) return usage_error(cmd, "--shard splits a batch: give --seeds A-B or a --set sweep");
  const bool manifest = batch && format->manifest;
  const std::string manifest_file = manifest_path(a.output, shard_index, shard_count);
  std::map<std::string, manifest_entry> done = manifest ? read_manifest(manifest_file) : std::map<std::string, manifest_entry>{};
  std::vector<manifest_entry> written;
  size_t skipped = 0;
  auto manifest_saved = clock_type::now();

  const fs::path out(a.output);
  if (out.has_parent_path()) {
    std::error_code ec;
    fs::create_directories(out.parent_path(), ec);
    if (ec) return fail(cmd, "cannot create the folder " + out.parent_path().string() + ": " + ec.message());
  }
  for (size_t i = 0; i < variants.size(); ++i) {
    if (!in_shard(i, shard_index, shard_count)) continue;
    const variant& v = variants[i];
    preset p = base;
    p.spec.seed = v.seed;
    for (const std::string& set : v.sets)
      if (std::string e = set_preset_param(p, set); !e.empty()) return usage_error(cmd, e);
    // Batch names: tree-<seed> when only the seed varies, else tree-<1-based variant index>.
    std::string path = a.output;
    if (batch) {
      const std::string suffix = swept ? std::to_string(i + 1) : std::to_string(v.seed);
      path = (out.parent_path() / (out.stem().string() + "-" + suffix + out.extension().string())).string();
    }
    if (manifest) {   // a rerun: a file the manifest lists with its size and hash is kept
      const auto it = done.find(fs::path(path).filename().string());
      if (it != done.end() && it->second.variant == i + 1 && still_complete(it->second, out.parent_path().string())) {
        written.push_back(it->second);
        ++skipped;
        continue;
      }
    }
    std::string what = "seed " + std::to_string(v.seed);
    for (const std::string& set : v.sets) what += ", " + set;
    manifest_entry e{i + 1, v.seed, fs::path(path).filename().string()};
    if (const int code = export_one(a, format, ext, p, path, what, e); code >= 0) return code;
    if (manifest && !format->render) {   // rewritten (atomically, synced) at most once a second: a killed job redoes only the last second's files
      e.sha256 = sha256_file(path);
      if (e.sha256.empty()) return fail(cmd, "cannot read back " + path + " to hash it");
      written.push_back(e);
      if (ms_since(manifest_saved) > 1000.0) {
        if (std::string err = write_manifest(manifest_file, written); !err.empty()) return fail(cmd, err);
        manifest_saved = clock_type::now();
      }
    }
  }
  if (manifest) {
    if (std::string err = write_manifest(manifest_file, written); !err.empty()) return fail(cmd, err);
    std::printf("%s: %zu files (%zu already complete, skipped)\n", manifest_file.c_str(), written.size(), skipped);
  }
  return 0;
}

}  // namespace

bool is_cli_command(const char* arg) {
  return !std::strcmp(arg, "params") || !std::strcmp(arg, "export") || !std::strcmp(arg, "bench") ||
         !std::strcmp(arg, "textures");
}

int run_cli(int argc, char** argv) {
  if (argc >= 2 && !std::strcmp(argv[1], "textures")) return run_textures_cli(argc, argv);  // app/cli/cli_textures.cpp
  CLI::App app{"Sylva: a tree designer. Without a command, `sylva [PRESET.json]` opens the editor.", "sylva"};
  app.require_subcommand(1);

  bool params_json = false;
  CLI::App* params = app.add_subcommand("params", "List every parameter: generator, key, symbol, range, default, help");
  params->add_flag("--json", params_json, "Print one JSON array");
  std::string params_preset;
  params->add_option("--preset", params_preset,
                     "List this preset's parameters with its values, and a text L-system's #define constants");

  export_args ex;
  CLI::App* exp = app.add_subcommand("export", "Grow a preset and write it; OUT's extension picks the format");
  exp->add_option("preset", ex.preset_path, "Preset JSON file")->required();
  exp->add_option("-o,--output", ex.output, "Output file: .glb .gltf .obj .fbx .json (skeleton) .png (render)")->required();
  ex.seed_opt = exp->add_option("--seed", ex.seed, "Seed (default: the preset's)");
  exp->add_option("--step", ex.step, "Export the tree as it stood at this growth step (-1: final)");
  exp->add_option("--set", ex.sets, "key=value, key=from:to:count to sweep a number, or key@STEP=value for a keyframe (repeatable)");
  exp->add_option("--seeds", ex.seeds, "A-B: one file per seed, OUT-A ... OUT-B, and OUT-manifest.tsv (seed, file, counts, SHA-256)");
  exp->add_option("--shard", ex.shard,
                  "I/N: write only variants I, I+N, I+2N ... of the batch (one job of N), manifest OUT-manifest-IofN.tsv; "
                  "a rerun skips the files its manifest lists as complete");
  exp->add_option("--width", ex.width, ".png width")->check(CLI::Range(16, 8192));
  exp->add_option("--height", ex.height, ".png height")->check(CLI::Range(16, 8192));
  exp->add_flag("--instancing", ex.instancing, "glTF: leaves as EXT_mesh_gpu_instancing instead of baked quads");
  std::string profile_help = "How the file carries the leaves:";
  for (int k = 0; export_profile_names[k]; ++k)
    profile_help += std::string(k ? "; " : " ") + export_profile_names[k] + (k ? "" : " (default)") + ": " + export_profile_help[k];
  const std::vector<std::string> profiles(export_profile_names, export_profile_names + std::size(export_profile_names) - 1);
  exp->add_option("--profile", ex.profile, profile_help)->check(CLI::IsMember(profiles));
  exp->add_flag("--compact", ex.compact,
                "glTF: quantized vertices (KHR_mesh_quantization), meshopt-compressed buffers (EXT_meshopt_compression), "
                "opaque textures as JPEG");
  exp->add_flag("--animation", ex.animation, "glTF: the growth steps as a STEP-interpolated animation");
  exp->add_flag("--lods", ex.lods, "Also write LOD1-LOD3 (budgets: render lod1_budget...) and, glTF, the impostor: glTF as MSFT_lod, FBX as an LOD group of <name>_LOD0..3, OBJ one file per level");
  add_float_option(exp, "--seconds-per-step", ex.seconds_per_step, "glTF animation speed", 0.001f, 60.0f);
  ex.wind_opt = add_float_option(exp, "--wind", ex.wind,
                                 "glTF, FBX: bake the preset's wind (render.wind_*) as a skin and a seamless loop of SECONDS "
                                 "(0.5-60); .png: render the wind's motion at SECONDS");

  std::vector<std::string> bench_paths;
  int repeat = 5;
  bool bench_json = false, bench_export = false, bench_render = false, bench_edit = false, bench_lods = false;
  int bench_width = 1280, bench_height = 720;
  bool bench_preset_light = false;
  CLI::App* bench = app.add_subcommand("bench", "Time grow and mesh per preset (default: every bench/*.json)");
  bench->add_option("presets", bench_paths, "Preset JSON files");
  bench->add_option("--repeat", repeat, "Runs per preset; medians are reported")->check(CLI::Range(1, 1000));
  bench->add_flag("--json", bench_json, "One JSON object per line");
  bench->add_flag("--export", bench_export, "Also time GLB export and report the file size");
  bool bench_stages = false;
  bench->add_flag("--stages", bench_stages, "Also time each stage of the mesher (frame, budget, rings, index, leaf placement, sky field, occlusion with the leaf sort and the bounds)");
  bench->add_flag("--render", bench_render,
                  "Time rendering instead: frame ms per pass (needs DISPLAY; default: one preset per generator)");
  bench->add_flag("--lods", bench_lods, "LOD triangles against their budgets, LOD build and impostor atlas times (default: every species preset)");
  std::string bench_sheet;
  bench->add_option("--sheet", bench_sheet, "--lods: also write each level's render and the impostor atlas as PNGs into this folder");
  bench->add_flag("--edit", bench_edit, "Time a slider release to the new tree on screen (worker, upload, one frame)");
  bench->add_option("--width", bench_width, "--render: image width")->check(CLI::Range(16, 8192));
  bench->add_option("--height", bench_height, "--render: image height")->check(CLI::Range(16, 8192));
  bench->add_flag("--preset-light", bench_preset_light,
                  "--render: keep each preset's sun (default: backlit with shadows and god rays, every pass runs)");
  std::string bench_ab;
  bench->add_option("--ab", bench_ab, "--render: time the A/B view (each preset as A beside this one as B) against A alone");
  int bench_threads = 0;
  bench->add_option("--threads", bench_threads,
                    "Threads the job pool may use for each parallel stage (1: the single-threaded path; default: all)")
      ->check(CLI::Range(1, 64));
  std::vector<std::string> bench_sets;
  bench->add_option("--set", bench_sets,
                    "key=value (as export --set, one value; repeatable) applied to every preset benched, e.g. render.wind=true")
      ->allow_extra_args(false);   // one value per --set: the preset paths that follow stay positional

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::string where = "sylva";
    for (CLI::App* sub : {params, exp, bench})
      if (sub->parsed()) where += " " + sub->get_name();
    std::fprintf(stderr, "%s: %s (see %s --help)\n", where.c_str(), e.what(), where.c_str());
    return 2;
  }
  try {
    if (params->parsed()) return run_params(params_json, params_preset);
    if (exp->parsed()) return run_export(ex);
    if (bench->parsed()) {
      if (std::string e = set_bench_sets(bench_sets); !e.empty()) return usage_error("bench", e);
      if (!bench_sets.empty()) std::fprintf(stderr, "sylva bench: every preset with %s\n", bench_sets_label().c_str());
      if (bench_threads > 0) set_job_pool_limit(bench_threads);
    }
    if (bench->parsed() && bench_lods)
      return run_bench_lods(bench_paths, repeat, bench_json, bench_sheet, bench_width, bench_height);
    if (bench->parsed() && bench_edit) return run_bench_edit(bench_paths, repeat, bench_json, bench_width, bench_height);
    if (bench->parsed() && !bench_ab.empty() && !bench_render) return usage_error("bench", "--ab times frames: give it with --render");
    if (bench->parsed() && bench_render) {
      if (bench_export) return usage_error("bench", "--render and --export time different things; give one");
      if (!bench_ab.empty())
        return run_bench_render_ab(bench_paths, bench_ab, repeat, bench_json, bench_width, bench_height, bench_preset_light);
      return run_bench_render(bench_paths, repeat, bench_json, bench_width, bench_height, bench_preset_light);
    }
    if (bench->parsed()) return run_bench(bench_paths, repeat, bench_json, bench_export, bench_stages);
  } catch (const std::bad_alloc&) {  // last line of defence: the memory ran out past every bound and budget
    const char* why = "out of memory: lower the node cap, the steps or the mesh settings (radial_segments, curve_rings), "
                      "or the mesh budget (mesh.mesh_budget)";
    for (CLI::App* sub : {params, exp, bench})
      if (sub->parsed()) return fail(sub->get_name(), why);
    std::fprintf(stderr, "sylva: %s\n", why);
    return 1;
  } catch (const std::exception& e) {  // last resort: a library threw; still one line and exit 1
    for (CLI::App* sub : {params, exp, bench})
      if (sub->parsed()) return fail(sub->get_name(), e.what());
    std::fprintf(stderr, "sylva: %s\n", e.what());
    return 1;
  }
  return 2;
}

}  // namespace sylva
