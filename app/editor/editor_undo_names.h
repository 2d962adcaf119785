// Names for undo entries ("Undo Influence radius"): what changed between two documents, in the
// words of the panel. Display-free, so it is tested.
#pragma once

#include <string>

#include "render/io/preset.h"

namespace sylva {

// "Influence radius", "Season and 2 more", "Generator", "Cut at step 12", "Open Oak"; "" when the
// documents are equal.
std::string change_name(const preset& before, const preset& after);

}  // namespace sylva
