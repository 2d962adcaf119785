// Issue 15 item 10: the documented peak memory of a growth holds. Each case is a request that
// drives one generator's memory (a runaway shadow grid, the marker and point caps, a long
// L-system string), grown by `sylva bench` in a child process whose peak RSS is its own.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "generators/guiding_vectors.h"
#include "generators/memory_bound.h"
#include "generators/self_organizing.h"
#include "render/io/preset.h"
#include "tests/run_sylva.h"
#include "tests/scratch_dir.h"

using namespace sylva;

namespace {

struct bound_case {
  const char* name;
  const char* generator;
  const char* params;  // JSON object text
};

}  // namespace

TEST(MemoryBound, WorstCaseIsStatedPerGenerator) {
  for (int g = 0; g < generator_count; ++g) {
    const std::string text = memory_bound_text(g);
    EXPECT_NE(text.find("peak growth memory <="), std::string::npos) << text;
    EXPECT_NE(text.find("at the default node_cap"), std::string::npos) << text;
    const memory_bound w = worst_memory_bound(g);
    EXPECT_GT(w.bytes(), 1e8);
    EXPECT_LT(w.bytes(), 16e9) << "generator " << g;  // every cap holds: no unbounded term
  }
  const sylva_run r = run_sylva("", "params");
  ASSERT_EQ(r.code, 0);
  size_t n = 0;
  for (size_t at = r.out.find("peak growth memory"); at != std::string::npos; at = r.out.find("peak growth memory", at + 1)) ++n;
  EXPECT_EQ(n, size_t(generator_count));
}

// The new caps say so: the shadow grid stops a runaway, markers are shared out under their cap.
TEST(MemoryBound, RequestsStayUnderTheirBound) {
  const bound_case cases[] = {
      // λ = 1 with the deepest, finest shadow and the widest cone: the grid reaches its cap.
      {"so_runaway", "self_organizing",
       R"({"lambda": 1, "q_max": 16, "voxel_size": 0.25, "perception_distance": 10, "alpha": 20, "steps": 200, "node_cap": 300000})"},
      // 8 trees × 1,000,000 markers: capped at 8,000,000 in all.
      {"so_markers", "self_organizing",
       R"({"environment": "space_colonization", "marker_count": 1000000, "tree_count": 8, "steps": 1, "node_cap": 100000})"},
      {"sc_points", "space_colonization", R"({"points": 2000000, "steps": 3, "node_cap": 1000})"},
      {"gv_points", "guiding_vectors", R"({"spacing": 0.08, "domain_size": [5, 5, 5], "volume_offset": [0, 3, 0], "steps": 2, "node_cap": 20000})"},
      {"ls_modules", "lsystem",
       R"({"mode": "text", "source": "#axiom F\nF -> FF\n", "derivations": 23, "module_cap": 5000000, "node_cap": 300000})"},
  };
  const sylva_test::scratch_dir scratch("sylva_membound");
  const std::filesystem::path& dir = scratch.dir;
  for (const bound_case& c : cases) {
    const std::string path = (dir / (std::string(c.name) + ".json")).string();
    {
      std::ofstream f(path);
      f << R"({"sylva_preset": 1, "name": ")" << c.name << R"(", "generator": ")" << c.generator
        << R"(", "seed": 1, "params": )" << c.params << "}\n";
    }
    preset p;
    const load_result loaded = load_preset_file(path, p);
    ASSERT_TRUE(loaded.ok) << c.name << ": " << loaded.error;
    ASSERT_TRUE(loaded.warnings.empty()) << c.name << ": " << loaded.warnings.front();
    const double bound_mib = growth_memory_bound(p.spec).bytes() / (1024.0 * 1024.0);
    const sylva_run r = run_sylva("", "bench --repeat 1 --json '" + path + "'");
    ASSERT_EQ(r.code, 0) << c.name << ": " << r.err;
    const nlohmann::json j = nlohmann::json::parse(r.out.substr(0, r.out.find('\n')));
    const double grow_mib = j["grow_peak_rss_mb"].get<double>();
    EXPECT_GT(j["nodes"].get<double>(), 0) << c.name;
    EXPECT_LE(grow_mib, bound_mib) << c.name;
    std::printf("%-12s peak %7.1f MiB, bound %7.1f MiB\n", c.name, grow_mib, bound_mib);
    if (std::string(c.name) == "so_runaway") { EXPECT_NE(r.err.find("shadow grid memory cap reached"), std::string::npos) << r.err; }
  }
}

TEST(MemoryBound, MarkerCapSaysSo) {
  self_organizing_params p;
  p.environment = so_environment::markers;
  p.tree_count = 9;
  p.marker_count = 1000000;
  grow_options o;
  o.steps = 0;
  grow_report rep;
  grow_self_organizing(p, o, &rep);
  EXPECT_NE(rep.message.find("markers capped at 8000000 in all: 888888 per tree"), std::string::npos) << rep.message;
}

TEST(MemoryBound, GuidingVectorsPointCapSaysSo) {
  // The sampler stops at its point cap (4,000,000 in growth; 1,000 here, to be quick) and says so.
  std::vector<glm::vec3> pts;
  std::string why;
  EXPECT_FALSE(sample_poisson_disc(glm::vec3(0), glm::vec3(4), glm::vec3(0), 0.1f, 12, 1, {}, pts, &why, 1000));
  EXPECT_NE(why.find("1000 points (its memory cap)"), std::string::npos) << why;
  EXPECT_TRUE(pts.empty());
  EXPECT_TRUE(sample_poisson_disc(glm::vec3(0), glm::vec3(4), glm::vec3(0), 0.1f, 12, 1, {}, pts, &why));
  EXPECT_GT(pts.size(), 1000u);
}
