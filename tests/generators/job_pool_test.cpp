// The shared job pool (generators/job_pool.h) and the mesher on it: every job runs once, errors
// come back to the caller, nested calls end, and the parallel mesh and self-organizing growth are
// the single thread's, byte for byte.
#include <gtest/gtest.h>

#include <atomic>
#include <cstring>
#include <stdexcept>
#include <string>
#include <variant>
#include <vector>

#include "generators/job_pool.h"
#include "generators/self_organizing.h"
#include "render/mesh/mesh.h"
#include "generators/guiding_vectors.h"
#include "generators/wood.h"
#include "render/io/preset.h"

using namespace sylva;

TEST(JobPool, RunsEveryJobOnceAndRethrows) {
  EXPECT_GE(job_pool_helpers(), 1);
  std::vector<std::atomic<int>> hits(10007);
  parallel_jobs(hits.size(), [&](size_t k) { hits[k].fetch_add(1); });
  for (size_t k = 0; k < hits.size(); ++k) ASSERT_EQ(hits[k].load(), 1) << k;

  std::atomic<size_t> sum{0};
  parallel_chunks(1000, 7, [&](size_t b, size_t e) {   // nested: the inner calls must end too
    parallel_jobs(e - b, [&](size_t k) { sum += b + k; });
  });
  EXPECT_EQ(sum.load(), 999u * 1000u / 2);

  EXPECT_THROW(parallel_jobs(64, [](size_t k) { if (k == 40) throw std::runtime_error("job 40"); }), std::runtime_error);
  std::atomic<int> after{0};
  parallel_jobs(64, [&](size_t) { ++after; });   // the pool still works after a failed batch
  EXPECT_EQ(after.load(), 64);
}

// Presets whose meshes run every parallel stage: the foliage model (shoots, tips, clumps,
// clusters), the generator's own leaves, a leaf cap, flare, collars, caps and the crown occlusion.
TEST(JobPool, ParallelMeshIsTheSingleThreadedMeshByteForByte) {
  int checked = 0;
  for (const char* name : {"species_oak", "species_maple_cards", "species_palm", "species_willow",
                           "self_organizing_default", "lsystem_honda_f", "species_sapling"}) {
    SCOPED_TRACE(name);
    preset p;
    ASSERT_TRUE(load_preset_file(std::string(SYLVA_SOURCE_DIR) + "/presets/" + name + ".json", p).ok);
    const tree_skeleton t = grow(p.spec, grow_options{});
    std::vector<mesh_params> variants{p.mesh};
    mesh_params capped = p.mesh;
    capped.leaves.cap = 1000;   // stops placement part way through a chunk
    variants.push_back(capped);
    mesh_params tips = p.mesh;
    tips.leaves.mode = leaf_mode::tips;
    variants.push_back(tips);
    for (const mesh_params& m : variants) {
      const int old = set_job_pool_limit(1);
      const tree_mesh one = mesh_tree(t, m, p.spec.seed);
      set_job_pool_limit(old);
      const tree_mesh many = mesh_tree(t, m, p.spec.seed);
      ASSERT_GT(one.position.size(), 0u);
      EXPECT_EQ(one.position, many.position);
      EXPECT_EQ(one.occlusion, many.occlusion);
      EXPECT_EQ(one.index, many.index);
      EXPECT_EQ(one.leaves.size(), many.leaves.size());
      EXPECT_EQ(mesh_digest(one), mesh_digest(many));
      ++checked;
    }
  }
  EXPECT_EQ(checked, 21);
}

// The self-organizing growth scans its buds' cones and adds its shadow pyramids on the pool: the
// tree is the single thread's, bit for bit, with ties in the cones (seed 000's planar rule draws
// from the same stream) and with shedding (pyramids taken away).
namespace {
// A shipped preset grown with the pool limited to one thread and with all of it: the same tree.
// `whole`: without the self-pruning pass, which runs on the finished growth (generators/history.h).
void expect_growth_is_the_single_threaded_one(const char* name, size_t min_nodes, bool whole = false) {
  SCOPED_TRACE(name);
  preset p;
  ASSERT_TRUE(load_preset_file(std::string(SYLVA_SOURCE_DIR) + "/presets/" + name + ".json", p).ok);
  if (auto* so = std::get_if<self_organizing_params>(&p.spec.params); so && whole) so->live_crown = 1;
  const int old = set_job_pool_limit(1);
  const tree_skeleton one = grow(p.spec, grow_options{});
  set_job_pool_limit(old);
  const tree_skeleton many = grow(p.spec, grow_options{});
  ASSERT_GT(one.size(), min_nodes);
  EXPECT_EQ(one.parent, many.parent);
  EXPECT_EQ(one.position, many.position);
  EXPECT_EQ(one.radius, many.radius);
}
}  // namespace

// The guiding-vector graph's edges are found for every vertex at once on the pool (after a few
// built one by one, which keep theirs): each vertex gets the edges yao8_edges finds alone, and the
// grown tree is the single thread's, bit for bit.
TEST(JobPool, GuidingVectorEdgesBuiltTogetherAreTheOnesBuiltOneByOne) {
  rng random(5);
  std::vector<glm::vec3> pts(3000);
  for (glm::vec3& q : pts) q = glm::vec3(random.uniform(), random.uniform(), random.uniform());
  gv_graph lazy = make_gv_graph(pts, 0.05f), all = make_gv_graph(pts, 0.05f);
  for (int32_t v : {7, 1200, 2999}) yao8_edges(all, v);
  build_all_yao8_edges(all);
  for (int32_t v = 0; v < int32_t(pts.size()); ++v) {
    ASSERT_GE(all.edge_at[size_t(v)], 0);
    const int32_t* want = yao8_edges(lazy, v);
    const int32_t* got = yao8_edges(all, v);
    for (int o = 0; o < 8; ++o) ASSERT_EQ(got[o], want[o]) << "vertex " << v << " octant " << o;
  }
  for (const char* name : {"guiding_vectors_default", "guiding_vectors_fig7_radial"})
    expect_growth_is_the_single_threaded_one(name, 150);
}

