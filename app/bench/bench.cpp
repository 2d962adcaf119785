// `sylva bench` and `sylva bench --render` (bench.h): grow, mesh, export and frame timings.
#include "app/bench/bench.h"

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include <epoxy/gl.h>

#include "app/bench/bench_set.h"
#include "app/common/messages.h"
#include "app/common/gl_window.h"
#include "generators/timing.h"
#include "render/io/export.h"
#include "render/io/preset.h"
#include "render/gl/renderer.h"
#include "render/mesh/overlay_geometry.h"

namespace sylva {

void print_bench_json(const nlohmann::ordered_json& j) {
  // A file name need not be UTF-8; its bad bytes print as U+FFFD instead of throwing.
  std::printf("%s\n", j.dump(-1, ' ', false, nlohmann::ordered_json::error_handler_t::replace).c_str());
}

namespace {

namespace fs = std::filesystem;
using json = nlohmann::ordered_json;

// ---------------------------------------------------------------------------------------------
// sylva bench

struct bench_result {  // plain bytes: sent from the measuring child through a pipe
  uint64_t nodes = 0, leaves = 0, triangles = 0, glb_bytes = 0;
  double grow_ms = 0, mesh_ms = 0, export_ms = 0, peak_rss_mb = 0;
  double grow_peak_rss_mb = 0;   // peak RSS after the first grow, before any mesh (the growth's own peak)
  mesh_stage_times stages;       // medians of each stage (--stages)
  uint64_t mesh_digest = 0;      // of the last mesh (--stages --json): the same bytes as another build's?
  int steps = 0;
  bool hit_node_cap = false, error = false;
  char message[240] = {};
};

// The stages of mesh_tree as `--stages` names them (mesh.h says what each covers).
constexpr std::pair<const char*, double mesh_stage_times::*> stage_fields[] = {
    {"frame", &mesh_stage_times::frame},        {"budget", &mesh_stage_times::budget},
    {"rings", &mesh_stage_times::rings},        {"index", &mesh_stage_times::index},
    {"leaf_place", &mesh_stage_times::leaf_place}, {"sky", &mesh_stage_times::sky},
    {"occlusion", &mesh_stage_times::occlusion}};

double process_peak_rss_mb() {
  rusage ru{};
  getrusage(RUSAGE_SELF, &ru);
  return double(ru.ru_maxrss) / 1024.0;  // Linux reports kilobytes
}

bench_result measure(const preset& p, int repeat, bool with_export) {
  bench_result r;
  std::vector<double> grow_ms, mesh_ms, export_ms;
  std::vector<mesh_stage_times> stages;
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
    m = mesh_tree(t, p.mesh, p.spec.seed, &stages.emplace_back());
    mesh_ms.push_back(ms_since(t0));
  }
  for (const auto& [name, f] : stage_fields) {
    std::vector<double> v;
    for (const mesh_stage_times& s : stages) v.push_back(s.*f);
    r.stages.*f = median(v);
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
  r.mesh_digest = mesh_digest(m);
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

int bench_one(const std::string& path, int repeat, bool as_json, bool with_export, bool stages);

int bench_presets(std::vector<std::string> paths, int repeat, bool as_json, bool with_export, bool stages) {
  const char* cmd = "bench";
  if (paths.empty()) {
    const fs::path dir = fs::path(SYLVA_SOURCE_DIR) / "bench";
    std::error_code ec;
    for (const auto& e : fs::directory_iterator(dir, ec))
      if (e.path().extension() == ".json") paths.push_back(e.path().string());
    if (ec || paths.empty()) return fail(cmd, "no presets given and none found in " + dir.string());
    std::sort(paths.begin(), paths.end());
  }
  if (!as_json) {
    std::printf("%-36s %-18s %9s %9s %10s %9s %9s %8s %8s%s", "preset", "generator", "nodes", "leaves", "triangles",
                "grow_ms", "mesh_ms", "grow_MB", "peak_MB", with_export ? "  glb_ms     glb_MB" : "");
    if (stages)   // the stage columns continue the line
      for (const auto& [name, f] : stage_fields) std::printf(" %10s", name);
    std::printf("\n");
  }
  int failures = 0;
  for (const std::string& path : paths) {
    try {   // one preset's failure is reported and the rest are still measured
      failures += bench_one(path, repeat, as_json, with_export, stages);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "sylva %s: %s: %s\n", cmd, path.c_str(), e.what());
      ++failures;
    }
    std::fflush(stdout);
  }
  if (!as_json)
    std::printf("medians over %d runs; peak_MB is each preset's own peak RSS (measured in a child process), grow_MB "
                "that peak right after the first grow, before meshing%s\n",
                repeat, stages ? "; stages: ms of each mesh_tree stage, each its own median (render/mesh/mesh.h)" : "");
  return failures ? 1 : 0;
}

// One preset of `sylva bench`: 0 when measured, 1 when it failed (reported on stderr).
int bench_one(const std::string& path, int repeat, bool as_json, bool with_export, bool stages) {
  {
    preset p;
    if (!load_bench_preset("bench", path, p)) return 1;
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
      if (stages) {
        json& st = j["stages_ms"];
        for (const auto& [stage, f] : stage_fields) st[stage] = r.stages.*f;
        char hex[17];
        std::snprintf(hex, sizeof hex, "%016llx", (unsigned long long)r.mesh_digest);
        j["mesh_digest"] = hex;
      }
      print_bench_json(j);
    } else {
      std::printf("%-36s %-18s %9llu %9llu %10llu %9.2f %9.2f %8.1f %8.1f", name.c_str(), generator_name(p.spec),
                  (unsigned long long)r.nodes, (unsigned long long)r.leaves, (unsigned long long)r.triangles,
                  r.grow_ms, r.mesh_ms, r.grow_peak_rss_mb, r.peak_rss_mb);
      if (with_export) std::printf(" %8.1f %10.2f", r.export_ms, double(r.glb_bytes) / (1024.0 * 1024.0));
      if (stages)
        for (const auto& [stage, f] : stage_fields) std::printf(" %10.2f", r.stages.*f);
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
// pass closed by glFinish (renderer_gpu::measure_passes). With `all_effects` the sun is put behind
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
  renderer_gpu r;
  gl_texture color;
  gl_framebuffer target;
  if (!init_renderer(r)) error = r.error.empty() ? "renderer initialisation failed" : r.error;
  if (error.empty()) {
    upload_tree(r, m);
    upload_wind(r, t);
    r.wind_time = 1.0f;
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
      upload_wind(r, t);
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

int bench_render_presets(std::vector<std::string> paths, int repeat, bool as_json, int width, int height,
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
    if (!load_bench_preset(cmd, path, p)) {
      ++failures;
      continue;
    }
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
      print_bench_json(j);
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

int run_bench(std::vector<std::string> paths, int repeat, bool as_json, bool with_export, bool stages) {
  return bench_presets(std::move(paths), repeat, as_json, with_export, stages);
}

int run_bench_render(std::vector<std::string> paths, int repeat, bool as_json, int width, int height,
                     bool preset_light) {
  return bench_render_presets(std::move(paths), repeat, as_json, width, height, preset_light);
}

}  // namespace sylva
