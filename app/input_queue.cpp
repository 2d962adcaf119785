// Keyboard input queue for ImGui 1.86 (see input_queue.h).
#include "app/input_queue.h"

#include <bitset>

#include <GLFW/glfw3.h>
#include <imgui.h>

namespace sylva {

namespace {

input_queue* installed = nullptr;

void key_callback(GLFWwindow*, int key, int, int action, int) {
  if (installed) installed->push_key(key, action);
}

void char_callback(GLFWwindow*, unsigned c) {
  if (installed) installed->push_char(c);
}

}  // namespace

int feed_imgui(input_queue& q, ImGuiIO& io) {
  constexpr int key_count = int(sizeof(io.KeysDown) / sizeof(io.KeysDown[0]));
  io.KeyRepeatDelay = 1e9f;   // repeats come from the system as GLFW_REPEAT events
  std::bitset<key_count> touched;
  int fed = 0;
  while (!q.events.empty()) {
    const input_event ev = q.events.front();
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

void install_input_queue(GLFWwindow* window, input_queue* q) {
  installed = q;
  glfwSetKeyCallback(window, key_callback);
  glfwSetCharCallback(window, char_callback);
}

}  // namespace sylva
