// Where a dynamic object is at a time, and the scene with the objects placed in it.
#include <radiosity/scene.h>

#include <algorithm>
#include <glm/gtc/matrix_transform.hpp>

namespace rad {

namespace {

// The value of one field of the path at `seconds`: linear between the keyframes that set it,
// held before the first and after the last; `fallback` when none sets it.
template <class Field>
Vec3 track(const std::vector<ObjectKeyframe>& path, double seconds, Field field, Vec3 fallback) {
  const ObjectKeyframe* before = nullptr;
  const ObjectKeyframe* after = nullptr;
  for (const ObjectKeyframe& k : path) {
    if (!(k.*field)) continue;
    if (k.t <= seconds) before = &k;
    if (k.t >= seconds && !after) after = &k;
  }
  if (!before && !after) return fallback;
  if (!before) return *(after->*field);
  if (!after || after == before) return *(before->*field);
  const float s = float((seconds - before->t) / (after->t - before->t));
  return glm::mix(*(before->*field), *(after->*field), s);
}

}  // namespace

glm::mat4 DynamicObject::placementAt(double seconds) const {
  const Vec3 position = track(path, seconds, &ObjectKeyframe::position, Vec3(0.0f));
  const Vec3 a = glm::radians(track(path, seconds, &ObjectKeyframe::rotationDeg, Vec3(0.0f)));
  return glm::translate(glm::mat4(1.0f), position) *
         glm::rotate(glm::mat4(1.0f), a.z, Vec3(0, 0, 1)) *
         glm::rotate(glm::mat4(1.0f), a.y, Vec3(0, 1, 0)) *
         glm::rotate(glm::mat4(1.0f), a.x, Vec3(1, 0, 0));
}

Scene Scene::withDynamicObjectsAt(double seconds) const {
  Scene out = *this;
  out.dynamicObjects.clear();
  out.staticTriangles = uint32_t(triangles.size());
  for (const DynamicObject& object : dynamicObjects) {
    const Scene& part = *object.mesh;
    const glm::mat4 m = object.placementAt(seconds);
    const glm::mat3 turn(m);  // a rotation: normals turn as positions do
    const uint32_t vertexBase = uint32_t(out.positions.size());
    const uint32_t triangleBase = uint32_t(out.triangles.size());
    const uint32_t faceBase = uint32_t(out.faces.size());
    const uint32_t materialBase = uint32_t(out.materials.size());
    const uint32_t objectIndex = uint32_t(out.objects.size());
    out.objects.push_back({object.name});
    for (Material material : part.materials) {
      if (object.rho) material.rho = *object.rho;
      // Without coordinates of its own, or in a scene without any, a texture is its mean.
      if (material.rhoTexture && (object.rho || part.texcoords.empty() || texcoords.empty())) {
        if (!object.rho) material.rho *= material.rhoTexture.texture->mean();
        material.rhoTexture = {};
      }
      if (material.alphaTexture && (part.texcoords.empty() || texcoords.empty())) {
        material.alpha *= material.alphaTexture.texture->meanAlpha();
        material.alphaTexture = {};
      }
      material.emission = Color(0.0f);  // a moving object lights the scene by its reflection only
      material.emissionTexture = {};
      material.name = object.name + "/" + material.name;
      out.materials.push_back(material);
    }
    for (const Vec3& p : part.positions) out.positions.push_back(Vec3(m * glm::vec4(p, 1.0f)));
    // Texture coordinates stay one per position, where the scene has them: the part's own, or
    // (0, 0) for a part without (whose textures became their means).
    if (!out.texcoords.empty()) {
      if (part.texcoords.empty())
        out.texcoords.resize(out.positions.size(), Vec2(0.0f));
      else
        out.texcoords.insert(out.texcoords.end(), part.texcoords.begin(), part.texcoords.end());
    }
    // Vertex alpha likewise, 1 where a scene or part has none.
    if (!out.vertexAlpha.empty() || !part.vertexAlpha.empty()) {
      out.vertexAlpha.resize(vertexBase, 1.0f);
      out.vertexAlpha.insert(out.vertexAlpha.end(), part.vertexAlpha.begin(),
                             part.vertexAlpha.end());
      out.vertexAlpha.resize(out.positions.size(), 1.0f);
    }
    for (const UVec3& t : part.triangles) out.triangles.push_back(t + UVec3(vertexBase));
    for (uint32_t f : part.triangleFace) out.triangleFace.push_back(f + faceBase);
    for (Face face : part.faces) {
      face.object = objectIndex;
      face.material += materialBase;
      face.firstTriangle += triangleBase;
      for (uint32_t& c : face.corners) c += vertexBase;
      face.normal = glm::normalize(turn * face.normal);
      out.faces.push_back(std::move(face));
    }
  }
  return out;
}

}  // namespace rad
