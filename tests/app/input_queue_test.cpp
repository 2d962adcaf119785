// The editor's keyboard queue: taps shorter than a frame register, held keys repeat at the system rate.
#include <gtest/gtest.h>

#include <cfloat>

#include <GLFW/glfw3.h>
#include <imgui.h>

#include "app/editor/input_queue.h"

using namespace sylva;

namespace {

struct imgui_context {
  imgui_context() {
    ImGui::CreateContext();
    ImGuiIO& io = ImGui::GetIO();
    io.IniFilename = nullptr;
    io.DisplaySize = ImVec2(800, 600);
    io.DeltaTime = 1.0f / 10;   // a slow frame
    unsigned char* pixels = nullptr;
    int w = 0, h = 0;
    io.Fonts->GetTexDataAsRGBA32(&pixels, &w, &h);
    for (int k = 0; k < ImGuiKey_COUNT; ++k) io.KeyMap[k] = -1;
    io.KeyMap[ImGuiKey_Backspace] = GLFW_KEY_BACKSPACE;
  }
  ~imgui_context() { ImGui::DestroyContext(); }
};

// One frame: feed the queue, start the frame, report whether `key` was pressed, end the frame.
bool frame_presses(input_queue& q, int key) {
  feed_imgui(q, ImGui::GetIO());
  ImGui::NewFrame();
  const bool pressed = ImGui::IsKeyPressed(key);
  ImGui::EndFrame();
  return pressed;
}

}  // namespace

TEST(InputQueue, ATapBetweenTwoFramesIsSeenOnce) {
  imgui_context ctx;
  input_queue q;
  EXPECT_FALSE(frame_presses(q, GLFW_KEY_F));
  q.push_key(GLFW_KEY_F, GLFW_PRESS);   // both events arrive before the next frame
  q.push_key(GLFW_KEY_F, GLFW_RELEASE);
  EXPECT_TRUE(frame_presses(q, GLFW_KEY_F));
  EXPECT_EQ(q.events.size(), 1u);   // the release waits for the next frame
  EXPECT_FALSE(frame_presses(q, GLFW_KEY_F));   // the release
  EXPECT_FALSE(ImGui::GetIO().KeysDown[GLFW_KEY_F]);
  EXPECT_TRUE(q.events.empty());
}

TEST(InputQueue, NineQuickTapsAreNineFramesWithAPress) {
  imgui_context ctx;
  input_queue q;
  for (int i = 0; i < 9; ++i) {
    q.push_key(GLFW_KEY_BACKSPACE, GLFW_PRESS);
    q.push_key(GLFW_KEY_BACKSPACE, GLFW_RELEASE);
  }
  int presses = 0;
  for (int frame = 0; frame < 40; ++frame) presses += frame_presses(q, GLFW_KEY_BACKSPACE);
  EXPECT_EQ(presses, 9);
}

TEST(InputQueue, ModifierAndKeyInOneFrameGiveTheShortcut) {
  imgui_context ctx;
  input_queue q;
  q.push_key(GLFW_KEY_LEFT_CONTROL, GLFW_PRESS);
  q.push_key(GLFW_KEY_Z, GLFW_PRESS);
  q.push_key(GLFW_KEY_Z, GLFW_RELEASE);
  q.push_key(GLFW_KEY_LEFT_CONTROL, GLFW_RELEASE);
  feed_imgui(q, ImGui::GetIO());
  ImGui::NewFrame();
  EXPECT_TRUE(ImGui::GetIO().KeyCtrl);
  EXPECT_TRUE(ImGui::IsKeyPressed(GLFW_KEY_Z));
  ImGui::EndFrame();
}

