// libFuzzer: export (glTF, GLB, OBJ, skeleton JSON; nothing written: a dry run) of one small tree
// with hostile render, LOD, wind and export settings: NaN, infinities, huge and zero values, zero
// budgets, a wind loop of 1e9 seconds. Half the inputs are clamped into the declared ranges first,
// as a preset or --set gives them; the other half reach the exporters as they are.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstdint>
#include <limits>
#include <string>

#include <fuzzer/FuzzedDataProvider.h>

#include "render/io/export.h"
#include "render/mesh/lod.h"
#include "tests/fuzz/fuzz_common.h"

using namespace sylva;

namespace {

float hostile_float(FuzzedDataProvider& in) {
  static const float table[] = {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity(),
                                -std::numeric_limits<float>::infinity(), 0.0f, -0.0f, 1e9f, -1e9f, 3.4e38f, -3.4e38f,
                                1e-45f, 1e-30f, 1.0f, 0.5f, -1.0f, 100.0f, 4096.0f};
  const uint8_t pick = in.ConsumeIntegral<uint8_t>();
  if (pick < 128) return table[pick % std::size(table)];
  return in.ConsumeFloatingPoint<float>();
}

int hostile_int(FuzzedDataProvider& in) {
  static const int table[] = {0, -1, 1, 2, 3, 4, 8, 16, 64, 1 << 20, std::numeric_limits<int>::max(),
                              std::numeric_limits<int>::min()};
  const uint8_t pick = in.ConsumeIntegral<uint8_t>();
  if (pick < 128) return table[pick % std::size(table)];
  return in.ConsumeIntegral<int>();
}

struct small_tree {
  preset p;
  tree_skeleton t;
  tree_mesh m;
};

const small_tree& tree() {
  static const small_tree s = [] {
    small_tree s;
    s.p = default_preset();
    make_growth_small(s.p);
    s.t = grow(s.p.spec, grow_options{});
    s.m = mesh_tree(s.t, s.p.mesh, s.p.spec.seed);
    return s;
  }();
  return s;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size > 4096) return 0;
  FuzzedDataProvider in(data, size);
  const small_tree& s = tree();
  const bool clamped = in.ConsumeBool();
  render_params rp = s.p.render;
  visit_params(rp, [&](auto& value, const param_info& info) {
    using T = std::decay_t<decltype(value)>;
    if constexpr (std::is_same_v<T, float>) value = hostile_float(in);
    else if constexpr (std::is_same_v<T, int>) value = hostile_int(in);
    else if constexpr (std::is_same_v<T, bool>) value = in.ConsumeBool();
    else if constexpr (std::is_enum_v<T>) value = T(in.ConsumeIntegralInRange<int>(-2, 40));
    else if constexpr (std::is_same_v<T, glm::vec3>) value = {hostile_float(in), hostile_float(in), hostile_float(in)};
    else if constexpr (std::is_same_v<T, std::string>) value.clear();   // no user texture files here
    if (clamped) clamp_param(value, info);
  });
  // Kept small so that one input stays cheap (its cost is PNG encoding, which grows with size).
  rp.lod.impostor_size = std::min(rp.lod.impostor_size, 64);

  export_options o;
  o.dry_run = true;
  o.mesh = s.p.mesh;
  apply_render_params(o, rp);
  o.texture_size = std::min(hostile_int(in), 32);
  o.texture_seed = in.ConsumeIntegral<uint64_t>();
  o.step = in.ConsumeIntegralInRange<int>(-3, s.t.steps + 3);
  o.gltf_instancing = in.ConsumeBool();
  o.growth_animation = in.ConsumeBool();
  o.seconds_per_step = hostile_float(in);
  o.max_animation_steps = std::min(hostile_int(in), 8);
  o.wind_seconds = hostile_float(in);
  if (!clamped) {
    o.alpha_cutoff = hostile_float(in);
    o.leaf_normal_blend = hostile_float(in);
    o.bark_color = {hostile_float(in), hostile_float(in), hostile_float(in)};
    o.leaf_color = {hostile_float(in), hostile_float(in), hostile_float(in)};
  }
  lod_chain chain;
  if (in.ConsumeBool() && !o.growth_animation && o.step < 0) {   // as --lods: the final tree only
    chain = build_lods(s.t, s.m, s.p.mesh, rp.lod);
    o.lod0_coverage = chain.coverage[0];
    for (int k = 1; k < lod_levels; ++k)
      o.lods.push_back({&chain.level[size_t(k) - 1], chain.coverage[size_t(k)], chain.target[size_t(k)]});
    for (const tree_mesh& level : chain.level) fuzz_check(validate_mesh(level).empty(), "every LOD mesh is valid");
  }
  static const char* const formats[] = {"/nonexistent-sylva-fuzz/t.glb", "/nonexistent-sylva-fuzz/t.gltf",
                                        "/nonexistent-sylva-fuzz/t.obj", "/nonexistent-sylva-fuzz/t.json"};
  const export_result r = export_tree(s.t, s.m, export_info{"lsystem", 1}, formats[in.ConsumeIntegralInRange(0, 3)], o);
  if (std::getenv("SYLVA_FUZZ_VERBOSE")) std::fprintf(stderr, "error: %s\nwarning: %s\n", r.error.c_str(), r.warning.c_str());
  fuzz_check(r.files.empty(), "a dry run writes nothing");
  if (r.error.empty()) fuzz_check(r.bytes > 0, "a successful export has a size");
  return 0;
}
