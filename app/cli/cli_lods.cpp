// `sylva export --lods` and `sylva bench --lods`.
#include "app/cli/cli_lods.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <filesystem>

#include "app/bench/bench.h"
#include "app/bench/bench_set.h"
#include "app/common/gl_window.h"
#include "generators/timing.h"
#include "generators/tree_spec.h"
#include "render/gl/renderer.h"

namespace sylva {

std::string make_impostor(const tree_mesh& m, const tree_skeleton& t, const preset& p, impostor_atlas& out,
                          double* worst_frame_ms) {
  if (std::string why = display_missing("the impostor atlas"); !why.empty()) return why;
  hidden_gl_context ctx;
  if (std::string why = open_hidden_gl_context(ctx, "sylva impostor", false); !why.empty()) return why;
  renderer_gpu r;
  std::string error;
  if (!init_renderer(r)) {
    error = r.error;
  } else {
    upload_tree(r, m);
    set_tree_step(r, t, p.mesh.min_radius, t.steps);
    out = render_impostor(r, p.render, p.render.lod.impostor_views, p.render.lod.impostor_size);
    error = out.error;
    if (error.empty() && worst_frame_ms) {
      // The editor's way (app/editor/editor_lod.cpp): begin, one view per step, the read-back, then the layers.
      impostor_build b;
      error = impostor_begin(b, r, p.render, p.render.lod.impostor_views, p.render.lod.impostor_size, &m);
      if (error.empty())
        while (!impostor_step(b, r)) {
        }
      if (error.empty()) error = b.atlas.error;
      const auto t0 = std::chrono::steady_clock::now();
      if (error.empty()) impostor_layers(b.atlas);
      *worst_frame_ms = std::max(b.worst_step_ms, ms_since(t0));
      impostor_cancel(b);
    }
  }
  destroy_renderer(r);
  close_hidden_gl_context(ctx);
  return error;
}

std::vector<std::string> prepare_lod_export(const tree_skeleton& t, const tree_mesh& m, const preset& p, bool gltf,
                                            export_options& o, lod_export_data& d) {
  std::vector<std::string> warnings;
  const auto t0 = std::chrono::steady_clock::now();
  d.chain = build_lods(t, m, p.mesh, p.render.lod);
  d.build_ms = ms_since(t0);
  if (!d.chain.message.empty()) warnings.push_back(d.chain.message);
  o.lods.clear();
  o.lod0_coverage = d.chain.coverage[0];
  for (int k = 1; k < lod_levels; ++k)
    o.lods.push_back({&d.chain.level[size_t(k) - 1], d.chain.coverage[size_t(k)], d.chain.target[size_t(k)]});
  if (!gltf) return warnings;
  const auto t1 = std::chrono::steady_clock::now();
  impostor_atlas atlas;
  std::string why = make_impostor(m, t, p, atlas);
  if (why.empty()) why = impostor_pngs(atlas, d.impostor.color_png, d.impostor.normal_png);
  d.impostor_ms = ms_since(t1);
  if (!why.empty()) {
    warnings.push_back("impostor left out: " + why);
    return warnings;
  }
  d.impostor.views = atlas.views;
  d.impostor.columns = atlas.columns;
  d.impostor.rows = atlas.rows;
  d.impostor.width = d.impostor.height = atlas.cell_metres;
  d.impostor.centre = atlas.centre;
  d.impostor.coverage = d.chain.impostor_coverage;
  o.impostor = &d.impostor;
  return warnings;
}

// The levels rendered alike (same camera, framed on LOD0) and the atlas, as PNGs in `dir`.
std::string write_sheet(const std::string& dir, const std::string& name, const tree_skeleton& t, const tree_mesh& m,
                        const lod_chain& c, const preset& p, int width, int height) {
  if (std::string why = display_missing("--sheet"); !why.empty()) return why;
  hidden_gl_context ctx;
  if (std::string why = open_hidden_gl_context(ctx, "sylva lod sheet", false); !why.empty()) return why;
  renderer_gpu r;
  std::string error;
  if (!init_renderer(r)) error = r.error;
  orbit_camera cam;
  frame_camera(cam, m.bounds_min, m.bounds_max, float(width) / float(height));
  for (int k = 0; k < lod_levels && error.empty(); ++k) {
    upload_tree(r, k == 0 ? m : c.level[size_t(k) - 1]);
    set_tree_step(r, t, p.mesh.min_radius, t.steps);
    error = save_view_png(r, p.render, cam, width, height, dir + "/" + name + "_lod" + std::to_string(k) + ".png");
  }
  if (error.empty()) {
    upload_tree(r, m);
    set_tree_step(r, t, p.mesh.min_radius, t.steps);
    const impostor_atlas a = render_impostor(r, p.render, p.render.lod.impostor_views, p.render.lod.impostor_size);
    error = a.error;
    if (error.empty()) error = save_png(image{a.width, a.height, 4, a.color}, dir + "/" + name + "_impostor.png");
    if (error.empty()) error = save_png(image{a.width, a.height, 4, a.normal}, dir + "/" + name + "_impostor_normal.png");
  }
  destroy_renderer(r);
  close_hidden_gl_context(ctx);
  return error;
}

int run_bench_lods(std::vector<std::string> paths, int repeat, bool as_json, const std::string& sheet_dir, int width,
                   int height) {
  namespace fs = std::filesystem;
  if (paths.empty()) {   // every species preset
    std::error_code ec;
    for (const auto& e : fs::directory_iterator(fs::path(SYLVA_SOURCE_DIR) / "presets", ec))
      if (e.path().filename().string().rfind("species_", 0) == 0 && e.path().extension() == ".json")
        paths.push_back(e.path().string());
    std::sort(paths.begin(), paths.end());
    if (paths.empty()) {
      std::fprintf(stderr, "sylva bench --lods: no species presets found\n");
      return 1;
    }
  }
  if (!as_json)
    std::printf("%-28s %8s %17s %17s %17s %9s %9s %9s %11s %9s\n", "preset", "LOD0", "LOD1/budget", "LOD2/budget",
                "LOD3/budget", "nodes", "lods_ms", "lods_cpu", "impostor_ms", "frame_ms");
  int failures = 0;
  for (const std::string& path : paths) {
    preset p;
    if (!load_bench_preset("bench --lods", path, p)) {
      ++failures;
      continue;
    }
    grow_report report;
    const tree_skeleton t = grow(p.spec, grow_options{}, &report);
    if (report.error) {
      std::fprintf(stderr, "sylva bench --lods: %s: growth failed: %s\n", path.c_str(), report.message.c_str());
      ++failures;
      continue;
    }
    const tree_mesh m = mesh_tree(t, p.mesh, p.spec.seed);
    std::vector<double> build, build_cpu, atlas_ms, frame_ms;
    lod_chain c;
    for (int k = 0; k < repeat; ++k) {
      // Wall time, and this process's CPU time (what the build costs on a core not shared).
      const auto t0 = std::chrono::steady_clock::now();
      const std::clock_t c0 = std::clock();
      c = build_lods(t, m, p.mesh, p.render.lod);
      build_cpu.push_back(1000.0 * double(std::clock() - c0) / CLOCKS_PER_SEC);
      build.push_back(ms_since(t0));
    }
    std::string impostor_error;
    for (int k = 0; k < repeat && impostor_error.empty(); ++k) {
      impostor_atlas a;
      double worst = 0;
      impostor_error = make_impostor(m, t, p, a, &worst);
      if (impostor_error.empty()) atlas_ms.push_back(a.ms), frame_ms.push_back(worst);
    }
    const std::string name = fs::path(path).stem().string();
    if (!sheet_dir.empty())
      if (std::string e = write_sheet(sheet_dir, name, t, m, c, p, width, height); !e.empty()) {
        std::fprintf(stderr, "sylva bench --lods: %s: sheet: %s\n", path.c_str(), e.c_str());
        ++failures;
      }
    if (as_json) {
      print_bench_json({{"preset", name},
                        {"nodes", t.size()},
                        {"triangles", {c.triangles[0], c.triangles[1], c.triangles[2], c.triangles[3]}},
                        {"budget", {c.target[0], c.target[1], c.target[2], c.target[3]}},
                        {"lods_ms", median(build)},
                        {"lods_cpu_ms", median(build_cpu)},
                        {"impostor_ms", median(atlas_ms)},
                        {"impostor_frame_ms", median(frame_ms)},
                        {"impostor_views", p.render.lod.impostor_views > 12 ? 16 : 8},
                        {"impostor_size", p.render.lod.impostor_size},
                        {"message", impostor_error}});
    } else {
      char cell[3][40];
      for (int k = 1; k < lod_levels; ++k)
        std::snprintf(cell[k - 1], sizeof cell[0], "%zu/%zu", c.triangles[size_t(k)], c.target[size_t(k)]);
      std::printf("%-28s %8zu %17s %17s %17s %9zu %9.2f %9.2f %11.1f %9.1f\n", name.c_str(), c.triangles[0], cell[0], cell[1],
                  cell[2], t.size(), median(build), median(build_cpu), median(atlas_ms), median(frame_ms));
      if (!impostor_error.empty()) std::printf("  impostor: %s\n", impostor_error.c_str());
      if (!c.message.empty()) std::printf("  %s\n", c.message.c_str());
    }
    std::fflush(stdout);
  }
  if (!as_json)
    std::printf("medians over %d runs; LODn/budget in triangles (budgets: the preset's lod1_budget..lod3_budget, %% of "
                "LOD0); impostor_ms: the preset's impostor_views x impostor_size atlas rendered and read back in one go; "
                "frame_ms: the longest frame of the editor's spread build (one view, the read-back or the layers)\n",
                repeat);
  return failures ? 1 : 0;
}

}  // namespace sylva
