// The headless commands: `sylva params`, `sylva export` (with batch variants) and `sylva bench`.
#include "app/cli.h"
#include "app/editor_bench.h"

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include <epoxy/gl.h>
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "app/cli_textures.h"
#include "app/headless.h"
#include "app/timing.h"
#include "render/export.h"
#include "render/files.h"
#include "render/gl/renderer.h"

namespace sylva {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::ordered_json;

// Failure: one line on stderr, exit 1 (DESIGN §7).
int fail(const std::string& command, const std::string& reason) {
  std::fprintf(stderr, "sylva %s: %s\n", command.c_str(), reason.c_str());
  return 1;
}
int usage_error(const std::string& command, const std::string& reason) {
  std::fprintf(stderr, "sylva %s: %s (see sylva %s --help)\n", command.c_str(), reason.c_str(), command.c_str());
  return 2;
}
void warn(const std::string& what, const std::string& message) {
  std::fprintf(stderr, "warning: %s: %s\n", what.c_str(), message.c_str());
}

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

int run_params(bool as_json) {
  json all = json::array();
  for (int g = 0; g < generator_count; ++g) {
    preset p;
    p.spec.params = default_params(g);
    const json saved = json::parse(save_preset_json(p));
    std::visit([&](const auto& gp) { list_params(gp, saved["params"], "params", generator_names[g], all); },
               p.spec.params);
    if (g == 0) {
      list_params(p.mesh, saved["mesh"], "mesh", nullptr, all);
      list_params(p.render, saved["render"], "render", nullptr, all);
    }
  }
  if (as_json) {
    std::printf("%s\n", all.dump(2).c_str());
    return 0;
  }
  std::string heading;
  for (const json& r : all) {
    const std::string h = r["generator"].is_null() ? r["section"].get<std::string>()
                                                   : "params of generator " + r["generator"].get<std::string>();
    if (h != heading) {
      std::printf("%s%s\n", heading.empty() ? "" : "\n", h.c_str());
      heading = h;
    }
    const std::string sym = r["symbol"].get<std::string>();
    std::printf("  %-22s %-6s %-6s [%g, %g]  default %s\n      %s\n", r["key"].get<std::string>().c_str(),
                sym.empty() ? "-" : sym.c_str(), r["type"].get<std::string>().c_str(), r["min"].get<double>(),
                r["max"].get<double>(), r["default"].dump().c_str(), r["help"].get<std::string>().c_str());
  }
  std::printf("\n--set takes any key above as key=value (vec3 as x,y,z); prefix params., mesh. or render. "
              "when a key is ambiguous.\n");
  return 0;
}

// ---------------------------------------------------------------------------------------------
// sylva export

struct export_args {
  std::string preset_path, output, seeds;
  uint64_t seed = 1;
  int step = -1, width = 1280, height = 720;
  std::vector<std::string> sets;
  bool instancing = false, animation = false;
  float seconds_per_step = 0.5f;
  CLI::Option* seed_opt = nullptr;
};

struct variant {
  uint64_t seed;
  std::vector<std::string> sets;  // one value per --set, sweeps expanded
};

bool parse_seed_range(const std::string& s, uint64_t& a, uint64_t& b) {
  const size_t dash = s.find('-');
  if (dash == std::string::npos || dash == 0 || dash + 1 >= s.size()) return false;
  try {
    size_t used = 0;
    a = std::stoull(s.substr(0, dash), &used);
    if (used != dash) return false;
    b = std::stoull(s.substr(dash + 1), &used);
    if (used != s.size() - dash - 1) return false;
  } catch (const std::exception&) {
    return false;
  }
  return a <= b && b - a < 100000;
}

int run_export(const export_args& a) {
  const char* cmd = "export";
  std::string ext = fs::path(a.output).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  if (std::find(std::begin(export_formats), std::end(export_formats), ext) == std::end(export_formats))
    return usage_error(cmd, "cannot tell the format of \"" + a.output + "\": use .glb, .gltf, .obj, .json or .png");
  if (a.step < -1) return usage_error(cmd, "--step must be -1 (final tree) or a step number");
  if (a.seed_opt->count() && !a.seeds.empty()) return usage_error(cmd, "--seed and --seeds exclude each other");

  preset base;
  load_result loaded = load_preset_file(a.preset_path, base);
  if (!loaded.ok) return fail(cmd, loaded.error);
  for (const std::string& w : loaded.warnings) warn(a.preset_path, w);

  // Variants: the product of the seed range and every --set's values.
  std::vector<uint64_t> seeds;
  if (!a.seeds.empty()) {
    uint64_t s0, s1;
    if (!parse_seed_range(a.seeds, s0, s1))
      return usage_error(cmd, "--seeds expects A-B with A <= B, got \"" + a.seeds + "\"");
    for (uint64_t s = s0; s <= s1; ++s) seeds.push_back(s);
  } else {
    seeds.push_back(a.seed_opt->count() ? a.seed : base.spec.seed);
  }
  std::vector<variant> variants;
  for (uint64_t s : seeds) variants.push_back({s, {}});
  bool swept = false;
  for (const std::string& set : a.sets) {
    std::vector<std::string> values;
    if (std::string e = expand_param_sweep(base, set, values); !e.empty()) return usage_error(cmd, e);
    swept |= values.size() > 1;
    std::vector<variant> next;
    for (const variant& v : variants)
      for (const std::string& value : values) {
        next.push_back(v);
        next.back().sets.push_back(value);
      }
    variants = std::move(next);
    if (variants.size() > 100000) return usage_error(cmd, "more than 100000 variants");
  }
  const bool batch = variants.size() > 1;

  const fs::path out(a.output);
  if (out.has_parent_path()) {
    std::error_code ec;
    fs::create_directories(out.parent_path(), ec);
    if (ec) return fail(cmd, "cannot create the folder " + out.parent_path().string() + ": " + ec.message());
  }
  for (size_t i = 0; i < variants.size(); ++i) {
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
    std::string what = "seed " + std::to_string(v.seed);
    for (const std::string& set : v.sets) what += ", " + set;

    if (ext == ".png") {
      headless_stats stats;
      const auto t0 = clock_type::now();
      if (std::string e = render_preset_png(p, a.step, path, a.width, a.height, &stats); !e.empty())
        return fail(cmd, path + ": " + e);
      std::printf("%s: %zu triangles, %zu leaves, %dx%d; grow %.1f ms, mesh %.1f ms, total %.1f ms (%s)\n",
                  path.c_str(), stats.triangles, stats.leaves, a.width, a.height, stats.grow_ms, stats.mesh_ms,
                  ms_since(t0), what.c_str());
      continue;
    }
    auto t0 = clock_type::now();
    grow_report report;
    const tree_skeleton t = grow(p.spec, grow_options{}, &report);
    const double grow_ms = ms_since(t0);
    if (report.error) return fail(cmd, path + ": growth failed: " + report.message);
    if (!report.message.empty()) warn(path, report.message);
    if (a.step > t.steps) warn(path, "--step " + std::to_string(a.step) + " is past the last step (" +
                                         std::to_string(t.steps) + "); exporting the final tree");
    t0 = clock_type::now();
    const tree_mesh m = mesh_tree(t, p.mesh, p.spec.seed);
    const double mesh_ms = ms_since(t0);

    export_options o;
    o.step = a.step > t.steps ? -1 : a.step;
    o.gltf_instancing = a.instancing;
    o.growth_animation = a.animation;
    o.seconds_per_step = a.seconds_per_step;
    o.mesh = p.mesh;
    apply_render_params(o, p.render);  // bark archetype, tints, alpha cutoff, the user's textures
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
  }
  return 0;
}

// ---------------------------------------------------------------------------------------------
// sylva bench

struct bench_result {  // plain bytes: sent from the measuring child through a pipe
  uint64_t nodes = 0, leaves = 0, triangles = 0, glb_bytes = 0;
  double grow_ms = 0, mesh_ms = 0, export_ms = 0, peak_rss_mb = 0;
  double grow_peak_rss_mb = 0;   // peak RSS after the first grow, before any mesh (the growth's own peak)
  int steps = 0;
  bool hit_node_cap = false, error = false;
  char message[240] = {};
};

double process_peak_rss_mb() {
  rusage ru{};
  getrusage(RUSAGE_SELF, &ru);
  return double(ru.ru_maxrss) / 1024.0;  // Linux reports kilobytes
}

bench_result measure(const preset& p, int repeat, bool with_export) {
  bench_result r;
  std::vector<double> grow_ms, mesh_ms, export_ms;
  tree_skeleton t;
  tree_mesh m;
  grow_report report;
  for (int i = 0; i < repeat; ++i) {
    report = {};
    auto t0 = clock_type::now();
    t = grow(p.spec, grow_options{}, &report);
    grow_ms.push_back(ms_since(t0));
    if (i == 0) r.grow_peak_rss_mb = process_peak_rss_mb();
    t0 = clock_type::now();
    m = mesh_tree(t, p.mesh, p.spec.seed);
    mesh_ms.push_back(ms_since(t0));
  }
  if (with_export) {
    const fs::path tmp = fs::temp_directory_path() / ("sylva-bench-" + std::to_string(::getpid()) + ".glb");
    export_options o;
    o.mesh = p.mesh;
    o.texture_seed = p.spec.seed;
    for (int i = 0; i < repeat; ++i) {
      const auto t0 = clock_type::now();
      export_result e = export_tree(t, m, export_info{generator_name(p.spec), p.spec.seed}, tmp.string(), o);
      export_ms.push_back(ms_since(t0));
      if (!e.error.empty()) {
        std::snprintf(r.message, sizeof r.message, "GLB export failed: %s", e.error.c_str());
        r.error = true;
        break;
      }
      r.glb_bytes = e.bytes;
    }
    std::error_code ec;
    fs::remove(tmp, ec);
  }
  r.nodes = t.size();
  r.leaves = m.leaves.size();
  r.triangles = m.triangles() + 2 * m.leaves.size();  // bark plus one quad per leaf, as exported
  r.steps = t.steps;
  r.grow_ms = median(grow_ms);
  r.mesh_ms = median(mesh_ms);
  r.export_ms = median(export_ms);
  r.hit_node_cap = report.hit_node_cap;
  if (!r.error && !report.message.empty()) {
    std::snprintf(r.message, sizeof r.message, "%s", report.message.c_str());
    r.error = report.error;
  }
  return r;
}

// Runs the workload in a forked child so that each preset's peak RSS is its own (wait4 returns
// the child's ru_maxrss); falls back to this process and its running peak if fork fails.
bench_result measure_isolated(const preset& p, int repeat, bool with_export, bool& isolated) {
  int fds[2];
  isolated = false;
  if (::pipe(fds) == 0) {
    std::fflush(nullptr);
    const pid_t pid = ::fork();
    if (pid == 0) {
      ::close(fds[0]);
      const bench_result r = measure(p, repeat, with_export);
      const ssize_t n = ::write(fds[1], &r, sizeof r);
      ::_exit(n == ssize_t(sizeof r) ? 0 : 1);
    }
    ::close(fds[1]);
    if (pid > 0) {
      bench_result r;
      size_t got = 0;
      while (got < sizeof r) {
        const ssize_t n = ::read(fds[0], reinterpret_cast<char*>(&r) + got, sizeof r - got);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) break;
        got += size_t(n);
      }
      ::close(fds[0]);
      int status = 0;
      rusage ru{};
      while (::wait4(pid, &status, 0, &ru) < 0 && errno == EINTR) {}
      isolated = true;
      if (got != sizeof r || !WIFEXITED(status) || WEXITSTATUS(status) != 0) {
        bench_result bad;
        bad.error = true;
        std::snprintf(bad.message, sizeof bad.message, "the measuring process died (%s)",
                      WIFSIGNALED(status) ? strsignal(WTERMSIG(status)) : "no result");
        return bad;
      }
      r.peak_rss_mb = double(ru.ru_maxrss) / 1024.0;
      return r;
    }
    ::close(fds[0]);
  }
  bench_result r = measure(p, repeat, with_export);
  r.peak_rss_mb = process_peak_rss_mb();
  return r;
}

