// Every parameter declares what a change of it redoes (generators/params.h: regrow, re-mesh or
// render); the walk below checks each one against what it really does, and the worker's reuse.
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <map>
#include <set>
#include <string>
#include <thread>

#include "app/common/worker.h"
#include "render/io/preset.h"
#include "tests/fixtures.h"

using namespace sylva;

namespace {

// Moves a parameter to another value in its range (toward the far end; bools flip, enums take the
// next option, lists and vectors each element). False for strings, which no walk here changes.
template <class T>
bool nudge(T& v, const param_info& info) {
  auto other = [&](float x) { return x - info.min > info.max - x ? info.min + 0.25f * (x - info.min) : x + 0.5f * (info.max - x); };
  if constexpr (std::is_same_v<T, float>) {
    v = other(v);
  } else if constexpr (std::is_same_v<T, int>) {
    const int w = int(std::lround(other(float(v))));
    v = w != v ? w : (v < int(info.max) ? v + 1 : v - 1);
  } else if constexpr (std::is_same_v<T, bool>) {
    v = !v;
  } else if constexpr (std::is_enum_v<T>) {
    v = T((int(v) + 1) % std::max(option_count(info), 1));
  } else if constexpr (std::is_same_v<T, glm::vec3>) {
    for (int i = 0; i < 3; ++i) v[i] = other(v[i]);
  } else if constexpr (std::is_same_v<T, std::vector<float>>) {
    for (float& e : v) e = other(e);
    return !v.empty();
  } else {
    return false;
  }
  return true;
}

// Calls f(copy, key, class) for every parameter of `params`, where `copy` is `params` with that one
// parameter nudged; parameters that cannot be nudged are counted in `skipped`.
template <class P, class F>
void each_nudged(const P& params, F&& f, int* skipped = nullptr) {
  int count = 0;
  visit_params(params, [&](const auto&, const param_info&) { ++count; });
  for (int k = 0; k < count; ++k) {
    P copy = params;
    int at = 0;
    bool moved = false;
    std::string key;
    param_class cls = param_class::regrow;
    visit_params(copy, [&](auto& value, const param_info& info) {
      if (at++ != k) return;
      moved = nudge(value, info);
      key = info.key;
      cls = class_of(info);
    });
    if (moved && !(copy == params)) f(copy, key, cls);
    else if (skipped) ++*skipped;
  }
}

// How many of the three class flags a parameter carries, per key, for one params struct.
template <class P>
void expect_one_class(const P& params, param_class want, const char* what) {
  int n = 0;
  visit_params(params, [&](const auto&, const param_info& info) {
    const unsigned c = info.flags & (param_regrow | param_remesh | param_render);
    EXPECT_TRUE(c == param_regrow || c == param_remesh || c == param_render) << what << "." << info.key << " declares "
                                                                            << "no class or several";
    EXPECT_EQ(int(class_of(info)), int(want)) << what << "." << info.key;
    ++n;
  });
  EXPECT_GT(n, 0) << what;
}

uint64_t skeleton_digest(const tree_skeleton& t) {
  tree_mesh probe;   // the skeleton's own arrays through the mesh digest's hash
  probe.position.assign(t.position.begin(), t.position.end());
  probe.final_radius = t.radius;
  probe.node.assign(t.parent.begin(), t.parent.end());
  probe.index.assign(t.born.begin(), t.born.end());
  probe.steps = t.steps;
  return mesh_digest(probe) ^ (uint64_t(t.leaves.size()) << 32);
}

// Small presets of all four generators, with the foliage model, clusters and clumping between them.
constexpr const char* small_presets[] = {"species_sapling", "species_palm", "species_bush", "species_poplar",
                                         "species_cypress"};

}  // namespace

TEST(ParamClass, EveryParameterDeclaresExactlyOneClass) {
  for (int g = 0; g < generator_count; ++g)
    std::visit([&](const auto& p) { expect_one_class(p, param_class::regrow, generator_names[g]); }, default_params(g));
  expect_one_class(wood_params{}, param_class::regrow, "wood");
  expect_one_class(mesh_params{}, param_class::remesh, "mesh");
  expect_one_class(leaf_params{}, param_class::remesh, "mesh.leaves");
  expect_one_class(render_params{}, param_class::render, "render");
  expect_one_class(lod_params{}, param_class::render, "render.lod");
  expect_one_class(wind_params{}, param_class::render, "render.wind");
}

