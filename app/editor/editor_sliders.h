// How a parameter's slider behaves: drag speed scaled to its range (Shift for fine steps), a
// logarithmic scale where the range spans decades, and a number format with sensible digits and
// the unit. Display-free, so it is tested.
#pragma once

#include <string>

#include "generators/params.h"

namespace sylva {

// Whether the slider moves on a log scale: declared so, or a positive range spanning at least two
// decades or more (0.0001 to 1 m reads nothing on a linear slider).
bool slider_is_log(const param_info& info);
// Value change per pixel of drag: the whole range over about 600 pixels (three slider widths), a
// tenth of that with `fine` (Shift); on a log slider, the whole log scale over the same pixels.
float drag_speed(const param_info& info, bool fine);
// The unit the help names ("m", "°", "%"...) or "".
std::string param_unit(const param_info& info);
// A printf format for a float parameter: digits enough for its range, then its unit
// ("%.2f m", "%.1f°", "%.3g").
std::string slider_format(const param_info& info);

// A path parameter being typed (param_path: a user texture). The text applies to the document
// only on Enter or when the field is left, so a half-typed path never loads a file.
struct path_field_edit {
  unsigned id = 0;    // the field being typed (its ImGui id; 0: none)
  std::string text;   // what it holds so far
};

}  // namespace sylva
