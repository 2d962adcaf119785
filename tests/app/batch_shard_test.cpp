// `sylva export … --seeds A-B --shard I/N`: the shards' files are the unsharded run's byte for byte,
// their manifests merge to its manifest, and a rerun skips what is complete and redoes what is not.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "tests/scratch_dir.h"
#include "app/cli/cli_batch.h"
#include "tests/run_sylva.h"

namespace fs = std::filesystem;

using sylva_test::slurp;

namespace {

std::vector<std::string> lines_of(const fs::path& p) {
  std::vector<std::string> out;
  std::istringstream s(slurp(p));
  for (std::string line; std::getline(s, line);)
    if (!line.empty() && line[0] != '#') out.push_back(line);
  return out;
}

struct batch_dir : sylva_test::scratch_dir {
  batch_dir() : scratch_dir("sylva_shard_test") {}
};

const std::string preset = std::string(SYLVA_SOURCE_DIR) + "/presets/lsystem_honda_a.json";

}  // namespace

TEST(BatchShard, Sha256MatchesFips180Examples) {
  EXPECT_EQ(sylva::sha256_hex(""), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  EXPECT_EQ(sylva::sha256_hex("abc"), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  EXPECT_EQ(sylva::sha256_hex("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq"),
            "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
  int i = 0, n = 0;
  EXPECT_TRUE(sylva::parse_shard("2/4", i, n));
  EXPECT_EQ(i, 2);
  EXPECT_EQ(n, 4);
  for (const char* bad : {"0/4", "5/4", "1/0", "a/4", "1/", "/4", "1-4", "1/4/2"}) EXPECT_FALSE(sylva::parse_shard(bad, i, n)) << bad;
}

TEST(BatchShard, FourShardsEqualOneRunAndReruns) {
  batch_dir d;
  const std::string seeds = " --seeds 1-10 --set derivations=4";
  sylva_run all = run_sylva("", "export '" + preset + "' -o '" + (d.dir / "all" / "t.glb").string() + "'" + seeds);
  ASSERT_EQ(all.code, 0) << all.err;
  for (int i = 1; i <= 4; ++i) {
    sylva_run r = run_sylva("", "export '" + preset + "' -o '" + (d.dir / "shards" / "t.glb").string() + "'" + seeds +
                                    " --shard " + std::to_string(i) + "/4");
    ASSERT_EQ(r.code, 0) << r.err;
  }
  const std::vector<std::string> whole = lines_of(d.dir / "all" / "t-manifest.tsv");
  ASSERT_EQ(whole.size(), size_t(10));
  std::vector<std::string> merged;
  for (int i = 1; i <= 4; ++i) {
    const std::vector<std::string> part = lines_of(d.dir / "shards" / ("t-manifest-" + std::to_string(i) + "of4.tsv"));
    EXPECT_EQ(part.size(), i <= 2 ? size_t(3) : size_t(2)) << "shard " << i;   // variants i, i+4, i+8
    merged.insert(merged.end(), part.begin(), part.end());
  }
  std::sort(merged.begin(), merged.end(), [](const std::string& a, const std::string& b) { return std::stoul(a) < std::stoul(b); });
  EXPECT_EQ(merged, whole);
  for (uint64_t s = 1; s <= 10; ++s) {
    const std::string name = "t-" + std::to_string(s) + ".glb";
    const std::string a = slurp(d.dir / "all" / name), b = slurp(d.dir / "shards" / name);
    ASSERT_GT(a.size(), size_t(1000)) << name;
    EXPECT_EQ(a, b) << name << " differs between the sharded and the unsharded run";
  }
  // A rerun of shard 1 skips its three files; one made incomplete (truncated) is written again.
  fs::resize_file(d.dir / "shards" / "t-5.glb", 100);
  sylva_run again = run_sylva("", "export '" + preset + "' -o '" + (d.dir / "shards" / "t.glb").string() + "'" + seeds + " --shard 1/4");
  ASSERT_EQ(again.code, 0) << again.err;
  EXPECT_NE(again.out.find("t-5.glb:"), std::string::npos) << again.out;
  EXPECT_EQ(again.out.find("t-1.glb:"), std::string::npos) << again.out;
  EXPECT_NE(again.out.find("(2 already complete, skipped)"), std::string::npos) << again.out;
  EXPECT_EQ(slurp(d.dir / "shards" / "t-5.glb"), slurp(d.dir / "all" / "t-5.glb"));
  // Bad shards are usage errors.
  EXPECT_EQ(run_sylva("", "export '" + preset + "' -o '" + (d.dir / "x.glb").string() + "'" + seeds + " --shard 5/4").code, 2);
  EXPECT_EQ(run_sylva("", "export '" + preset + "' -o '" + (d.dir / "x.glb").string() + "' --shard 1/2").code, 2);
}
