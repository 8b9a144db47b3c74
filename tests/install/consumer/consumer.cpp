// A program outside the source tree that finds the installed library with find_package.
#include <radiosity/radiosity.h>

#include <cstdio>

int main() {
  const rad::Scene scene = rad::loadScene("cornell");
  std::printf("cornell: %zu objects, %zu triangles\n", scene.objects.size(),
              scene.triangles.size());
  return scene.objects.size() == 8 ? 0 : 1;
}
