// `sylva textures`: what its help says of the archetypes.
#include <gtest/gtest.h>

#include <string>

#include "generators/archetypes.h"
#include "tests/run_sylva.h"

// The help counts the archetypes there are (it once said 9 leaf cards when there were 22).
TEST(TexturesCli, HelpCountsTheArchetypes) {
  const sylva_run r = run_sylva("", "textures --help");
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("the " + std::to_string(sylva::leaf_archetype_count) + " leaf cards and " +
                       std::to_string(sylva::bark_archetype_count) + " barks"),
            std::string::npos)
      << r.out;
}
