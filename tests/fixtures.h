// Fixtures several test files share: the shipped presets by name (presets/NAME.json). Both test
// binaries define SYLVA_SOURCE_DIR.
#pragma once

#include <string>
#include <vector>

#include <gtest/gtest.h>

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

}  // namespace sylva_test
