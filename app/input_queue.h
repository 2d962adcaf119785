// Keyboard input queue: ImGui 1.86 samples io.KeysDown once per frame, so a press and a release
// inside one frame (a quick tap on a slow frame) vanish. We queue GLFW's key and character events
// ourselves and feed ImGui at most one transition per key per frame, as newer ImGui does (issue 14).
#pragma once

#include <deque>

struct GLFWwindow;
struct ImGuiIO;

namespace sylva {

struct input_event {
  bool is_char = false;
  int key = 0;              // GLFW_KEY_*
  int action = 0;           // GLFW_PRESS, GLFW_RELEASE or GLFW_REPEAT
  unsigned codepoint = 0;   // is_char
};

struct input_queue {
  std::deque<input_event> events;
  void push_key(int key, int action) { events.push_back({false, key, action, 0}); }
  void push_char(unsigned c) { events.push_back({true, 0, 0, c}); }
};

// Feeds queued events to ImGui before ImGui::NewFrame(): in order, at most one press, release or
// repeat per key per frame; the rest wait for the next frame (characters keep their place among
// the keys). A repeat (the system's key repeat) counts as a fresh press, and ImGui's own key
// repeat is switched off, so a held key repeats only at the system rate. Returns the number of
// events fed.
int feed_imgui(input_queue& q, ImGuiIO& io);

// Replaces the ImGui GLFW backend's key and character callbacks (call after
// ImGui_ImplGlfw_InitForOpenGL) so that events land in `q` instead.
void install_input_queue(GLFWwindow* window, input_queue* q);

}  // namespace sylva
