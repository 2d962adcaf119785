// The preset format (docs/design/10-files.md): the preset struct, its JSON and `--set`, and safe
// file writing. Core I/O returns errors as values, never throws.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "generators/tree_spec.h"
#include "render/files.h"
#include "render/mesh/mesh.h"
#include "render/mesh/render_params.h"

namespace sylva {

inline constexpr int preset_version = 1;

// Input limits (docs/DESIGN-NOTES.md): a preset is a page of text; a texture or mesh may be large.
inline constexpr uint64_t max_preset_bytes = 64ull << 20;
// What one preset may hold, so a small file cannot expand into gigabytes once parsed.
inline constexpr size_t max_preset_values = 1000000;     // JSON values in the whole document
inline constexpr size_t max_preset_tags = 1000;
inline constexpr size_t max_preset_list = 100000;        // entries of a list parameter (positions, schedules)
inline constexpr size_t max_preset_text_bytes = 1 << 20;  // one string: a name, a tag, an L-system text

// True when `s` is well-formed UTF-8 (RFC 3629: no overlong forms, no surrogates, <= U+10FFFF).
bool valid_utf8(std::string_view s);

struct preset {
  std::string name = "Untitled";
  std::string description;
  std::vector<std::string> tags;
  tree_spec spec;
  mesh_params mesh;
  render_params render;
  bool operator==(const preset&) const = default;
};

struct load_result {
  bool ok = false;
  std::string error;                  // set when !ok; `out` is then untouched
  std::vector<std::string> warnings;  // unknown keys, clamped values, upgraded versions
};

// Tolerant load: missing keys keep defaults, unknown keys warn, out-of-range or NaN values are
// clamped with a warning, wrong types and malformed JSON are errors.
load_result load_preset_json(std::string_view text, preset& out);
load_result load_preset_file(const std::string& path, preset& out);
// Never throws: strings that are not UTF-8 (they cannot enter through the loaders or --set, but
// an editor document might hold one) are written with U+FFFD in place of the bad bytes.
std::string save_preset_json(const preset& p);
// Writes through a temporary file and a rename; returns "" or the error.
std::string save_preset_file(const preset& p, const std::string& path);

// What the loader refuses across fields of a document that each field alone cannot show: its
// keyframes and cuts against its generator and params (a text L-system carries none). "" when
// load_preset_json would take the document's save. The editor reverts a completed edit that makes
// it non-empty, and set_preset_param refuses such an assignment, so no edit makes a document that
// saves but cannot be reopened.
std::string document_refusal(const preset& p);
// The first number of the document that is NaN or infinite (finite_refusal, generators/params.h,
// naming the parameter), or "". JSON has no such numbers, so a document holding one would save
// as null and not load again; document_refusal starts with this check.
std::string non_finite_refusal(const preset& p);

// `key=value` for the current generator's params, mesh or render params (CLI --set), or
// `key@step=value` for a keyframe of a generator parameter (generators/keyframes.h).
// Returns "" or the error; on an error the preset is unchanged.
std::string set_preset_param(preset& p, std::string_view assignment);
// CLI `--set key=a:b:n` for a numeric parameter: appends n assignments from a to b, evenly spaced
// (rounded for integers); any other assignment is appended unchanged. Every value is checked as
// set_preset_param would, so a sweep is refused whole before anything is grown. Returns "" or the error.
std::string expand_param_sweep(const preset& p, std::string_view assignment, std::vector<std::string>& out);

// Honda's tree a (lsystem_params defaults): the editor's tree when no preset is named and the oak
// (presets/species_oak.json) is not found, and the scripted sessions' starting document.
preset default_preset();

}  // namespace sylva