int bench_one(const std::string& path, int repeat, bool as_json, bool with_export);

int run_bench(std::vector<std::string> paths, int repeat, bool as_json, bool with_export) {
  const char* cmd = "bench";
  if (paths.empty()) {
    const fs::path dir = fs::path(SYLVA_SOURCE_DIR) / "bench";
    std::error_code ec;
    for (const auto& e : fs::directory_iterator(dir, ec))
      if (e.path().extension() == ".json") paths.push_back(e.path().string());
    if (ec || paths.empty()) return fail(cmd, "no presets given and none found in " + dir.string());
    std::sort(paths.begin(), paths.end());
  }
  if (!as_json)
    std::printf("%-36s %-18s %9s %9s %10s %9s %9s %8s %8s%s\n", "preset", "generator", "nodes", "leaves", "triangles",
                "grow_ms", "mesh_ms", "grow_MB", "peak_MB", with_export ? "  glb_ms     glb_MB" : "");
  int failures = 0;
  for (const std::string& path : paths) {
    try {   // one preset's failure is reported and the rest are still measured
      failures += bench_one(path, repeat, as_json, with_export);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "sylva %s: %s: %s\n", cmd, path.c_str(), e.what());
      ++failures;
    }
    std::fflush(stdout);
  }
  if (!as_json)
    std::printf("medians over %d runs; peak_MB is each preset's own peak RSS (measured in a child process), grow_MB "
                "that peak right after the first grow, before meshing\n",
                repeat);
  return failures ? 1 : 0;
}

