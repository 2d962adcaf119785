// `sylva bench --edit`: the time from a slider release to the new tree on screen (issue 14).
#pragma once

#include <string>
#include <vector>

namespace sylva {

// For each preset (default: Honda's tree a and one default preset per other generator), `repeat`
// edits of the generator's first float parameter, alternately nudged up and down by 0.1 %: each
// is posted to the growth worker as the editor posts a released slider, and timed until its tree
// is uploaded and one frame of width × height is drawn (glFinish). Prints the medians of the
// total and of its parts (worker, upload, frame). Returns the process exit code.
int run_bench_edit(std::vector<std::string> paths, int repeat, bool as_json, int width, int height);

}  // namespace sylva
