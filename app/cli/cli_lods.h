// `sylva export --lods` and `sylva bench --lods`: the LOD chain and the impostor for
// the CLI.
#pragma once

#include <string>
#include <vector>

#include "render/io/export.h"
#include "render/io/preset.h"
#include "render/gl/impostor.h"
#include "render/mesh/lod.h"

namespace sylva {

struct lod_export_data {
  lod_chain chain;
  export_impostor impostor;
  double build_ms = 0, impostor_ms = 0;
};

// Builds the levels (and, for glTF with a display, the impostor atlas) and points o.lods and
// o.impostor into `d`. Returns the lines to warn about (clamped budgets, a tree too small to
// reduce, an impostor left out and why).
std::vector<std::string> prepare_lod_export(const tree_skeleton& t, const tree_mesh& m, const preset& p, bool gltf,
                                            export_options& o, lod_export_data& d);

// Renders the impostor atlas of `m` in a hidden GL context ("" or why not).
// With `worst_frame_ms`, also builds it again a view per frame as the editor does (impostor_build
// from LOD0's own copy, then the leaf layers) and stores the longest of those steps.
std::string make_impostor(const tree_mesh& m, const tree_skeleton& t, const preset& p, impostor_atlas& out,
                          double* worst_frame_ms = nullptr);

// `sylva bench --lods`: per preset, LOD0..3 triangles against their budgets, the median time to
// build the levels and to render the impostor atlas. 0 when every preset was measured.
// With `sheet_dir`, also writes per preset NAME_lod0.png .. NAME_lod3.png (each level framed alike,
// at the width x height given) and NAME_impostor.png (the colour atlas), for docs/LOD.md.
int run_bench_lods(std::vector<std::string> paths, int repeat, bool as_json, const std::string& sheet_dir = "",
                   int width = 480, int height = 480);

}  // namespace sylva
