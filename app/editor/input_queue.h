// Keyboard input queue: ImGui 1.86 samples io.KeysDown once per frame, so a press and a release
// inside one frame (a quick tap on a slow frame) vanish. We queue GLFW's key and character events
// ourselves and feed ImGui at most one transition per key per frame, as newer ImGui does.
#pragma once

#include <bitset>
#include <cstdint>
#include <deque>

struct GLFWwindow;
struct ImGuiIO;

namespace sylva {

struct input_event {
  bool is_char = false;
  int key = 0;              // GLFW_KEY_*
  int action = 0;           // GLFW_PRESS, GLFW_RELEASE or GLFW_REPEAT
  unsigned codepoint = 0;   // is_char
  uint64_t seq = 0;         // arrival order among keys and mouse events
};

// A mouse event: a move to (x, y) or a button press or release there (window coordinates).
struct mouse_event {
  bool is_button = false;
  int button = 0;           // 0 left, 1 right, 2 middle ...
  bool down = false;
  float x = 0, y = 0;
  uint64_t seq = 0;
};

struct input_queue {
  std::deque<input_event> events;
  std::bitset<512> repeated;          // keys whose change fed this frame was a system repeat
  std::deque<mouse_event> mouse;
  bool mouse_known = false;           // a position has been queued (the cursor is over the window)
  float mouse_x = 0, mouse_y = 0;     // the position fed last
  bool buttons[5] = {false, false, false, false, false};
  uint64_t next_seq = 1;
  uint64_t window_events = 0;         // other window events (scroll, resize, expose, focus, close): the frame pacer counts them
  void push_key(int key, int action) { events.push_back({false, key, action, 0, next_seq++}); }
  void push_char(unsigned c) { events.push_back({true, 0, 0, c, next_seq++}); }
  void push_move(float x, float y) { mouse.push_back({false, 0, false, x, y, next_seq++}); }
  void push_button(int button, bool down, float x, float y) { mouse.push_back({true, button, down, x, y, next_seq++}); }
  // Whether the key's press fed this frame came from the system's key repeat (held down): commands
  // that must not repeat (undo) ignore it.
  bool is_repeat(int key) const { return key >= 0 && key < int(repeated.size()) && repeated[size_t(key)]; }
};

// Feeds queued events to ImGui before ImGui::NewFrame(): in order, at most one press, release or
// repeat per key per frame; the rest wait for the next frame (characters keep their place among
// the keys). A repeat (the system's key repeat) counts as a fresh press, and ImGui's own key
// repeat is switched off, so a held key repeats only at the system rate. Keys and characters typed
// after a mouse click wait until the click has been fed (press and release, see feed_mouse): the
// click that puts the cursor in a text field comes first, so no character typed after it is lost.
// Returns the number of events fed.
int feed_imgui(input_queue& q, ImGuiIO& io);

// Feeds queued mouse events after the backend's ImGui_ImplGlfw_NewFrame (which polls the cursor)
// and before ImGui::NewFrame: at most one button change per frame, at the position where it
// happened. A press that follows a move waits for the next frame, so that the move is a frame of
// its own: the press then lands where the pointer is, with no motion in its frame, and is never
// read as a drag; the item under it has been hovered for a frame (a menu takes the first click).
// A press and release in one slow frame still give a click, one frame down and one up. Returns
// the number of events fed.
int feed_mouse(input_queue& q, ImGuiIO& io);

// Replaces the ImGui GLFW backend's key and character callbacks (call after
// ImGui_ImplGlfw_InitForOpenGL) so that events land in `q` instead, and counts the window's other
// events in q->window_events (the callbacks installed before are still called).
void install_input_queue(GLFWwindow* window, input_queue* q);

// The frame loop's pacing: it draws while something moves and otherwise waits for events, so an
// idle editor draws nothing (docs/design/09-editor.md "An editor that idles").
struct frame_pacer {
  uint64_t seen = 0;         // input and window events counted at the last frame
  uint64_t seen_wakes = 0;   // wakes (app/common/wake.h) counted at the last frame
  int settle = 0;            // frames still to draw: ImGui settles hovers, popups and sizes over a few after an
                             // event; a wake (a result to show) needs one
  bool waited = false;   // this frame followed a wait: its interval is no measure of drawing
};
inline constexpr int settle_frames = 3;
// Polls the window's events when `busy` (or input is still queued, or frames are settling), else
// waits for one at most `timeout_s`. True when a frame is to be drawn: then, or after an event or
// a wake since the last frame.
bool next_frame(frame_pacer& p, input_queue& q, bool busy, double timeout_s);

}  // namespace sylva
