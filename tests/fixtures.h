// Fixtures several test files share: the shipped presets by name (presets/NAME.json). Both test
// binaries define SYLVA_SOURCE_DIR.
#pragma once

#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "generators/lsystem.h"
#include "generators/space_colonization.h"
#include "render/io/export.h"
#include "render/io/preset.h"

namespace sylva_test {

// presets/NAME.json as shipped. One that does not load fails the test (naming the preset and why)
// and gives the default preset; `warnings`, when given, gets what the loader warned about.
inline sylva::preset shipped_preset(const std::string& name, std::vector<std::string>* warnings = nullptr) {
  sylva::preset p;
  const sylva::load_result r = sylva::load_preset_file(std::string(SYLVA_SOURCE_DIR) + "/presets/" + name + ".json", p);
  EXPECT_TRUE(r.ok) << name << ": " << r.error;
  if (warnings) *warnings = r.warnings;
  return p;
}

// A space-colonization crown small enough for a test: `points` points in a 4 m box over a 1 m trunk.
inline sylva::space_colonization_params small_colonization_crown(int points) {
  sylva::space_colonization_params p;
  p.points = points;
  p.size = {4, 4, 4};
  p.offset = {0, 3, 0};
  p.segment_length = 0.2f;
  p.influence_radius = 1.2f;
  p.kill_distance = 0.3f;
  p.trunk_length = 1.0f;
  p.steps = 400;
  return p;
}

// The export tests' tree: Honda's tree a (lsystem_params' defaults) after `derivations` steps,
// meshed with 6 radial segments, and export options that re-mesh it alike, with textures of
// texture_size pixels.
struct honda_export {
  sylva::tree_skeleton t;
  sylva::tree_mesh m;
  sylva::export_options o;
};
inline honda_export honda_for_export(int derivations, int texture_size) {
  sylva::lsystem_params lp;
  lp.derivations = derivations;
  honda_export h;
  h.t = sylva::grow_honda(lp, {});
  sylva::mesh_params p;
  p.radial_segments = 6;
  h.m = sylva::mesh_tree(h.t, p);
  h.o.mesh = p;
  h.o.texture_size = texture_size;
  return h;
}

}  // namespace sylva_test
