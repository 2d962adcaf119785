// libFuzzer: the OBJ envelope reader, then inside tests at fixed points of the unit box.
#include <cstdint>
#include <string>
#include <vector>

#include "generators/space_colonization.h"
#include "tests/fuzz/fuzz_common.h"

using namespace sylva;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size > 1 << 16) return 0;
  static const std::vector<glm::vec3> queries = [] {
    std::vector<glm::vec3> q;
    for (int i = 0; i < 27; ++i) q.push_back(glm::vec3(i % 3, (i / 3) % 3, i / 9) * 0.9f - 0.9f);
    return q;
  }();
  std::vector<bool> inside;
  const std::string e = check_envelope_obj(std::string_view(reinterpret_cast<const char*>(data), size), queries, &inside);
  fuzz_check(!e.empty() || inside.size() == queries.size(), "one answer per query");
  return 0;
}
