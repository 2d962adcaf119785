// The interactive editor's entry point (DESIGN §5).
#pragma once

#include <string>

namespace sylva {

struct editor_options {
  std::string preset_path;       // "" opens default_preset() (render/io/preset.h)
  std::string screenshot_path;   // non-empty: render `frames` frames after the tree is shown, save, quit
  int frames = 3;
  int width = 1600, height = 1000;
  bool fit_screen = true;        // size from ~/Sylva/settings.ini, or fit the monitor's work area (else width×height)
  bool overlays = false;         // start with the growth-debug overlays shown
};

// Opens the editor window on a preset file, or on default_preset() (render/io/preset.h) when the path
// is empty. Returns the process exit code. The environment can ask for an automatic screenshot
// (used by the GUI smoke test): SYLVA_SCREENSHOT=PATH, SYLVA_FRAMES=N, SYLVA_WINDOW=WxH,
// SYLVA_OVERLAYS=1.
int run_editor(const std::string& preset_path);
int run_editor(const editor_options& options);

}  // namespace sylva
