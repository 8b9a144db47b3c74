#include <radiosity/gltf_export.h>

// Only tinygltf's declarations: the implementation is compiled once, in
// src/scene/io/gltf_loader.cpp. These switches must match it there, because TinyGLTF's inline
// constructor takes the addresses of the stb image callbacks unless they are switched off.
#define TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#define TINYGLTF_NO_EXTERNAL_IMAGE
#include <fmt/format.h>
#include <radiosity/atomic_file.h>
#include <tiny_gltf.h>

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <limits>
#include <map>
#include <span>
#include <sstream>
#include <stdexcept>

#include "output/image_formats.h"

namespace rad {

namespace {

constexpr const char* kUnlit = "KHR_materials_unlit";

// glTF COLOR_0 must be in [0, 1]; NaN (which std::clamp would keep) becomes black.
float unitColor(float c) {
  return c > 0.0f ? std::min(c, 1.0f) : 0.0f;
}

Vec3 unitNormal(const Vec3& n) {
  const float length = glm::length(n);
  // The material is unlit, so a stand-in only matters to validators, which demand unit length.
  return length > 0.0f && std::isfinite(length) ? n / length : Vec3(0.0f, 0.0f, 1.0f);
}

class ModelBuilder {
 public:
  ModelBuilder() {
    model_.asset.version = "2.0";
    model_.asset.generator = "radiosity";
    model_.buffers.emplace_back();  // uri left empty: it becomes the .glb's BIN chunk
    model_.scenes.emplace_back();
    model_.defaultScene = 0;
  }

  /// Appends a tightly packed array and an accessor over it; returns the accessor's index.
  template <typename T>
  int accessor(const std::vector<T>& values, int componentType, int type, int target) {
    std::vector<unsigned char>& data = model_.buffers[0].data;
    // Every component here is 4 bytes; images before may leave the buffer unaligned.
    data.resize((data.size() + 3) / 4 * 4, 0);
    tinygltf::BufferView view;
    view.buffer = 0;
    view.byteOffset = data.size();
    view.byteLength = values.size() * sizeof(T);
    view.target = target;
    const auto* bytes = reinterpret_cast<const unsigned char*>(values.data());
    data.insert(data.end(), bytes, bytes + view.byteLength);
    model_.bufferViews.push_back(view);
    tinygltf::Accessor a;
    a.bufferView = int(model_.bufferViews.size()) - 1;
    a.componentType = componentType;
    a.type = type;
    a.count = values.size();
    model_.accessors.push_back(a);
    return int(model_.accessors.size()) - 1;
  }

  int positions(const std::vector<Vec3>& p) {
    const int index = accessor(p, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3,
                               TINYGLTF_TARGET_ARRAY_BUFFER);
    // POSITION accessors must carry their bounds (glTF 2.0, 3.7.2.1).
    Vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
    for (const Vec3& v : p) {
      lo = glm::min(lo, v);
      hi = glm::max(hi, v);
    }
    model_.accessors[index].minValues = {lo.x, lo.y, lo.z};
    model_.accessors[index].maxValues = {hi.x, hi.y, hi.z};
    return index;
  }

  /// The white unlit one-sided material (each side of a surface has triangles of its own),
  /// made on first use.
  int material() {
    if (material_ < 0) material_ = unlitMaterial("radiosity", Color(1.0f), -1, 0);
    return material_;
  }

  /// The unlit material showing texture `index` of `mesh` times its factor on TEXCOORD_0, its
  /// image embedded as PNG, made on first use.
  int texturedMaterial(const LitMesh& mesh, uint32_t index) {
    if (texturedMaterials_.size() < mesh.textures.size())
      texturedMaterials_.resize(mesh.textures.size(), -1);
    if (texturedMaterials_[index] >= 0) return texturedMaterials_[index];
    const LitMeshTexture& t = mesh.textures[index];
    tinygltf::Sampler sampler;
    sampler.wrapS = wrapMode(t.wrapU);
    sampler.wrapT = wrapMode(t.wrapV);
    const int texture = embedTexture(
        t.name, encodePng(t.texture->width(), t.texture->height(), t.texture->srgb8()), sampler);
    return texturedMaterials_[index] = unlitMaterial(t.name, t.factor, texture, 0);
  }

  /// The unlit material showing the lightmap's radiance (x 2^exposureEV, as sRGB) on
  /// TEXCOORD_1, made on first use.
  int lightmapMaterial(const GlbLightmap& lightmap, float exposureEV) {
    if (lightmapMaterial_ >= 0) return lightmapMaterial_;
    // Linear filtering without mipmaps: a mipmap level would blend neighbouring charts.
    tinygltf::Sampler sampler;
    sampler.magFilter = TINYGLTF_TEXTURE_FILTER_LINEAR;
    sampler.minFilter = TINYGLTF_TEXTURE_FILTER_LINEAR;
    sampler.wrapS = sampler.wrapT = TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE;
    const int texture =
        embedTexture("lightmap", encodeTonemappedPng(lightmap.radiance, exposureEV), sampler);
    return lightmapMaterial_ = unlitMaterial("lightmap", Color(1.0f), texture, 1);
  }