TEST(InputQueue, HeldKeysRepeatOnlyWithTheSystem) {
  imgui_context ctx;
  input_queue q;
  q.push_key(GLFW_KEY_BACKSPACE, GLFW_PRESS);
  EXPECT_TRUE(frame_presses(q, GLFW_KEY_BACKSPACE));
  int presses = 0;
  for (int frame = 0; frame < 30; ++frame) presses += frame_presses(q, GLFW_KEY_BACKSPACE);   // 3 s held
  EXPECT_EQ(presses, 0);
  q.push_key(GLFW_KEY_BACKSPACE, GLFW_REPEAT);
  q.push_key(GLFW_KEY_BACKSPACE, GLFW_REPEAT);
  EXPECT_TRUE(frame_presses(q, GLFW_KEY_BACKSPACE));
  EXPECT_TRUE(frame_presses(q, GLFW_KEY_BACKSPACE));
  EXPECT_FALSE(frame_presses(q, GLFW_KEY_BACKSPACE));
}

TEST(InputQueue, CharactersKeepTheirPlaceAmongKeys) {
  imgui_context ctx;
  input_queue q;
  q.push_key(GLFW_KEY_BACKSPACE, GLFW_PRESS);
  q.push_key(GLFW_KEY_BACKSPACE, GLFW_RELEASE);
  q.push_char('x');
  feed_imgui(q, ImGui::GetIO());
  EXPECT_EQ(ImGui::GetIO().InputQueueCharacters.Size, 0);   // waits behind the release
  ImGui::NewFrame();
  ImGui::EndFrame();
  feed_imgui(q, ImGui::GetIO());
  EXPECT_EQ(ImGui::GetIO().InputQueueCharacters.Size, 1);
  EXPECT_TRUE(q.events.empty());
}

namespace {

// One frame with the mouse: the backend's poll (here: the pointer already at its final place and
// the buttons up), then the queue, then ImGui.
struct mouse_frame {
  bool clicked = false, dragging = false;
  ImVec2 pos, delta;
};
mouse_frame frame_mouse(input_queue& q, ImVec2 polled) {
  ImGuiIO& io = ImGui::GetIO();
  io.MousePos = polled;
  for (bool& b : io.MouseDown) b = false;
  feed_mouse(q, io);
  ImGui::NewFrame();
  mouse_frame f{ImGui::IsMouseClicked(0), ImGui::IsMouseDragging(0, 3), io.MousePos, io.MouseDelta};
  ImGui::EndFrame();
  return f;
}

}  // namespace

// On a slow frame the pointer moves onto the tree and clicks before the next frame: the move is
// a frame of its own, the press lands where it happened with no motion in its frame, and nothing
// counts as a drag (the view must not orbit; the click picks).
TEST(InputQueue, AMoveThenAQuickClickIsAClickNotADrag) {
  imgui_context ctx;
  input_queue q;
  frame_mouse(q, ImVec2(100, 100));
  q.push_move(100, 100);
  frame_mouse(q, ImVec2(100, 100));
  for (int x = 110; x <= 400; x += 10) q.push_move(float(x), 300);
  q.push_button(0, true, 400, 300);
  q.push_button(0, false, 400, 300);
  const mouse_frame moved = frame_mouse(q, ImVec2(400, 300));
  EXPECT_FALSE(moved.clicked);
  EXPECT_EQ(moved.pos.x, 400);
  const mouse_frame pressed = frame_mouse(q, ImVec2(400, 300));
  EXPECT_TRUE(pressed.clicked);
  EXPECT_EQ(pressed.delta.x, 0);
  EXPECT_EQ(pressed.delta.y, 0);
  EXPECT_FALSE(pressed.dragging);
  const mouse_frame released = frame_mouse(q, ImVec2(400, 300));
  EXPECT_FALSE(released.clicked);
  EXPECT_FALSE(ImGui::GetIO().MouseDown[0]);
  EXPECT_TRUE(q.mouse.empty());
  EXPECT_LT(ImGui::GetIO().MouseDragMaxDistanceSqr[0], 9);
}

