// `sylva bench --edit`: the time from a slider release to the new tree on screen.
#pragma once

#include <string>
#include <vector>

namespace sylva {

// For each preset (default: Honda's tree a and one default preset per other generator) and each
// parameter class (generators/params.h), `repeat` edits of the first float parameter of that class
// (the generator's, the mesh's, the renderer's), alternately nudged up and down by 0.1 %: each is
// posted to the growth worker as the editor posts a released slider (a render edit posts nothing,
// as in the editor), and timed until its tree is uploaded and one frame of width × height is drawn
// (glFinish). Prints the medians of the total and of its parts (worker, the worker's grow and mesh,
// upload, frame). Returns the process exit code.
int run_bench_edit(std::vector<std::string> paths, int repeat, bool as_json, int width, int height);

}  // namespace sylva
