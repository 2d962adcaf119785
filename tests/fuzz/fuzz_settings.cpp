// libFuzzer: ~/Sylva/settings.ini as the editor reads it back. Whatever the text, every field read
// lies in its range (so the window can always be made), and the settings save as text that reads
// back to the same settings without a message.
#include <cstdint>
#include <string>

#include "app/editor/editor_settings.h"
#include "tests/fuzz/fuzz_common.h"

using namespace sylva;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  std::vector<std::string> notes;
  const editor_settings s = parse_settings(text, &notes);
  fuzz_check(notes.size() <= 21, "at most 20 messages and a count");
  fuzz_check(s.width == 0 || (s.width >= settings_window_min && s.width <= settings_window_max &&
                              s.height >= settings_window_min && s.height <= settings_window_max),
             "a window read is one that can be made");
  fuzz_check(s.node_budget == 0 || (s.node_budget >= settings_budget_min && s.node_budget <= settings_budget_max),
             "the node budget is in the slider's range");
  fuzz_check(s.recent.size() <= settings_recent_max, "at most 10 recent files");
  for (const std::string& r : s.recent) fuzz_check(check_saved_path(r).empty(), "every recent path is a clean line");
  std::vector<std::string> again;
  fuzz_check(parse_settings(settings_text(s), &again) == s, "settings save and read back equal");
  fuzz_check(again.empty(), "saved settings read back without a message");
  return 0;
}