// A window without the keyboard focus (another window has it, or there is no window manager): the
// backend polls no position, yet a queued click still presses and releases over its button.
TEST(InputQueue, AClickOnAnUnfocusedWindowIsAClick) {
  imgui_context ctx;
  input_queue q;
  const ImVec2 nowhere(-FLT_MAX, -FLT_MAX);
  q.push_move(200, 120);
  q.push_button(0, true, 200, 120);
  q.push_button(0, false, 200, 120);
  int clicks = 0;
  bool released_over_it = false;
  for (int frame = 0; frame < 3; ++frame) {
    ImGuiIO& io = ImGui::GetIO();
    io.MousePos = nowhere;
    for (bool& b : io.MouseDown) b = false;
    feed_mouse(q, io);
    ImGui::NewFrame();
    clicks += ImGui::IsMouseClicked(0);
    if (ImGui::IsMouseReleased(0)) released_over_it = io.MousePos.x == 200 && io.MousePos.y == 120;
    ImGui::EndFrame();
  }
  EXPECT_EQ(clicks, 1);
  EXPECT_TRUE(released_over_it);
}

// Two quick clicks inside one frame are two clicks, one per frame pair, never one.
TEST(InputQueue, TwoClicksInOneFrameAreTwoClicks) {
  imgui_context ctx;
  input_queue q;
  q.push_move(50, 50);
  frame_mouse(q, ImVec2(50, 50));
  for (int i = 0; i < 2; ++i) q.push_button(0, true, 50, 50), q.push_button(0, false, 50, 50);
  int clicks = 0;
  for (int frame = 0; frame < 8; ++frame) clicks += frame_mouse(q, ImVec2(50, 50)).clicked;
  EXPECT_EQ(clicks, 2);
}

// A held key's system repeats are marked, so that undo can take one step per press.
TEST(InputQueue, SystemRepeatsAreMarked) {
  imgui_context ctx;
  input_queue q;
  q.push_key(GLFW_KEY_Z, GLFW_PRESS);
  q.push_key(GLFW_KEY_Z, GLFW_REPEAT);
  EXPECT_TRUE(frame_presses(q, GLFW_KEY_Z));
  EXPECT_FALSE(q.is_repeat(GLFW_KEY_Z));
  EXPECT_TRUE(frame_presses(q, GLFW_KEY_Z));
  EXPECT_TRUE(q.is_repeat(GLFW_KEY_Z));
  EXPECT_FALSE(frame_presses(q, GLFW_KEY_Z));
  EXPECT_FALSE(q.is_repeat(GLFW_KEY_Z));
}

// A quick click into a text field and typing straight after it, all before the next frame: the
// characters wait until the click has reached ImGui, so the field is active when they arrive.
TEST(InputQueue, TypingAfterAClickWaitsForTheClick) {
  imgui_context ctx;
  input_queue q;
  q.push_move(10, 10);
  frame_mouse(q, ImVec2(10, 10));
  q.push_move(120, 40);
  q.push_button(0, true, 120, 40);
  q.push_button(0, false, 120, 40);
  q.push_key(GLFW_KEY_K, GLFW_PRESS);
  q.push_char('k');
  q.push_key(GLFW_KEY_K, GLFW_RELEASE);
  int frames_before_the_char = 0;
  for (int frame = 0; frame < 10; ++frame) {
    ImGuiIO& io = ImGui::GetIO();
    feed_imgui(q, io);
    const bool got_char = io.InputQueueCharacters.Size > 0;
    io.MousePos = ImVec2(120, 40);
    for (bool& b : io.MouseDown) b = false;
    feed_mouse(q, io);
    if (got_char) {
      EXPECT_TRUE(q.mouse.empty());   // the press and the release went first
      break;
    }
    ++frames_before_the_char;
    ImGui::NewFrame();
    ImGui::EndFrame();
  }
  EXPECT_EQ(frames_before_the_char, 3);   // the move, the press, the release
}
