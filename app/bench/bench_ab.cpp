// `sylva bench --render --ab PRESET_B` (bench.h): the A/B view's frame against a single tree's.
//
// Issue 18's goal: "A/B doubles the GPU work at most". The editor draws two slots side by side (each
// tree into one half of the view, with the same camera and the selected slot's sun) or as a split
// view (both trees over the whole view, with two blits for the divider; app/editor/editor_ab.cpp). Here the
// same draws are timed off screen, frame by frame closed by glFinish, interleaved with single frames
// of A and of B at the full size so that a change in the machine's load touches all of them alike.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <epoxy/gl.h>
#include <glm/common.hpp>

#include "app/bench/bench.h"
#include "app/bench/bench_set.h"
#include "app/common/messages.h"
#include "app/common/gl_window.h"
#include "generators/timing.h"
#include "render/gl/renderer.h"
#include "render/mesh/mesh.h"
#include "render/io/preset.h"

namespace sylva {

namespace {

namespace fs = std::filesystem;

struct grown_tree {
  tree_skeleton t;
  tree_mesh m;
};

std::string grow_preset(const preset& p, grown_tree& out) {
  grow_report report;
  out.t = grow(p.spec, grow_options{}, &report, nullptr);
  if (report.error) return "growth failed: " + report.message;
  out.m = mesh_tree(out.t, p.mesh, p.spec.seed);
  return "";
}

struct ab_bench_result {
  size_t nodes_a = 0, nodes_b = 0, triangles_a = 0, triangles_b = 0;
  double single_a_ms = 0, single_b_ms = 0, side_ms = 0, split_ms = 0;
};

// One pair: A alone over the whole view, B alone, both side by side (two half-width frames), and
// the split view (two full frames and two blits of A's part).
std::string measure_ab(const preset& pa, const preset& pb, int repeat, int width, int height, bool all_effects,
                       ab_bench_result& out) {
  grown_tree a, b;
  if (std::string e = grow_preset(pa, a); !e.empty()) return "A: " + e;
  if (std::string e = grow_preset(pb, b); !e.empty()) return "B: " + e;
  out.nodes_a = a.t.size();
  out.nodes_b = b.t.size();

  hidden_gl_context context;
  if (std::string why = open_hidden_gl_context(context, "sylva bench", false); !why.empty()) return why;
  std::string error;
  renderer_gpu ra, rb;
  gl_texture color, keep_color;
  gl_framebuffer target, keep;
  if (!init_renderer(ra) || !init_renderer(rb, ra.shared))   // one context: one set of programs
    error = "renderer initialisation failed: " + ra.error + rb.error;
  if (error.empty()) error = create_color_target(width, height, color, target);
  if (error.empty()) error = create_color_target(width, height, keep_color, keep);
  if (error.empty()) {
    const struct { renderer_gpu& r; const grown_tree& g; const preset& p; } slots[2] = {{ra, a, pa}, {rb, b, pb}};
    for (const auto& s : slots) {
      upload_tree(s.r, s.g.m);
      upload_wind(s.r, s.g.t);
      s.r.wind_time = 1.0f;
      set_tree_step(s.r, s.g.t, s.p.mesh.min_radius, s.g.t.steps);
    }
    // The single view frames its tree; A/B frames both trees' box for a half (as the editor's F).
    orbit_camera cam_a, cam_b, cam_ab;
    frame_camera(cam_a, ra.bounds_min, ra.bounds_max, float(width) / float(height));
    frame_camera(cam_b, rb.bounds_min, rb.bounds_max, float(width) / float(height));
    frame_camera(cam_ab, glm::min(ra.bounds_min, rb.bounds_min), glm::max(ra.bounds_max, rb.bounds_max),
                 float(width / 2) / float(height));
    // Both slots are lit by A's sun, as the editor lights both by the selected slot's.
    render_params rpa = pa.render, rpb = pb.render;
    if (all_effects) {
      place_sun_behind(rpa, cam_a.yaw);
      rpa.shadows = rpb.shadows = true;
    }
    rpb.sun_azimuth = rpa.sun_azimuth;
    rpb.sun_elevation = rpa.sun_elevation;
    const int errors_before = gl_error_count();
    std::vector<double> single_a, single_b, side, split;
    const int hw = std::max(1, width / 2), cut = width / 2;
    for (int i = 0; i <= repeat; ++i) {   // frame 0 of each kind warms up
      auto t0 = clock_type::now();
      draw_frame(ra, rpa, cam_a, width, height, target);
      glFinish();
      if (i > 0) single_a.push_back(ms_since(t0));
      t0 = clock_type::now();
      draw_frame(rb, rpb, cam_b, width, height, target);
      glFinish();
      if (i > 0) single_b.push_back(ms_since(t0));
      t0 = clock_type::now();
      draw_frame(ra, rpa, cam_ab, hw, height, target, nullptr, {0, 0});
      draw_frame(rb, rpb, cam_ab, width - hw, height, target, nullptr, {hw, 0});
      glFinish();
      if (i > 0) side.push_back(ms_since(t0));
      t0 = clock_type::now();
      draw_frame(ra, rpa, cam_a, width, height, target);
      glBindFramebuffer(GL_READ_FRAMEBUFFER, target.id);
      glBindFramebuffer(GL_DRAW_FRAMEBUFFER, keep.id);
      glBlitFramebuffer(0, 0, cut, height, 0, 0, cut, height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
      draw_frame(rb, rpb, cam_a, width, height, target);
      glBindFramebuffer(GL_READ_FRAMEBUFFER, keep.id);
      glBindFramebuffer(GL_DRAW_FRAMEBUFFER, target.id);
      glBlitFramebuffer(0, 0, cut, height, 0, 0, cut, height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
      glBindFramebuffer(GL_FRAMEBUFFER, 0);
      glFinish();
      if (i > 0) split.push_back(ms_since(t0));
    }
    check_gl("bench A/B frames");
    if (gl_error_count() > errors_before)
      error = std::to_string(gl_error_count() - errors_before) + " GL error(s): " + gl_last_message();
    out.single_a_ms = median(single_a);
    out.single_b_ms = median(single_b);
    out.side_ms = median(side);
    out.split_ms = median(split);
    draw_frame(ra, rpa, cam_a, width, height, target);
    out.triangles_a = ra.triangles_drawn + 2 * ra.leaves_drawn;
    draw_frame(rb, rpb, cam_b, width, height, target);
    out.triangles_b = rb.triangles_drawn + 2 * rb.leaves_drawn;
  }
  delete_gl(keep);
  delete_gl(keep_color);
  delete_gl(target);
  delete_gl(color);
  destroy_renderer(ra);
  destroy_renderer(rb);
  close_hidden_gl_context(context);
  return error;
}

}  // namespace

int run_bench_render_ab(std::vector<std::string> paths, const std::string& b_path, int repeat, bool as_json, int width,
                        int height, bool preset_light) {
  const char* cmd = "bench --render --ab";
  if (std::string why = display_missing("rendering"); !why.empty()) return fail(cmd, why);
  if (paths.empty()) paths.push_back((fs::path(SYLVA_SOURCE_DIR) / "presets" / "self_organizing_default.json").string());
  preset pb;
  if (!load_bench_preset(cmd, b_path, pb)) return 1;   // --set applies to both slots
  if (!as_json)
    std::printf("%-28s %-28s %9s %9s %9s %9s %9s %9s %7s %7s %7s %7s\n", "preset A", "preset B", "tris_A", "tris_B", "A_ms",
                "B_ms", "side_ms", "split_ms", "side/A", "split/A", "side/mx", "split/mx");
  int failures = 0;
  for (const std::string& path : paths) {
    preset pa;
    if (!load_bench_preset(cmd, path, pa)) {
      ++failures;
      continue;
    }
    ab_bench_result r;
    if (std::string e = measure_ab(pa, pb, repeat, width, height, !preset_light, r); !e.empty()) {
      std::fprintf(stderr, "sylva %s: %s: %s\n", cmd, path.c_str(), e.c_str());
      ++failures;
      continue;
    }
    const std::string na = fs::path(path).stem().string(), nb = fs::path(b_path).stem().string();
    // "Doubles the GPU work at most": against A alone, and against the heavier of the two single
    // frames (a B heavier than A costs more however it is drawn).
    const double side_ratio = r.side_ms / std::max(r.single_a_ms, 1e-9), split_ratio = r.split_ms / std::max(r.single_a_ms, 1e-9);
    const double heavier = std::max({r.single_a_ms, r.single_b_ms, 1e-9});
    if (as_json) {
      nlohmann::ordered_json j;
      j["preset"] = na;
      j["preset_b"] = nb;
      j["width"] = width;
      j["height"] = height;
      j["light"] = preset_light ? "preset" : "backlit";
      j["nodes_a"] = r.nodes_a;
      j["nodes_b"] = r.nodes_b;
      j["triangles_a"] = r.triangles_a;
      j["triangles_b"] = r.triangles_b;
      j["single_a_ms"] = r.single_a_ms;
      j["single_b_ms"] = r.single_b_ms;
      j["side_by_side_ms"] = r.side_ms;
      j["split_ms"] = r.split_ms;
      j["side_by_side_ratio"] = side_ratio;
      j["split_ratio"] = split_ratio;
      j["side_by_side_ratio_heavier"] = r.side_ms / heavier;
      j["split_ratio_heavier"] = r.split_ms / heavier;
      j["repeat"] = repeat;
      print_bench_json(j);
    } else {
      std::printf("%-28s %-28s %9zu %9zu %9.2f %9.2f %9.2f %9.2f %7.2f %7.2f %7.2f %7.2f\n", na.c_str(), nb.c_str(),
                  r.triangles_a, r.triangles_b, r.single_a_ms, r.single_b_ms, r.side_ms, r.split_ms, side_ratio, split_ratio,
                  r.side_ms / heavier, r.split_ms / heavier);
    }
    std::fflush(stdout);
  }
  if (!as_json)
    std::printf("%dx%d, medians over %d frames of each kind after one warm-up, interleaved; each frame ends in glFinish; "
                "A_ms/B_ms: one tree over the whole view; side: A and B in half-width views (the editor's side by side); "
                "split: both over the whole view plus two blits; ratios to A_ms and to the heavier of A_ms, B_ms (mx) "
                "(goal: at most 2); %s\n",
                width, height, repeat, preset_light ? "the presets' own light" : "A's sun behind the tree, shadows on");
  return failures ? 1 : 0;
}

}  // namespace sylva
