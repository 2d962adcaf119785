// The generator cases the keyframe and pruning tests run over: each generator, the self-organizing
// model in both of its environments.
#pragma once

namespace sylva_test {

struct case_t {
  int generator;
  bool markers;
  const char* name;
};
inline const case_t cases[] = {{0, false, "self_organizing (shadow)"},
                               {0, true, "self_organizing (markers)"},
                               {1, false, "space_colonization"},
                               {2, false, "guiding_vectors"},
                               {3, false, "lsystem (Honda)"}};

}  // namespace sylva_test
