// Entry point: `sylva params|export|bench ...` runs headless, anything else opens the editor.
#include <cstdio>

#include <malloc.h>
#include <new>
#include <string>

#include "app/cli/cli.h"
#include "app/editor/editor.h"

int main(int argc, char** argv) {
  // Regrowing on every slider move allocates and frees the same large arrays again and again; keep
  // them in the heap instead of returning them to the kernel each time (halves mesh time).
  mallopt(M_MMAP_THRESHOLD, 256 << 20);
  mallopt(M_TRIM_THRESHOLD, 256 << 20);
  try {
    if (argc >= 2 && (sylva::is_cli_command(argv[1]) || argv[1][0] == '-')) return sylva::run_cli(argc, argv);
    if (argc > 2) {
      std::fprintf(stderr, "sylva: expected at most one preset, got %d arguments (see sylva --help)\n", argc - 1);
      return 2;
    }
    return sylva::run_editor(argc == 2 ? argv[1] : "");
  } catch (const std::bad_alloc&) {   // the last line of defence: every bound and budget missed it
    std::fprintf(stderr, "sylva: out of memory: lower the node cap, the steps, the mesh settings (radial_segments, "
                         "curve_rings) or the mesh budget (mesh_budget)\n");
    return 1;
  }
}
