// The scripted session: its file, its idle measure and the loop that runs its lines; the commands
// are a table (app/editor/editor_script_commands.cpp).
#include "app/editor/editor_script.h"

#include <cstdio>

#include <sys/resource.h>

namespace sylva::ed {

void idle_mark_start(script_state& sc, uint64_t frames_drawn) {
  if (!sc.idle_pending) return;
  sc.idle_pending = false;
  sc.idle_started = true;
  sc.idle_from = std::chrono::steady_clock::now();
  sc.idle_until = sc.idle_from + std::chrono::duration_cast<std::chrono::steady_clock::duration>(std::chrono::duration<double>(sc.idle_span));
  sc.idle_cpu = process_cpu_seconds();
  sc.idle_frames = frames_drawn;
}

double process_cpu_seconds() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return double(u.ru_utime.tv_sec + u.ru_stime.tv_sec) + 1e-6 * double(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

bool load_script(const std::string& path, script_state& sc, std::string& error) {
  std::string text;
  if (error = read_file(path, text); !error.empty()) return false;
  size_t a = 0;
  while (a <= text.size()) {
    size_t b = text.find('\n', a);
    if (b == std::string::npos) b = text.size();
    sc.lines.push_back(text.substr(a, b - a));
    a = b + 1;
  }
  return true;
}

bool run_script(editor_state& e, script_state& sc) {
  using clock = std::chrono::steady_clock;
  auto fail = [&](const std::string& why) {
    std::fprintf(stderr, "sylva script: FAIL at line %zu (%s): %s\n", sc.next + 1, sc.lines[sc.next].c_str(), why.c_str());
    sc.failed = true;
    return false;
  };
  while (sc.next < sc.lines.size()) {
    const std::string& line = sc.lines[sc.next];
    const size_t sp = line.find(' ');
    const std::string cmd = line.substr(0, sp), arg = sp == std::string::npos ? "" : line.substr(sp + 1);
    script_call call{e, sc, cmd, arg, std::chrono::duration<double>(clock::now() - sc.started_line).count(),
                     e.cur().growth == slot_growth::growing};
    if (!line.empty() && line[0] != '#') {   // (a comment or an empty line does nothing)
      const script_handler run = find_script_command(cmd);
      if (!run) return fail("unknown command");
      if (std::string why = run(call); !why.empty()) return fail(why);
    }
    if (!call.done) return true;
    static const auto script_start = clock::now();
    std::printf("sylva script: ok %s (%.1f s)\n", line.c_str(), std::chrono::duration<double>(clock::now() - script_start).count());
    std::fflush(stdout);
    ++sc.next;
    sc.started_line = clock::now();
    if (sc.frames_left > 0) return true;   // continue after that many frames
  }
  sc.finished = true;
  return false;
}

}  // namespace sylva::ed
