// Entry point: the editor, or a headless CLI command.
#include <cstdio>

int main(int, char**) {
  std::puts("sylva");
  return 0;
}