// One preset of `sylva bench`: 0 when measured, 1 when it failed (reported on stderr).
int bench_one(const std::string& path, int repeat, bool as_json, bool with_export) {
  {
    preset p;
    load_result loaded = load_preset_file(path, p);
    if (!loaded.ok) {
      std::fprintf(stderr, "sylva bench: %s\n", loaded.error.c_str());
      return 1;
    }
    for (const std::string& w : loaded.warnings) warn(path, w);
    bool isolated = false;
    const bench_result r = measure_isolated(p, repeat, with_export, isolated);
    if (r.message[0]) {
      if (r.error) {
        std::fprintf(stderr, "sylva bench: %s: %s\n", path.c_str(), r.message);
        return 1;
      }
      warn(path, r.message);
    }
    const std::string name = fs::path(path).stem().string();
    if (as_json) {
      json j;
      j["preset"] = name;
      j["generator"] = generator_name(p.spec);
      j["nodes"] = r.nodes;
      j["leaves"] = r.leaves;
      j["triangles"] = r.triangles;
      j["grow_ms"] = r.grow_ms;
      j["mesh_ms"] = r.mesh_ms;
      j["peak_rss_mb"] = r.peak_rss_mb;
      j["grow_peak_rss_mb"] = r.grow_peak_rss_mb;
      j["peak_rss_scope"] = isolated ? "preset" : "process";
      j["steps"] = r.steps;
      j["repeat"] = repeat;
      if (r.hit_node_cap) j["hit_node_cap"] = true;
      if (with_export) {
        j["export_ms"] = r.export_ms;
        j["glb_bytes"] = r.glb_bytes;
      }
      // A file name need not be UTF-8; its bad bytes print as U+FFFD instead of throwing.
      std::printf("%s\n", j.dump(-1, ' ', false, json::error_handler_t::replace).c_str());
    } else {
      std::printf("%-36s %-18s %9llu %9llu %10llu %9.2f %9.2f %8.1f %8.1f", name.c_str(), generator_name(p.spec),
                  (unsigned long long)r.nodes, (unsigned long long)r.leaves, (unsigned long long)r.triangles,
                  r.grow_ms, r.mesh_ms, r.grow_peak_rss_mb, r.peak_rss_mb);
      if (with_export) std::printf(" %8.1f %10.2f", r.export_ms, double(r.glb_bytes) / (1024.0 * 1024.0));
      std::printf("%s\n", isolated ? "" : "  (peak of the whole process)");
    }
  }
  return 0;
}

