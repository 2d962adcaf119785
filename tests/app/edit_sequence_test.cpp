// Save and recovery round-trip every document the editor can hold: edit sequences like the
// editor's (tests/edit_sequence.h) on every generator, each ending in a document whose save loads
// back equal; and the keyframe stranded past the last step by lowering Growth steps.
#include <gtest/gtest.h>

#include <random>

#include "app/editor/editor_keyframes.h"
#include "tests/edit_sequence.h"
#include "tests/fixtures.h"

using namespace sylva;

namespace {


}  // namespace

// Open self_organizing_default, key lambda at step 20 ("From this step on"), lower Growth steps to
// 5: the document keeps the keyframe, inactive; its save (and so its autosave) loads back equal;
// raising the steps again applies it.
TEST(EditSequences, AKeyframeStrandedByLoweringTheStepsSavesAndReopens) {
  preset p = sylva_test::shipped_preset("self_organizing_default");
  const generator_params before = params_at_step(p.spec, 20);
  generator_params after = before;
  std::get<self_organizing_params>(after).lambda = 0.62f;
  ASSERT_EQ(key_edits(p.spec, before, after, 20), "");
  ASSERT_EQ(set_preset_param(p, "steps=5"), "");
  ASSERT_EQ(p.spec.keyframes.size(), 1u);
  EXPECT_EQ(p.spec.keyframes[0].step, 20);
  EXPECT_FALSE(step_active(p.spec, 20));
  preset back;
  const load_result r = load_preset_json(save_preset_json(p), back);
  ASSERT_TRUE(r.ok) << r.error;
  EXPECT_EQ(back, p);
  ASSERT_EQ(set_preset_param(back, "steps=24"), "");
  EXPECT_TRUE(step_active(back.spec, 20));
  EXPECT_EQ(std::get<self_organizing_params>(params_at_step(back.spec, 21)).lambda, 0.62f);
}

// Thousands of random edit sequences on each generator's default and two species: every edit
// leaves a document that saves and loads back equal, and every refused edit changes nothing.
TEST(EditSequences, EveryEditSequenceSavesAndLoadsBackEqual) {
  const char* presets[] = {"self_organizing_default", "space_colonization_seed_sphere", "guiding_vectors_default",
                           "lsystem_honda_a", "species_oak", "species_pine"};
  std::mt19937 rng(2026);
  int sequences = 0, edits = 0;
  for (const char* name : presets) {
    const preset start = sylva_test::shipped_preset(name);
    for (int n = 0; n < 300; ++n) {
      std::vector<uint8_t> bytes(8 + rng() % 120);
      for (uint8_t& b : bytes) b = uint8_t(rng());
      preset p = start;
      const std::string e = sylva_test::run_edit_sequence(p, bytes.data(), bytes.size());
      ASSERT_EQ(e, "") << name << ", sequence " << n;
      ++sequences;
      edits += int(p.spec.keyframes.size() + p.spec.cuts.size());
    }
  }
  EXPECT_EQ(sequences, 1800);
  EXPECT_GT(edits, 1000);   // the sequences do reach keyframes and cuts, not only sliders
}
