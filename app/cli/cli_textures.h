// `sylva textures`: the archetype texture sets as files, a contact sheet, and their timing.
#pragma once

namespace sylva {

// argv[1] is "textures". Returns the exit code: 0 success, 1 failure, 2 usage error.
int run_textures_cli(int argc, char** argv);

}  // namespace sylva