// ---------------------------------------------------------------------------------------------
// sylva bench --render: frame cost per pass with the editor's renderer

struct render_bench_result {
  size_t nodes = 0, leaves = 0, triangles = 0;
  double shadow_ms = 0, lit_ms = 0, occlusion_ms = 0, blur_ms = 0, march_ms = 0, exposure_ms = 0, composite_ms = 0,
         frame_ms = 0;
  double take_ms = 0;    // a new tree taken as the editor takes a worker result, before its first frame
  frame_counts counts;   // of the last measured frame
};

// Steady-state frames, not the PNG path's single first frame: one warm-up frame allocates the
// targets and lets the driver compile its shader variants, then `repeat` frames are timed, each
// pass closed by glFinish (renderer_state::measure_passes). With `all_effects` the sun is put behind
// the tree as the editor's "Backlit rays" button does, with shadows on, and the frames are drawn
// once with the radial shafts and once with the volumetric ones (the reported frame), so that every
// pass runs and a regression in any of them shows; otherwise the preset's own light is used.
std::string measure_render(const preset& p, int repeat, int width, int height, bool all_effects,
                           render_bench_result& out) {
  grow_report report;
  growth_debug debug;
  const tree_skeleton t = grow(p.spec, grow_options{}, &report, &debug);
  if (report.error) return "growth failed: " + report.message;
  const tree_mesh m = mesh_tree(t, p.mesh, p.spec.seed);
  const auto overlays = std::make_shared<const overlay_geometry>(build_overlays(debug, &t));   // the worker's part
  out.nodes = t.size();

  hidden_gl_context context;
  if (std::string why = open_hidden_gl_context(context, "sylva bench", false); !why.empty()) return why;

  std::string error;
  renderer_state r;
  gl_texture color;
  gl_framebuffer target;
  if (!init_renderer(r)) error = r.error.empty() ? "renderer initialisation failed" : r.error;
  if (error.empty()) {
    upload_tree(r, m);
    set_tree_step(r, t, p.mesh.min_radius, t.steps);
    orbit_camera cam;
    frame_camera(cam, r.bounds_min, r.bounds_max, float(width) / float(height));
    render_params rp = p.render;
    if (all_effects) {
      place_sun_behind(rp, cam.yaw);
      rp.shadows = true;
    }
    const bool both = all_effects;
    // The image goes to an off-screen RGBA8 target of the asked size, as for `export x.png`.
    error = create_color_target(width, height, color, target);
    const int errors_before = gl_error_count();
    std::vector<double> shadow, lit, occlusion, blur, march, exposure, composite, frame, take;
    // The frame that takes a new tree costs this more than a steady one: what the editor does on the
    // UI thread with a worker's result (mesh and overlay upload, the step's radii), overlays hidden.
    for (int i = 0; i <= repeat && error.empty(); ++i) {
      const auto t0 = clock_type::now();
      upload_tree(r, m);
      set_overlays(r, overlays);
      set_tree_step(r, t, p.mesh.min_radius, t.steps);
      glFinish();
      if (i > 0) take.push_back(ms_since(t0));
      draw_frame(r, rp, cam, width, height, target);
    }
    r.measure_passes = true;
    if (both) {   // the radial shafts' two passes, timed on their own frames
      render_params radial = rp;
      radial.shafts = light_shafts::radial;
      for (int i = 0; i <= repeat && error.empty(); ++i) {
        draw_frame(r, radial, cam, width, height, target);
        glFinish();
        if (i == 0) continue;
        occlusion.push_back(r.timings.occlusion);
        blur.push_back(r.timings.blur);
      }
      rp.shafts = light_shafts::volumetric;
    }
    for (int i = 0; i <= repeat && error.empty(); ++i) {
      const auto t0 = clock_type::now();
      draw_frame(r, rp, cam, width, height, target);
      glFinish();
      if (i == 0) continue;   // warm-up
      frame.push_back(ms_since(t0));
      shadow.push_back(r.timings.shadow);
      lit.push_back(r.timings.lit);
      if (!both) occlusion.push_back(r.timings.occlusion), blur.push_back(r.timings.blur);
      march.push_back(r.timings.march);
      exposure.push_back(r.timings.exposure);
      composite.push_back(r.timings.composite);
    }
    check_gl("bench frames");
    if (error.empty() && gl_error_count() > errors_before)
      error = std::to_string(gl_error_count() - errors_before) + " GL error(s): " + gl_last_message();
    out.leaves = r.leaves_drawn;
    out.triangles = r.triangles_drawn + 2 * r.leaves_drawn;   // bark plus one quad per leaf
    out.shadow_ms = median(shadow);
    out.lit_ms = median(lit);
    out.occlusion_ms = median(occlusion);
    out.blur_ms = median(blur);
    out.march_ms = median(march);
    out.exposure_ms = median(exposure);
    out.composite_ms = median(composite);
    out.frame_ms = median(frame);
    out.take_ms = median(take);
    out.counts = r.counts;
  }
  delete_gl(target);
  delete_gl(color);
  destroy_renderer(r);
  close_hidden_gl_context(context);
  return error;
}

