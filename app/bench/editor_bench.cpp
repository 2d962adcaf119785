// `sylva bench --edit`: slider release to the new tree on screen (editor_bench.h).
#include "app/bench/editor_bench.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <thread>

#include <epoxy/gl.h>

#include "app/bench/bench.h"
#include "app/bench/bench_set.h"
#include "app/common/gl_window.h"
#include "generators/timing.h"
#include "app/common/worker.h"
#include "render/io/preset.h"
#include "render/gl/renderer.h"

namespace sylva {

namespace {

namespace fs = std::filesystem;

// The first float parameter of `params` declaring class `c`, as a pointer into it (nullptr if none).
template <class P>
float* first_float(P& params, param_class c) {
  float* out = nullptr;
  visit_params(params, [&](auto& value, const param_info& info) {
    if constexpr (std::is_same_v<std::remove_cvref_t<decltype(value)>, float>)
      if (!out && class_of(info) == c) out = &value;
  });
  return out;
}

struct edit_result {
  double total = 0, worker = 0, upload = 0, frame = 0, grow = 0, mesh = 0;
  size_t nodes = 0;
  const char* knob = "";
  std::string error;
};

// Edits of the first float parameter of class `c`: the generator's (regrow), the mesh's (re-mesh)
// or the renderer's (render: as in the editor, nothing is posted to the worker; the frame is drawn
// with the new settings).
edit_result measure(const preset& p, param_class c, int repeat, int width, int height) {
  edit_result out;
  hidden_gl_context context;
  if (std::string why = open_hidden_gl_context(context, "sylva bench --edit", false); !why.empty()) {
    out.error = why;
    return out;
  }
  renderer_gpu r;
  worker_state w;
  if (!init_renderer(r)) out.error = r.error.empty() ? "renderer initialisation failed" : r.error;
  start_worker(w);
  w.node_budget = int64_t(1) << 40;   // time the growth, never the question
  gl_texture color;
  gl_framebuffer target;
  if (out.error.empty()) out.error = create_color_target(width, height, color, target);
  std::vector<double> total, worker, upload, frame, grow, meshing;
  tree_spec spec = p.spec;
  mesh_params mesh = p.mesh;
  render_params render = p.render;
  float* knob = c == param_class::regrow ? std::visit([&](auto& gp) { return first_float(gp, c); }, spec.params)
                : c == param_class::remesh ? first_float(mesh, c)
                                           : first_float(render, c);
  auto name_of = [&](auto& params) {
    visit_params(params, [&](auto& value, const param_info& info) {
      if (static_cast<const void*>(&value) == knob) out.knob = info.key;
    });
  };
  std::visit(name_of, spec.params);
  name_of(mesh);
  name_of(render);
  const float base = knob ? *knob : 0;
  orbit_camera cam;
  uint32_t seen = 0;
  for (int i = 0; i <= repeat && out.error.empty(); ++i) {   // i == 0: the first tree, a warm-up
    if (knob && i > 0) *knob = base * (i % 2 ? 1.001f : 0.999f) + (base == 0 ? 1e-4f : 0);
    const auto t0 = clock_type::now();
    auto t1 = t0, t2 = t0;
    if (c != param_class::render || i == 0) {   // a render edit posts nothing: the tree on screen stays
      const uint32_t g = post_request(w, spec, mesh);
      std::shared_ptr<const grow_result> res;
      while (!(res = take_result(w, seen)) || res->generation != g) std::this_thread::sleep_for(std::chrono::microseconds(200));
      seen = res->generation;
      t1 = clock_type::now();
      upload_tree(r, res->mesh);
      set_tree_step(r, *res->skeleton, res->mesh_settings.min_radius, res->skeleton->steps);
      glFinish();
      t2 = clock_type::now();
      out.nodes = res->skeleton->size();
      if (res->report.error) out.error = "growth failed: " + res->report.message;
      if (i > 0) {
        grow.push_back(res->regrown ? res->grow_ms : 0.0);
        meshing.push_back(res->mesh_ms);
      }
    } else {
      grow.push_back(0);
      meshing.push_back(0);
    }
    if (i == 0) frame_camera(cam, r.bounds_min, r.bounds_max);
    draw_frame(r, render, cam, width, height, target);
    glFinish();
    const auto t3 = clock_type::now();
    if (i == 0) continue;
    total.push_back(ms_between(t0, t3));
    worker.push_back(ms_between(t0, t1));
    upload.push_back(ms_between(t1, t2));
    frame.push_back(ms_between(t2, t3));
  }
  stop_worker(w);
  delete_gl(target);
  delete_gl(color);
  destroy_renderer(r);
  close_hidden_gl_context(context);
  out.total = median(total), out.worker = median(worker), out.upload = median(upload), out.frame = median(frame);
  out.grow = median(grow), out.mesh = median(meshing);
  return out;
}

}  // namespace

int run_bench_edit(std::vector<std::string> paths, int repeat, bool as_json, int width, int height) {
  if (std::string why = display_missing("bench --edit"); !why.empty()) {
    std::fprintf(stderr, "sylva bench --edit: %s\n", why.c_str());
    return 1;
  }
  if (paths.empty())
    for (const char* name : {"lsystem_honda_a", "self_organizing_default", "space_colonization_seed_cube",
                             "guiding_vectors_default"})
      paths.push_back((fs::path(SYLVA_SOURCE_DIR) / "presets" / (std::string(name) + ".json")).string());
  if (!as_json)
    std::printf("%-34s %-8s %-18s %9s %10s %10s %10s %10s %10s %10s\n", "preset", "class", "parameter", "nodes", "edit_ms",
                "worker_ms", "grow_ms", "mesh_ms", "upload_ms", "frame_ms");
  int failures = 0;
  for (const std::string& path : paths) {
    preset p;
    if (!load_bench_preset("bench --edit", path, p)) {
      ++failures;
      continue;
    }
    const std::string name = fs::path(path).stem().string();
    for (param_class c : {param_class::regrow, param_class::remesh, param_class::render}) {
      const edit_result r = measure(p, c, repeat, width, height);
      if (!r.error.empty()) {
        std::fprintf(stderr, "sylva bench --edit: %s: %s\n", path.c_str(), r.error.c_str());
        ++failures;
        break;
      }
      const char* cls = param_class_names[int(c)];
      if (as_json)
        print_bench_json({{"preset", name}, {"class", cls}, {"parameter", r.knob}, {"nodes", r.nodes}, {"edit_ms", r.total},
                          {"worker_ms", r.worker}, {"grow_ms", r.grow}, {"mesh_ms", r.mesh}, {"upload_ms", r.upload},
                          {"frame_ms", r.frame}});
      else
        std::printf("%-34s %-8s %-18s %9zu %10.1f %10.1f %10.1f %10.1f %10.1f %10.1f\n", name.c_str(), cls, r.knob, r.nodes,
                    r.total, r.worker, r.grow, r.mesh, r.upload, r.frame);
      std::fflush(stdout);
    }
  }
  return failures ? 1 : 0;
}

}  // namespace sylva