  void addNode(const std::string& name, tinygltf::Mesh mesh) {
    mesh.name = name;
    model_.meshes.push_back(std::move(mesh));
    tinygltf::Node node;
    node.name = name;
    node.mesh = int(model_.meshes.size()) - 1;
    model_.nodes.push_back(node);
    model_.scenes[0].nodes.push_back(int(model_.nodes.size()) - 1);
  }

  const tinygltf::Model& model() const { return model_; }
  void setAssetExtras(tinygltf::Value extras) { model_.asset.extras = std::move(extras); }

 private:
  static int wrapMode(TextureWrap wrap) {
    switch (wrap) {
      case TextureWrap::ClampToEdge:
        return TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE;
      case TextureWrap::MirroredRepeat:
        return TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT;
      case TextureWrap::Repeat:
        break;
    }
    return TINYGLTF_TEXTURE_WRAP_REPEAT;
  }

  // A PNG in the buffer with its sampler, as a texture; returns the texture's index.
  int embedTexture(const std::string& name, const std::string& png, tinygltf::Sampler sampler) {
    std::vector<unsigned char>& data = model_.buffers[0].data;
    tinygltf::BufferView view;
    view.buffer = 0;
    view.byteOffset = data.size();
    view.byteLength = png.size();
    data.insert(data.end(), png.begin(), png.end());
    model_.bufferViews.push_back(view);
    tinygltf::Image image;
    image.name = name;
    image.mimeType = "image/png";
    image.bufferView = int(model_.bufferViews.size()) - 1;
    model_.images.push_back(image);
    model_.samplers.push_back(sampler);
    tinygltf::Texture texture;
    texture.source = int(model_.images.size()) - 1;
    texture.sampler = int(model_.samplers.size()) - 1;
    model_.textures.push_back(texture);
    return int(model_.textures.size()) - 1;
  }

  // An unlit material showing `texture` (on TEXCOORD_<texCoord>; -1: none) times `factor`.
  // Viewers without KHR_materials_unlit fall back to a rough dielectric, the closest lit look
  // to baked colours (the extension's own recommendation).
  int unlitMaterial(const std::string& name, Color factor, int texture, int texCoord) {
    tinygltf::Material m;
    m.name = name;
    m.pbrMetallicRoughness.baseColorFactor = {factor.r, factor.g, factor.b, 1.0};
    m.pbrMetallicRoughness.baseColorTexture.index = texture;
    m.pbrMetallicRoughness.baseColorTexture.texCoord = texCoord;
    m.pbrMetallicRoughness.metallicFactor = 0.0;
    m.pbrMetallicRoughness.roughnessFactor = 1.0;
    m.extensions[kUnlit] = tinygltf::Value(tinygltf::Value::Object());
    model_.materials.push_back(m);
    if (model_.extensionsUsed.empty()) model_.extensionsUsed.push_back(kUnlit);
    return int(model_.materials.size()) - 1;
  }