// A re-mesh parameter leaves the skeleton alone and changes the mesh (on at least one preset where
// the editor shows it); a render parameter changes neither the skeleton nor a byte of the mesh;
// a generator parameter is classed regrow by the worker. edit_class sees each edit as declared.
TEST(ParamClass, EachClassRedoesWhatItDeclares) {
  std::map<std::string, bool> mesh_changed;   // re-mesh key -> changed some preset's mesh
  std::set<std::string> mesh_keys;
  std::vector<std::pair<std::string, preset>> cases;
  for (const char* name : small_presets) cases.emplace_back(name, sylva_test::shipped_preset(name));
  // Settings that bring the mode-dependent sliders in: tips mode; whorls, clumps and finer rings
  // (the flare's lobes are at most half the radial segments).
  cases.emplace_back("sapling, tips", cases[0].second);
  cases.back().second.mesh.leaves.mode = leaf_mode::tips;
  cases.emplace_back("sapling, whorled and clumped", cases[0].second);
  cases.back().second.mesh.leaves.arrangement = leaf_arrangement::whorled;
  cases.back().second.mesh.leaves.clumping = 0.6f;
  cases.back().second.mesh.radial_segments = 16;
  cases.back().second.mesh.flare_strength = 0.8f;
  cases.emplace_back("sapling, needle shoots", cases[0].second);   // leaf_needle_spread shows and acts
  cases.back().second.mesh.leaves.archetype = leaf_archetype::flat_spray;
  for (const auto& [name, p] : cases) {
    SCOPED_TRACE(name);
    const tree_skeleton t = grow(p.spec, grow_options{});
    ASSERT_GT(t.size(), 1u);
    const uint64_t bark = mesh_digest(mesh_tree(t, p.mesh, p.spec.seed));

    each_nudged(p.mesh, [&](const mesh_params& m, const std::string& key, param_class cls) {
      EXPECT_EQ(int(cls), int(param_class::remesh)) << key;
      EXPECT_EQ(int(edit_class(p.spec, p.mesh, p.spec, m)), int(param_class::remesh)) << key;
      mesh_keys.insert(key);
      // Relevant: the editor shows it for these settings (a leaf slider of another leaf mode is not).
      bool shown = false;
      visit_params(m, [&](const auto& value, const param_info& info) {
        if (info.key == key) shown = param_relevant(m, &value, info);
      });
      if (!shown) return;
      const tree_mesh after = mesh_tree(t, m, p.spec.seed);
      EXPECT_EQ(validate_mesh(after), "") << key;
      mesh_changed[key] |= mesh_digest(after) != bark;
    });

    each_nudged(p.render, [&](const render_params& rp, const std::string& key, param_class cls) {
      EXPECT_EQ(int(cls), int(param_class::render)) << key;
      preset q = p;
      q.render = rp;
      // What the editor posts (spec and mesh settings) is untouched, and so is the mesh.
      EXPECT_TRUE(q.spec == p.spec && q.mesh == p.mesh) << key;
      if (&p == &cases[0].second) {   // grown and meshed again from what the worker is given, once
        EXPECT_EQ(mesh_digest(mesh_tree(grow(q.spec, grow_options{}), q.mesh, q.spec.seed)), bark) << key;
      }
    });

    int regrow_params = 0;
    std::visit([&](const auto& gp) {
      each_nudged(gp, [&](const auto& changed, const std::string& key, param_class cls) {
        EXPECT_EQ(int(cls), int(param_class::regrow)) << key;
        tree_spec s = p.spec;
        s.params = changed;
        EXPECT_EQ(int(edit_class(p.spec, p.mesh, s, p.mesh)), int(param_class::regrow)) << key;
        ++regrow_params;
      });
    }, p.spec.params);
    EXPECT_GT(regrow_params, 5);
    each_nudged(p.spec.wood, [&](const wood_params& wd, const std::string& key, param_class) {
      tree_spec s = p.spec;
      s.wood = wd;
      EXPECT_EQ(int(edit_class(p.spec, p.mesh, s, p.mesh)), int(param_class::regrow)) << key;
    });
    tree_spec reseeded = p.spec;
    reseeded.seed += 1;
    EXPECT_EQ(int(edit_class(p.spec, p.mesh, reseeded, p.mesh)), int(param_class::regrow));
    EXPECT_EQ(int(edit_class(p.spec, p.mesh, p.spec, p.mesh)), int(param_class::render));
  }
  // Re-mesh parameters that change no mesh of these presets, and why that is still their class.
  const std::set<std::string> inert = {
      "leaf_cap",   // a cap above every small preset's leaf count
      "mesh_budget",   // a budget above every small preset's mesh bound (a change re-checks it)
  };
  for (const std::string& key : mesh_keys) {
    if (inert.count(key)) continue;
    EXPECT_TRUE(mesh_changed[key]) << key << " is declared re-mesh but changed no mesh";
  }
  EXPECT_GT(mesh_keys.size(), 20u);
}