int run_bench_render(std::vector<std::string> paths, int repeat, bool as_json, int width, int height,
                     bool preset_light) {
  const char* cmd = "bench --render";
if (std::string why = display_missing("rendering"); !why.empty()) return fail(cmd, why);
  if (paths.empty()) {   // the default presets: Honda's tree a and one preset per other generator
    for (const char* name : {"lsystem_honda_a", "self_organizing_default", "space_colonization_seed_cube",
                             "guiding_vectors_default"})
      paths.push_back((fs::path(SYLVA_SOURCE_DIR) / "presets" / (std::string(name) + ".json")).string());
  }
  if (!as_json)
    std::printf("%-30s %10s %8s %9s %9s %9s %9s %9s %9s %9s %9s %9s %6s %7s\n", "preset", "triangles", "leaves",
                "shadow_ms", "lit_ms", "occl_ms", "blur_ms", "march_ms", "expo_ms", "comp_ms", "frame_ms", "take_ms",
                "draws", "uploads");
  int failures = 0;
  for (const std::string& path : paths) {
    preset p;
    load_result loaded = load_preset_file(path, p);
    if (!loaded.ok) {
      std::fprintf(stderr, "sylva %s: %s\n", cmd, loaded.error.c_str());
      ++failures;
      continue;
    }
    for (const std::string& w : loaded.warnings) warn(path, w);
    render_bench_result r;
    if (std::string e = measure_render(p, repeat, width, height, !preset_light, r); !e.empty()) {
      std::fprintf(stderr, "sylva %s: %s: %s\n", cmd, path.c_str(), e.c_str());
      ++failures;
      continue;
    }
    const std::string name = fs::path(path).stem().string();
    if (as_json) {
      json j;
      j["preset"] = name;
      j["generator"] = generator_name(p.spec);
      j["width"] = width;
      j["height"] = height;
      j["light"] = preset_light ? "preset" : "backlit";
      j["nodes"] = r.nodes;
      j["leaves"] = r.leaves;
      j["triangles"] = r.triangles;
      j["shadow_ms"] = r.shadow_ms;
      j["lit_ms"] = r.lit_ms;
      j["occlusion_ms"] = r.occlusion_ms;
      j["blur_ms"] = r.blur_ms;
      j["march_ms"] = r.march_ms;
      j["exposure_ms"] = r.exposure_ms;
      j["composite_ms"] = r.composite_ms;
      j["frame_ms"] = r.frame_ms;
      j["take_ms"] = r.take_ms;
      j["draw_calls"] = r.counts.draw_calls;
      j["leaf_draw_calls"] = r.counts.leaf_draw_calls;
      j["uploads"] = r.counts.uploads;
      j["repeat"] = repeat;
      std::printf("%s\n", j.dump().c_str());
    } else {
      std::printf("%-30s %10zu %8zu %9.2f %9.2f %9.2f %9.2f %9.2f %9.2f %9.2f %9.2f %9.2f %6d %7d\n", name.c_str(),
                  r.triangles, r.leaves, r.shadow_ms, r.lit_ms, r.occlusion_ms, r.blur_ms, r.march_ms, r.exposure_ms,
                  r.composite_ms, r.frame_ms, r.take_ms, r.counts.draw_calls, r.counts.uploads);
    }
    std::fflush(stdout);
  }
  if (!as_json)
    std::printf("%dx%d, medians over %d frames after one warm-up; each pass ends in glFinish; take: a new tree's "
                "uploads before its first frame, overlays hidden, as the editor takes a worker result; %s\n", width, height,
                repeat,
                preset_light ? "the presets' own light (a pass that does not run reads 0)"
                             : "sun behind the tree, shadows on; occl+blur: radial shafts, timed on their own frames; "
                               "march: volumetric shafts, in the frame reported (--preset-light: the presets' own)");
  return failures ? 1 : 0;
}

}  // namespace

