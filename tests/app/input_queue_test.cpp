// The editor's keyboard queue: taps shorter than a frame register, held keys repeat at the system rate.
#include <gtest/gtest.h>

#include <GLFW/glfw3.h>
#include <imgui.h>

#include "app/input_queue.h"

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