namespace {
std::shared_ptr<const grow_result> wait_for(worker_state& w, uint32_t g) {
  for (int i = 0; i < 3000; ++i) {
    if (auto x = take_result(w, 0); x && x->generation == g) return x;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return nullptr;
}
}  // namespace

// The worker honours the classes: a re-mesh edit keeps the skeleton (the same object) and meshes
// it again to the bytes a fresh mesh of it gives; an unchanged request keeps the mesh too.
TEST(ParamClass, WorkerRedoesOnlyWhatTheEditNeeds) {
  const preset p = sylva_test::shipped_preset("species_sapling");
  worker_state w;
  start_worker(w);
  w.node_budget = int64_t(1) << 40;
  auto first = wait_for(w, post_request(w, p.spec, p.mesh));
  ASSERT_TRUE(first);
  EXPECT_TRUE(first->regrown);
  EXPECT_EQ(int(first->edit), int(param_class::regrow));

  mesh_params m = p.mesh;
  m.gnarl += 2;
  auto remeshed = wait_for(w, post_request(w, p.spec, m));
  ASSERT_TRUE(remeshed);
  EXPECT_EQ(int(remeshed->edit), int(param_class::remesh));
  EXPECT_FALSE(remeshed->regrown);
  EXPECT_TRUE(remeshed->remeshed);
  EXPECT_EQ(remeshed->skeleton.get(), first->skeleton.get());
  EXPECT_EQ(mesh_digest(remeshed->mesh), mesh_digest(mesh_tree(*first->skeleton, m, p.spec.seed)));
  EXPECT_NE(mesh_digest(remeshed->mesh), mesh_digest(first->mesh));

  auto same = wait_for(w, post_request(w, p.spec, m));
  ASSERT_TRUE(same);
  EXPECT_EQ(int(same->edit), int(param_class::render));
  EXPECT_FALSE(same->regrown);
  EXPECT_FALSE(same->remeshed);
  EXPECT_EQ(same->mesh_ms, 0.0);
  EXPECT_EQ(mesh_digest(same->mesh), mesh_digest(remeshed->mesh));

  tree_spec grown = p.spec;
  grown.seed += 1;
  auto regrown = wait_for(w, post_request(w, grown, m));
  ASSERT_TRUE(regrown);
  EXPECT_EQ(int(regrown->edit), int(param_class::regrow));
  EXPECT_TRUE(regrown->regrown);
  EXPECT_NE(skeleton_digest(*regrown->skeleton), skeleton_digest(*first->skeleton));
  stop_worker(w);
}

// The status bar names the class of the last edit and what it cost.
TEST(ParamClass, StatusTextNamesTheClassAndItsTimes) {
  grow_result r;
  r.grow_ms = 12.04, r.mesh_ms = 4.06;
  EXPECT_EQ(edit_timing_text(param_class::regrow, &r, 0.94), "regrow: grow 12.0 ms, mesh 4.1 ms, upload 0.9 ms");
  r.regrown = false;
  EXPECT_EQ(edit_timing_text(param_class::remesh, &r, 0.94), "re-mesh: grow kept, mesh 4.1 ms, upload 0.9 ms");
  EXPECT_EQ(edit_timing_text(param_class::render, &r, 0.94), "render: no grow, no mesh, no upload");
  EXPECT_EQ(edit_timing_text(param_class::regrow, nullptr, 0), "regrow: no grow, no mesh, no upload");
}
