// libFuzzer: the editor's recovery file (a preset, autosaved) with its companion `.source` path, as
// the editor reads them back at start: either it says why not, or the document saves, loads back
// equal and grows (small), and the path is one clean line.
#include <cstdint>
#include <string>

#include "app/editor/editor_settings.h"
#include "tests/fuzz/fuzz_common.h"

using namespace sylva;

// Input: the recovery file's text, then a NUL byte and the .source file's text (none: no path).
extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string_view in(reinterpret_cast<const char*>(data), size);
  const size_t nul = in.find('\0');
  const std::string_view json = in.substr(0, nul), source = nul == std::string_view::npos ? "" : in.substr(nul + 1);
  preset doc;
  std::string path = "unchanged";
  const std::string why = parse_recovery(json, source, doc, path);
  if (!why.empty()) {
    fuzz_check(path == "unchanged", "a refused recovery sets no path");
    return 0;
  }
  fuzz_check(path.empty() || check_saved_path(path).empty(), "the recovered path is one clean line");
  preset back;
  fuzz_check(load_preset_json(save_preset_json(doc), back).ok && back == doc, "the recovered document round-trips");
  make_growth_small(doc);
  const tree_skeleton t = grow(doc.spec, grow_options{});
  fuzz_check(validate_mesh(mesh_tree(t, doc.mesh, doc.spec.seed)).empty(), "its mesh is valid");
  return 0;
}
