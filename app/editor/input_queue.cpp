// Keyboard input queue for ImGui 1.86 (see input_queue.h).
#include "app/editor/input_queue.h"

#include <algorithm>
#include <bitset>
#include <cfloat>

#include <GLFW/glfw3.h>
#include <imgui.h>

#include "app/common/wake.h"

namespace sylva {

namespace {

input_queue* installed = nullptr;

void key_callback(GLFWwindow*, int key, int, int action, int) {
  if (installed) installed->push_key(key, action);
}

void char_callback(GLFWwindow*, unsigned c) {
  if (installed) installed->push_char(c);
}

void cursor_callback(GLFWwindow*, double x, double y) {
  if (installed) installed->push_move(float(x), float(y));
}

void button_callback(GLFWwindow* w, int button, int action, int) {
  if (!installed) return;
  double x = 0, y = 0;
  glfwGetCursorPos(w, &x, &y);
  installed->push_button(button, action == GLFW_PRESS, float(x), float(y));
}

// The window's other events wake the frame loop; the callbacks they replace are still called.
GLFWscrollfun prev_scroll = nullptr;
GLFWwindowfocusfun prev_focus = nullptr;
GLFWcursorenterfun prev_enter = nullptr;
GLFWwindowclosefun prev_close = nullptr;
GLFWwindowcontentscalefun prev_scale = nullptr;

void count_event() {
  if (installed) ++installed->window_events;
}
void scroll_callback(GLFWwindow* w, double x, double y) {
  count_event();
  if (prev_scroll) prev_scroll(w, x, y);
}
void focus_callback(GLFWwindow* w, int focused) {
  count_event();
  if (prev_focus) prev_focus(w, focused);
}
void enter_callback(GLFWwindow* w, int entered) {
  count_event();
  if (prev_enter) prev_enter(w, entered);
}
void close_callback(GLFWwindow* w) {
  count_event();
  if (prev_close) prev_close(w);
}
void scale_callback(GLFWwindow* w, float x, float y) {
  count_event();
  if (prev_scale) prev_scale(w, x, y);
}

}  // namespace

int feed_imgui(input_queue& q, ImGuiIO& io) {
  constexpr int key_count = int(sizeof(io.KeysDown) / sizeof(io.KeysDown[0]));
  io.KeyRepeatDelay = 1e9f;   // repeats come from the system as GLFW_REPEAT events
  std::bitset<key_count> touched;
  q.repeated.reset();
  uint64_t click_seq = UINT64_MAX;   // the first mouse button event not fed yet
  for (const mouse_event& m : q.mouse)
    if (m.is_button) {
      click_seq = m.seq;
      break;
    }
  int fed = 0;
  while (!q.events.empty()) {
    const input_event ev = q.events.front();
    if (ev.seq > click_seq) break;   // typed after a click that has not reached ImGui yet
    if (ev.is_char) {
      if (ev.codepoint > 0 && ev.codepoint < 0x10000) io.AddInputCharacter(ev.codepoint);
    } else if (ev.key >= 0 && ev.key < key_count) {
      if (touched[size_t(ev.key)]) break;   // this key changed already: the rest waits a frame
      touched[size_t(ev.key)] = true;
      if (ev.action == GLFW_PRESS) {
        io.KeysDown[ev.key] = true;
      } else if (ev.action == GLFW_RELEASE) {
        io.KeysDown[ev.key] = false;
      } else if (ev.action == GLFW_REPEAT) {
        // ImGui::NewFrame turns a negative duration of a held key into 0: pressed this frame.
        io.KeysDown[ev.key] = true;
        io.KeysDownDuration[ev.key] = -1.0f;
        if (size_t(ev.key) < q.repeated.size()) q.repeated[size_t(ev.key)] = true;
      }
    }
    q.events.pop_front();
    ++fed;
  }
  io.KeyCtrl = io.KeysDown[GLFW_KEY_LEFT_CONTROL] || io.KeysDown[GLFW_KEY_RIGHT_CONTROL];
  io.KeyShift = io.KeysDown[GLFW_KEY_LEFT_SHIFT] || io.KeysDown[GLFW_KEY_RIGHT_SHIFT];
  io.KeyAlt = io.KeysDown[GLFW_KEY_LEFT_ALT] || io.KeysDown[GLFW_KEY_RIGHT_ALT];
  io.KeySuper = io.KeysDown[GLFW_KEY_LEFT_SUPER] || io.KeysDown[GLFW_KEY_RIGHT_SUPER];
  return fed;
}

int feed_mouse(input_queue& q, ImGuiIO& io) {
  constexpr int buttons = int(sizeof(q.buttons) / sizeof(q.buttons[0]));
  int fed = 0;
  bool moved = false, button = false;
  while (!q.mouse.empty()) {
    const mouse_event ev = q.mouse.front();
    if (ev.is_button && ev.button >= 0 && ev.button < buttons) {
      if (ev.down && moved) break;   // the move gets this frame, the press the next one
      q.buttons[ev.button] = ev.down;
      q.mouse_x = ev.x, q.mouse_y = ev.y, q.mouse_known = true;
      q.mouse.pop_front();
      ++fed;
      button = true;
      break;                         // one button change per frame; what follows waits
    }
    if (!ev.is_button) {
      q.mouse_x = ev.x, q.mouse_y = ev.y, q.mouse_known = true;
      moved = true;
    }
    q.mouse.pop_front();
    ++fed;
  }
  // The backend polled the cursor: outside the window (and unfocused) it reports no position;
  // otherwise the queued position is the one in step with the buttons. A button change fed this
  // frame happened in this window at its place, focused or not: the release of a click on a
  // window without the focus (beside another window, or with no window manager) must land on the
  // button it pressed, or the click is lost.
  const bool outside = io.MousePos.x <= -FLT_MAX * 0.5f;
  bool any_down = false;
  for (int b = 0; b < buttons; ++b) any_down |= q.buttons[b];
  if (q.mouse_known && (!outside || any_down || button)) io.MousePos = ImVec2(q.mouse_x, q.mouse_y);
  for (int b = 0; b < buttons; ++b) io.MouseDown[b] = q.buttons[b];
  return fed;
}

void install_input_queue(GLFWwindow* window, input_queue* q) {
  installed = q;
  glfwSetKeyCallback(window, key_callback);
  glfwSetCharCallback(window, char_callback);
  glfwSetCursorPosCallback(window, cursor_callback);
  glfwSetMouseButtonCallback(window, button_callback);
  prev_scroll = glfwSetScrollCallback(window, scroll_callback);
  prev_focus = glfwSetWindowFocusCallback(window, focus_callback);
  prev_enter = glfwSetCursorEnterCallback(window, enter_callback);
  prev_close = glfwSetWindowCloseCallback(window, close_callback);
  prev_scale = glfwSetWindowContentScaleCallback(window, scale_callback);
  glfwSetWindowSizeCallback(window, [](GLFWwindow*, int, int) { count_event(); });
  glfwSetFramebufferSizeCallback(window, [](GLFWwindow*, int, int) { count_event(); });
  glfwSetWindowRefreshCallback(window, [](GLFWwindow*) { count_event(); });   // uncovered: draw again
  glfwSetWindowIconifyCallback(window, [](GLFWwindow*, int) { count_event(); });
  glfwSetWindowMaximizeCallback(window, [](GLFWwindow*, int) { count_event(); });
}

bool next_frame(frame_pacer& p, input_queue& q, bool busy, double timeout_s) {
  const bool draw = busy || p.settle > 0 || !q.events.empty() || !q.mouse.empty();
  p.waited = !draw;
  if (draw) glfwPollEvents();
  else glfwWaitEventsTimeout(timeout_s);
  // Input and window events settle over a few frames; work finished elsewhere is shown in one.
  const uint64_t events = q.next_seq + q.window_events, wakes = ui_wakes.load();
  const bool woken = wakes != p.seen_wakes;
  p.seen_wakes = wakes;
  if (events != p.seen) {
    p.seen = events;
    p.settle = settle_frames;
  } else if (woken) {
    p.settle = std::max(p.settle, 1);
  } else if (!draw) {
    return false;
  }
  if (p.settle > 0) --p.settle;
  return true;
}

}  // namespace sylva
