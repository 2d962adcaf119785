// The interactive editor's entry point (docs/design/09-editor.md).
#pragma once

#include <cstdint>
#include <optional>
#include <string>

namespace sylva {

struct editor_options {
  std::string preset_path;       // "" opens default_preset() (render/io/preset.h)
  std::string screenshot_path;   // non-empty: render `frames` frames after the tree is shown, save, quit
  int frames = 3;
  int width = 1600, height = 1000;
  bool fit_screen = true;        // size from ~/Sylva/settings.ini, or fit the monitor's work area (else width×height)
  bool overlays = false;         // start with the growth-debug overlays shown
  // For the editor's tests and measurements (unset: as a person starts it).
  std::optional<std::string> script_path;   // drive the editor from this script (app/editor/editor_script.h)
  std::optional<int64_t> node_budget;       // the growth node budget (at least 1000), over the saved setting
  std::optional<bool> show_browser, show_export;   // start with the preset library, the Export dialog open or closed
  std::optional<float> ui_scale;            // the UI's scale, kept when the window moves to another monitor
};

// Opens the editor window on a preset file, or on default_preset() (render/io/preset.h) when the path
// is empty. Returns the process exit code. The environment, read once into the options, can ask
// for an automatic screenshot (used by the GUI smoke test): SYLVA_SCREENSHOT=PATH, SYLVA_FRAMES=N,
// SYLVA_WINDOW=WxH, SYLVA_OVERLAYS=1; and for the rest of the options: SYLVA_SCRIPT=FILE,
// SYLVA_NODE_BUDGET=N, SYLVA_SHOW_BROWSER=0|1, SYLVA_SHOW_EXPORT=0|1, SYLVA_UI_SCALE=S.
int run_editor(const std::string& preset_path);
int run_editor(const editor_options& options);

}  // namespace sylva
