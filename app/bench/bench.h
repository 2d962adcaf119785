// `sylva bench`: grow, mesh and export timings per preset; `--render`: frame cost per pass.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace sylva {

// Medians over `repeat` runs of each preset (default: every bench/*.json), each measured in a
// forked child so that its peak RSS is its own; with `stages`, also the median of each mesh_tree
// stage (mesh_stage_times). Returns the exit code.
int run_bench(std::vector<std::string> paths, int repeat, bool as_json, bool with_export, bool stages = false);

// Steady frames of the editor's renderer, pass by pass, and the cost of taking a new tree
// (default presets: Honda's tree a and one per other generator). Needs a display.
int run_bench_render(std::vector<std::string> paths, int repeat, bool as_json, int width, int height,
                     bool preset_light);

// `--render --ab PRESET_B` (app/bench/bench_ab.cpp): each preset as slot A beside PRESET_B as slot B, the
// A/B view's frame (side by side, and split) against A's single frame, with the ratio.
int run_bench_render_ab(std::vector<std::string> paths, const std::string& b_path, int repeat, bool as_json, int width,
                        int height, bool preset_light);

// Every bench command's --json line: one object per line, bad UTF-8 replaced rather than thrown.
void print_bench_json(const nlohmann::ordered_json& j);

}  // namespace sylva