  tinygltf::Model model_;
  int material_ = -1;
  int lightmapMaterial_ = -1;
  std::vector<int> texturedMaterials_;
};

void validate(const LitMesh& mesh, const GlbLightmap* lightmap) {
  auto fail = [](const std::string& what) { throw std::invalid_argument("lit mesh: " + what); };
  const size_t vertices = mesh.positions.size();
  if (mesh.normals.size() != vertices || mesh.colors.size() != vertices)
    fail(fmt::format("{} positions, {} normals and {} colours differ", vertices,
                     mesh.normals.size(), mesh.colors.size()));
  if (mesh.indices.size() % 3 != 0) fail("index count is not a multiple of 3");
  const size_t triangles = mesh.indices.size() / 3;
  for (uint32_t i : mesh.indices)
    if (i >= vertices) fail(fmt::format("index {} out of range ({} vertices)", i, vertices));
  for (const Vec3& p : mesh.positions)
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      fail("a position is not finite");
  for (const LitMeshGroup& g : mesh.groups)
    if (size_t(g.firstTriangle) + g.triangleCount > triangles)
      fail(fmt::format("group '{}' runs past the {} triangles", g.name, triangles));
  if (!mesh.texcoords.empty() && mesh.texcoords.size() != vertices)
    fail(fmt::format("{} texture coordinates for {} vertices", mesh.texcoords.size(), vertices));
  if (!mesh.triangleTextures.empty() && mesh.triangleTextures.size() != triangles)
    fail(fmt::format("{} triangle textures for {} triangles", mesh.triangleTextures.size(),
                     triangles));
  if (!mesh.lightmapTexcoords.empty() && mesh.lightmapTexcoords.size() != vertices)
    fail(fmt::format("{} lightmap coordinates for {} vertices", mesh.lightmapTexcoords.size(),
                     vertices));
  for (uint32_t t : mesh.triangleTextures)
    if (t != LitMesh::kUntextured &&
        (t >= mesh.textures.size() || mesh.texcoords.empty() || !mesh.textures[t].texture))
      fail(fmt::format("texture {} of a triangle does not exist", t));
  if (lightmap && mesh.lightmapTexcoords.empty()) fail("a lightmap without lightmap coordinates");
}

// A group's own vertices (the mesh's, in order of first use) and its triangles over them.
struct GroupVertices {
  std::vector<uint32_t> vertices, indices;
};
GroupVertices groupVertices(const LitMesh& mesh, const LitMeshGroup& group,
                            std::vector<uint32_t>& local) {
  GroupVertices out;
  for (uint32_t t = group.firstTriangle; t < group.firstTriangle + group.triangleCount; ++t) {
    for (int k = 0; k < 3; ++k) {
      const uint32_t v = mesh.indices[3 * size_t(t) + k];
      if (local[v] == ~0u) {
        local[v] = uint32_t(out.vertices.size());
        out.vertices.push_back(v);
      }
      out.indices.push_back(local[v]);
    }
  }
  for (uint32_t v : out.vertices) local[v] = ~0u;  // ready for the next group, no O(V) reset
  return out;
}

// The groups as written: all the triangles in one when the mesh names none.
std::vector<LitMeshGroup> groupsOf(const LitMesh& mesh) {
  if (!mesh.groups.empty()) return mesh.groups;
  return {{"radiosity", 0, uint32_t(mesh.indices.size() / 3)}};
}

// The vertex attributes of a group's mesh, one accessor each (-1: not written).
struct GroupAttributes {
  int position = -1, normal = -1, color = -1, texcoord = -1, lightmap = -1;
};
GroupAttributes groupAttributes(ModelBuilder& builder, const LitMesh& mesh,
                                const std::vector<uint32_t>& vertices, float scale, bool textured,
                                bool lightmapped) {
  std::vector<Vec3> positions, normals, colors;
  std::vector<Vec2> texcoords, lightmap;
  for (uint32_t v : vertices) {
    positions.push_back(mesh.positions[v]);
    normals.push_back(unitNormal(mesh.normals[v]));
    const Color c = mesh.colors[v] * scale;
    colors.emplace_back(unitColor(c.r), unitColor(c.g), unitColor(c.b));
    if (lightmapped) lightmap.push_back(mesh.lightmapTexcoords[v]);
    // glTF's TEXCOORD sets start at 0: without coordinates of its own, the lightmap's again.
    if (textured || lightmapped)
      texcoords.push_back(mesh.texcoords.empty() ? mesh.lightmapTexcoords[v] : mesh.texcoords[v]);
  }
  auto vec = [&](const auto& values, int type) {
    return builder.accessor(values, TINYGLTF_COMPONENT_TYPE_FLOAT, type,
                            TINYGLTF_TARGET_ARRAY_BUFFER);
  };
  GroupAttributes a;
  a.position = builder.positions(positions);
  a.normal = vec(normals, TINYGLTF_TYPE_VEC3);
  if (!lightmapped) a.color = vec(colors, TINYGLTF_TYPE_VEC3);
  if (!texcoords.empty()) a.texcoord = vec(texcoords, TINYGLTF_TYPE_VEC2);
  if (lightmapped) a.lightmap = vec(lightmap, TINYGLTF_TYPE_VEC2);
  return a;
}

// Each group becomes a mesh of its own vertices (so that a node stands alone, e.g. when Blender
// splits the import into objects), a primitive per texture its triangles show (the untextured
// ones last); with a lightmap, one primitive showing it.
void addGroup(ModelBuilder& builder, const LitMesh& mesh, const LitMeshGroup& group,
              float exposureEV, const GlbLightmap* lightmap, std::vector<uint32_t>& local) {
  GroupVertices own = groupVertices(mesh, group, local);
  if (own.vertices.empty()) return;                     // a glTF mesh needs at least one primitive
  std::map<uint32_t, std::vector<uint32_t>> byTexture;  // kUntextured sorts last
  for (uint32_t k = 0; k < group.triangleCount; ++k) {
    const uint32_t texture = mesh.triangleTextures.empty() || lightmap
                                 ? LitMesh::kUntextured
                                 : mesh.triangleTextures[group.firstTriangle + k];
    std::vector<uint32_t>& indices = byTexture[texture];
    indices.insert(indices.end(), own.indices.begin() + 3 * k, own.indices.begin() + 3 * k + 3);
  }
  const GroupAttributes a =
      groupAttributes(builder, mesh, own.vertices, std::exp2(exposureEV),
                      byTexture.begin()->first != LitMesh::kUntextured, lightmap != nullptr);
  tinygltf::Mesh gltfMesh;
  for (const auto& [texture, indices] : byTexture) {
    tinygltf::Primitive p;
    p.attributes = {{"POSITION", a.position}, {"NORMAL", a.normal}};
    if (a.color >= 0) p.attributes["COLOR_0"] = a.color;
    if (a.texcoord >= 0) p.attributes["TEXCOORD_0"] = a.texcoord;
    if (a.lightmap >= 0) p.attributes["TEXCOORD_1"] = a.lightmap;
    p.indices = builder.accessor(indices, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT,
                                 TINYGLTF_TYPE_SCALAR, TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
    if (lightmap)
      p.material = builder.lightmapMaterial(*lightmap, exposureEV);
    else
      p.material = texture == LitMesh::kUntextured ? builder.material()
                                                   : builder.texturedMaterial(mesh, texture);
    p.mode = TINYGLTF_MODE_TRIANGLES;
    gltfMesh.primitives.push_back(p);
  }
  builder.addNode(group.name, std::move(gltfMesh));
}

// What the asset's extras say of the light it carries.
tinygltf::Value bakeDescription(float exposureEV, const GlbLightmap* lightmap) {
  tinygltf::Value::Object baked;
  baked["exposure_ev"] = tinygltf::Value(double(exposureEV));
  if (lightmap) {
    tinygltf::Value::Object atlas;
    atlas["irradiance_uri"] = tinygltf::Value(lightmap->irradianceUri);
    atlas["irradiance"] = tinygltf::Value(std::string(
        "linear irradiance H (W per square scene unit), OpenEXR, on TEXCOORD_1; an engine "
        "multiplies it by albedo / pi"));
    atlas["texcoord"] = tinygltf::Value(1);
    atlas["size"] = tinygltf::Value(lightmap->radiance.width);
    atlas["texels_per_unit"] = tinygltf::Value(double(lightmap->texelsPerUnit));
    atlas["shown"] = tinygltf::Value(
        std::string("the material's base colour texture: outgoing radiance x 2^exposure_ev, sRGB"));
    baked["lightmap"] = tinygltf::Value(atlas);
  } else {
    baked["colors"] = tinygltf::Value(std::string(
        "linear outgoing radiance x 2^exposure_ev, clamped to [0, 1]; under a base colour "
        "texture, irradiance / pi x 2^exposure_ev (the texture times its factor is the albedo)"));
  }
  tinygltf::Value::Object extras;
  extras["radiosity"] = tinygltf::Value(baked);
  return tinygltf::Value(extras);
}

}  // namespace

std::string litMeshGlb(const LitMesh& mesh, float exposureEV, const GlbLightmap* lightmap) {
  validate(mesh, lightmap);
  ModelBuilder builder;
  std::vector<uint32_t> local(mesh.positions.size(), ~0u);
  for (const LitMeshGroup& group : groupsOf(mesh))
    addGroup(builder, mesh, group, exposureEV, lightmap, local);
  builder.setAssetExtras(bakeDescription(exposureEV, lightmap));
  // Serialized in memory (the buffer as the .glb's BIN chunk, compact JSON): tinygltf's file
  // writer does not check its stream, writeBytesAtomically does.
  std::ostringstream glb(std::ios::binary);
  tinygltf::TinyGLTF writer;
  if (!writer.WriteGltfSceneToStream(&builder.model(), glb, false, true))
    throw std::runtime_error("cannot serialize the glTF file");
  return std::move(glb).str();
}

std::vector<uint32_t> glbVertexOrder(const LitMesh& mesh) {
  std::vector<uint32_t> order, local(mesh.positions.size(), ~0u);
  for (const LitMeshGroup& group : groupsOf(mesh)) {
    const GroupVertices own = groupVertices(mesh, group, local);
    order.insert(order.end(), own.vertices.begin(), own.vertices.end());
  }
  return order;
}

void writeLitMeshGlb(const std::string& path, const LitMesh& mesh, float exposureEV,
                     const GlbLightmap* lightmap) {
  std::string bytes;
  try {
    bytes = litMeshGlb(mesh, exposureEV, lightmap);
  } catch (const std::runtime_error& e) {
    throw std::runtime_error(fmt::format("{}: {}", path, e.what()));
  }
  writeBytesAtomically(path, std::span<const char>(bytes.data(), bytes.size()));
}

}  // namespace rad
