// Waking the editor's frame loop from another thread. With nothing moving, the loop waits for
// events (app/editor/editor.cpp), so work that finishes off the UI thread with something to show
// (a grown tree, its overlays, a LOD chain) says so here: a count the loop compares, and an empty
// event that ends its wait (the editor installs glfwPostEmptyEvent; tests and the CLI install none).
#pragma once

#include <atomic>
#include <cstdint>

namespace sylva {

inline std::atomic<uint64_t> ui_wakes{0};
inline std::atomic<void (*)()> ui_waker{nullptr};

inline void wake_ui() {
  ui_wakes.fetch_add(1, std::memory_order_relaxed);
  if (void (*post)() = ui_waker.load()) post();
}

}  // namespace sylva
