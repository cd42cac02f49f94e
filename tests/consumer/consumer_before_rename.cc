// A consumer written before apps/scene became apps/case: the old include path and the old target
// name (needle::scene) still build, through the installed forwarding headers and an alias.
#include <cstdio>

#include "needle/apps/scene/case_scene.h"

int main(int argc, char** argv) {
  if (argc != 2) return 2;
  const needle::Case c = needle::LoadCase(argv[1]);
  std::printf("%s loads\n", c.title.c_str());
  return 0;
}
