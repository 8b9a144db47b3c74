// A complete program against the public API: load a scene, path trace it, write an image.
//   render_scene_example [SCENE] [OUT.png]     (defaults: cornell, render_scene.png)
#include <radiosity/radiosity.h>

#include <cstdio>
#include <exception>

int main(int argc, char** argv) {
  const char* sceneName = argc > 1 ? argv[1] : "cornell";
  const char* output = argc > 2 ? argv[2] : "render_scene.png";
  try {
    rad::Scene scene = rad::loadScene(sceneName);
    rad::requireEmitters(scene);
    rad::Camera camera = scene.cameraOrDefault();
    camera.width = 64;
    camera.height = 64;
    rad::PathTracerSettings settings;
    settings.samplesPerPixel = 16;
    const rad::PathTracedImage result = rad::renderPathTraced(scene, camera, settings);
    rad::writeImage(output, result.image);
    std::printf("%s: %zu triangles, %llu rays, wrote %s\n", sceneName, scene.triangles.size(),
                static_cast<unsigned long long>(result.stats.rays), output);
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "render_scene_example: %s\n", e.what());
    return 1;
  }
}