// A step of long cone scans (the bush's fine voxels make large cones) scans them all on the pool
// first and replays each shoot's choices on the RNG in order: the tree is the single thread's.
TEST(JobPool, ShadowConesScannedTogetherAreTheSingleThreadedOnes) {
  // The hazel's growth whole: its self-pruning pass takes most of the stems' side shoots away after
  // the growth this test is about (a vase of bare stems, about 800 nodes left of 9,400).
  expect_growth_is_the_single_threaded_one("species_bush", 3000, true);
}

// Space colonization finds a crown step's new nodes' points on the pool before they take them one
// by one: the oak (steps of hundreds of new nodes, with kills) is the single thread's.
TEST(JobPool, ColonizationVisitsFoundTogetherAreTheSingleThreadedOnes) {
  expect_growth_is_the_single_threaded_one("species_oak", 3000);
  expect_growth_is_the_single_threaded_one("space_colonization_seed_cube", 3000);
}

// The space-colonization environment scans its buds' cones in chunks on the pool: the tree is the
// single thread's, bit for bit, with the preset's markers and with three buds a node in wide cones,
// where a node's buds stand at one point and tie for every marker they all perceive.
TEST(JobPool, MarkerLightFoundTogetherIsTheSingleThreadedOne) {
  expect_growth_is_the_single_threaded_one("self_organizing_markers", 20000);
  preset p;
  ASSERT_TRUE(load_preset_file(std::string(SYLVA_SOURCE_DIR) + "/presets/self_organizing_markers.json", p).ok);
  auto& so = std::get<self_organizing_params>(p.spec.params);
  so.phyllotaxis = so_phyllotaxis::opposite, so.perception_angle = 170, so.steps = 12;
  const int old = set_job_pool_limit(1);
  const tree_skeleton one = grow(p.spec, grow_options{});
  set_job_pool_limit(old);
  const tree_skeleton many = grow(p.spec, grow_options{});
  ASSERT_GT(one.size(), 500u);
  EXPECT_EQ(one.parent, many.parent);
  EXPECT_EQ(one.position, many.position);
}

// On a lattice many points tie for an octant's nearest: the grid's first pass hands those vertices
// to the k-d tree, so the edges are still the ones yao8_edges finds (the first tied point it meets).
TEST(JobPool, GuidingVectorEdgesOnALatticeAreTheOnesBuiltOneByOne) {
  std::vector<glm::vec3> pts;
  for (int z = 0; z < 9; ++z)
    for (int y = 0; y < 11; ++y)
      for (int x = 0; x < 10; ++x) pts.push_back(glm::vec3(float(x), float(y), float(z)) * 0.25f);
  gv_graph lazy = make_gv_graph(pts, 0.25f), all = make_gv_graph(pts, 0.25f);
  build_all_yao8_edges(all);
  for (int32_t v = 0; v < int32_t(pts.size()); ++v) {
    const int32_t* want = yao8_edges(lazy, v);
    const int32_t* got = yao8_edges(all, v);
    for (int o = 0; o < 8; ++o) ASSERT_EQ(got[o], want[o]) << "vertex " << v << " octant " << o;
  }
}


// The wood pass sweeps a large tree's subtrees on the pool and its trunk on the calling thread: the
// bent tree, its leaves and the bend replayed at earlier steps are the one-thread pass's, bit for
// bit, on a tree that sheds (the default) and on nine trees in one skeleton (the forest's roots).
TEST(JobPool, WoodPassOnThePoolIsTheOneThreadPass) {
  for (const char* name : {"self_organizing_default", "species_forest"}) {
    SCOPED_TRACE(name);
    preset p;
    ASSERT_TRUE(load_preset_file(std::string(SYLVA_SOURCE_DIR) + "/presets/" + name + ".json", p).ok);
    p.spec.wood = wood_params{};   // grown unbent, then bent here both ways
    const tree_skeleton grown = grow(p.spec, grow_options{});
    ASSERT_GT(grown.size(), 16384u);   // the pool's threshold in wood.cpp
    wood_params w;
    w.gravity = 1;
    tree_skeleton one = grown, many = grown;
    const int old = set_job_pool_limit(1);
    apply_wood(one, w);
    const std::vector<glm::vec3> one_mid = positions_at_step(one, one.steps / 2);
    const std::vector<glm::vec3> one_late = positions_at_step(one, one.steps - 2);
    set_job_pool_limit(old);
    apply_wood(many, w);
    ASSERT_NE(one.position, grown.position);   // it bent
    EXPECT_EQ(one.position, many.position);
    ASSERT_EQ(one.leaves.size(), many.leaves.size());
    for (size_t k = 0; k < one.leaves.size(); ++k) ASSERT_EQ(one.leaves[k].position, many.leaves[k].position) << k;
    EXPECT_EQ(one_mid, positions_at_step(many, many.steps / 2));
    EXPECT_EQ(one_late, positions_at_step(many, many.steps - 2));
  }
}