bool is_cli_command(const char* arg) {
  return !std::strcmp(arg, "params") || !std::strcmp(arg, "export") || !std::strcmp(arg, "bench") ||
         !std::strcmp(arg, "textures");
}

int run_cli(int argc, char** argv) {
  if (argc >= 2 && !std::strcmp(argv[1], "textures")) return run_textures_cli(argc, argv);  // app/cli_textures.cpp
  CLI::App app{"Sylva: a tree designer. Without a command, `sylva [PRESET.json]` opens the editor.", "sylva"};
  app.require_subcommand(1);

  bool params_json = false;
  CLI::App* params = app.add_subcommand("params", "List every parameter: generator, key, symbol, range, default, help");
  params->add_flag("--json", params_json, "Print one JSON array");

  export_args ex;
  CLI::App* exp = app.add_subcommand("export", "Grow a preset and write it; OUT's extension picks the format");
  exp->add_option("preset", ex.preset_path, "Preset JSON file")->required();
  exp->add_option("-o,--output", ex.output, "Output file: .glb .gltf .obj .json (skeleton) .png (render)")->required();
  ex.seed_opt = exp->add_option("--seed", ex.seed, "Seed (default: the preset's)");
  exp->add_option("--step", ex.step, "Export the tree as it stood at this growth step (-1: final)");
  exp->add_option("--set", ex.sets, "key=value, or key=from:to:count to sweep a number (repeatable)");
  exp->add_option("--seeds", ex.seeds, "A-B: one file per seed, OUT-A ... OUT-B");
  exp->add_option("--width", ex.width, ".png width")->check(CLI::Range(16, 8192));
  exp->add_option("--height", ex.height, ".png height")->check(CLI::Range(16, 8192));
  exp->add_flag("--instancing", ex.instancing, "glTF: leaves as EXT_mesh_gpu_instancing instead of baked quads");
  exp->add_flag("--animation", ex.animation, "glTF: the growth steps as a STEP-interpolated animation");
  exp->add_option("--seconds-per-step", ex.seconds_per_step, "glTF animation speed")->check(CLI::Range(0.001, 60.0));

  std::vector<std::string> bench_paths;
  int repeat = 5;
  bool bench_json = false, bench_export = false, bench_render = false, bench_edit = false;
  int bench_width = 1280, bench_height = 720;
  bool bench_preset_light = false;
  CLI::App* bench = app.add_subcommand("bench", "Time grow and mesh per preset (default: every bench/*.json)");
  bench->add_option("presets", bench_paths, "Preset JSON files");
  bench->add_option("--repeat", repeat, "Runs per preset; medians are reported")->check(CLI::Range(1, 1000));
  bench->add_flag("--json", bench_json, "One JSON object per line");
  bench->add_flag("--export", bench_export, "Also time GLB export and report the file size");
  bench->add_flag("--render", bench_render,
                  "Time rendering instead: frame ms per pass (needs DISPLAY; default: one preset per generator)");
  bench->add_flag("--edit", bench_edit, "Time a slider release to the new tree on screen (worker, upload, one frame)");
  bench->add_option("--width", bench_width, "--render: image width")->check(CLI::Range(16, 8192));
  bench->add_option("--height", bench_height, "--render: image height")->check(CLI::Range(16, 8192));
  bench->add_flag("--preset-light", bench_preset_light,
                  "--render: keep each preset's sun (default: backlit with shadows and god rays, every pass runs)");

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
    if (params->parsed()) return run_params(params_json);
    if (exp->parsed()) return run_export(ex);
    if (bench->parsed() && bench_edit) return run_bench_edit(bench_paths, repeat, bench_json, bench_width, bench_height);
    if (bench->parsed() && bench_render) {
      if (bench_export) return usage_error("bench", "--render and --export time different things; give one");
      return run_bench_render(bench_paths, repeat, bench_json, bench_width, bench_height, bench_preset_light);
    }
    if (bench->parsed()) return run_bench(bench_paths, repeat, bench_json, bench_export);
  } catch (const std::exception& e) {  // last resort: a library threw; still one line and exit 1
    for (CLI::App* sub : {params, exp, bench})
      if (sub->parsed()) return fail(sub->get_name(), e.what());
    std::fprintf(stderr, "sylva: %s\n", e.what());
    return 1;
  }
  return 2;
}

}  // namespace sylva
