// glTF 2.0 reader on top of tinygltf (Khronos glTF 2.0 specification: node hierarchy, accessor
// layout, materials; KHR_materials_emissive_strength for emission above 1).

#define TINYGLTF_IMPLEMENTATION
#define TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#define TINYGLTF_NO_EXTERNAL_IMAGE
#include "scene/io/gltf_loader.h"

#include <fmt/format.h>
#include <radiosity/error.h>
#include <radiosity/ies_profile.h>
#include <radiosity/message_text.h>
#include <tiny_gltf.h>

#include <algorithm>
#include <cstring>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <glm/gtx/transform.hpp>
#include <limits>
#include <set>
#include <tuple>

#include "core/checked_size.h"
#include "core/json_nesting.h"
#include "scene/io/text_file.h"
#include "scene/io/texture_files.h"

namespace rad {

namespace {

// Images are kept encoded as tinygltf hands them over (a data URI's or a bufferView's bytes) and
// decoded by Texture when a material uses them. tinygltf hands over no bytes for an image in a
// file of its own (TINYGLTF_NO_EXTERNAL_IMAGE): only its URI, which textureMap reads.
bool keepEncodedImage(tinygltf::Image* image, const int, std::string*, std::string*, int, int,
                      const unsigned char* bytes, int size, void*) {
  image->image.assign(bytes, bytes + size);
  return true;
}

bool isDataUri(const std::string& uri) {
  return uri.rfind("data:", 0) == 0;
}

TextureWrap wrapOf(int mode) {
  switch (mode) {
    case TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE:
      return TextureWrap::ClampToEdge;
    case TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT:
      return TextureWrap::MirroredRepeat;
    default:
      return TextureWrap::Repeat;
  }
}

// KHR_texture_transform: uv' = T(offset) R(rotation) S(scale) uv, R turning counter-clockwise
// in the extension's (ratified) column-major matrix (cos, -sin; sin, cos).
void applyTextureTransform(const tinygltf::Value& ext, TextureMap& map) {
  auto number = [](const tinygltf::Value& v, double fallback) {
    return v.IsNumber() ? v.GetNumberAsDouble() : fallback;
  };
  const tinygltf::Value& offset = ext.Get("offset");
  const tinygltf::Value& scale = ext.Get("scale");
  const double r = number(ext.Get("rotation"), 0.0);
  const double ox = offset.IsArray() && offset.ArrayLen() == 2 ? number(offset.Get(0), 0.0) : 0.0;
  const double oy = offset.IsArray() && offset.ArrayLen() == 2 ? number(offset.Get(1), 0.0) : 0.0;
  const double sx = scale.IsArray() && scale.ArrayLen() == 2 ? number(scale.Get(0), 1.0) : 1.0;
  const double sy = scale.IsArray() && scale.ArrayLen() == 2 ? number(scale.Get(1), 1.0) : 1.0;
  const double c = std::cos(r), s = std::sin(r);
  const double m[6] = {sx * c, sy * s, -sx * s, sy * c, ox, oy};
  for (int k = 0; k < 6; ++k) map.transform[k] = float(m[k]);
}

std::string oneLine(std::string s) {
  while (!s.empty() && (s.back() == '\n' || s.back() == ' ')) s.pop_back();
  std::replace(s.begin(), s.end(), '\n', ';');
  return s;
}

glm::mat4 localTransform(const tinygltf::Node& node) {
  if (node.matrix.size() == 16) {
    glm::dmat4 m;
    std::copy(node.matrix.begin(), node.matrix.end(), glm::value_ptr(m));  // column-major both
    return glm::mat4(m);
  }
  glm::mat4 t(1.0f), r(1.0f), s(1.0f);
  if (node.translation.size() == 3)
    t = glm::translate(glm::vec3(node.translation[0], node.translation[1], node.translation[2]));
  if (node.rotation.size() == 4)  // glTF stores x, y, z, w
    r = glm::mat4_cast(glm::quat(float(node.rotation[3]), float(node.rotation[0]),
                                 float(node.rotation[1]), float(node.rotation[2])));
  if (node.scale.size() == 3)
    s = glm::scale(glm::vec3(node.scale[0], node.scale[1], node.scale[2]));
  return t * r * s;
}

class GltfReader {
 public:
  GltfReader(SceneBuilder& builder, const tinygltf::Model& model, std::string path)
      : builder_(builder), model_(model), path_(std::move(path)) {}

  void visit(int nodeIndex, const glm::mat4& parent, int depth);
  void finish();

 private:
  std::string at(const std::string& jsonPath) const { return path_ + ": " + jsonPath; }
  const tinygltf::Accessor& accessor(int index, const std::string& where) const;
  /// Start of element 0 and the stride of an accessor, after checking it fits its buffer.
  const unsigned char* elements(const tinygltf::Accessor& a, size_t elementSize, size_t& stride,
                                const std::string& where) const;
  std::vector<Vec3> positions(int index, const std::string& where) const;
  std::vector<Vec2> texcoords(int index, const std::string& where) const;
  std::vector<float> colorAlpha(int index, const std::string& where) const;
  /// alphaMode, alphaCutoff, baseColorFactor's alpha and KHR_materials_transmission into `mat`.
  void readCoverage(const tinygltf::Material& m, const std::string& where, Material& mat);
  /// The texture a material's textureInfo names, or none (after a warning where it cannot be
  /// used); `texCoord` gets the coordinate set it reads.
  TextureMap textureMap(const tinygltf::TextureInfo& info, const std::string& material,
                        const std::string& where, int& texCoord);
  std::vector<uint32_t> indices(int index, const std::string& where) const;
  uint32_t material(int index);
  void addMesh(int meshIndex, const glm::mat4& world, uint32_t object);
  void addCamera(int cameraIndex, const glm::mat4& world, const std::string& where);
  void addLight(const tinygltf::Node& node, const glm::mat4& world, const std::string& where);

  SceneBuilder& builder_;
  const tinygltf::Model& model_;
  std::string path_;
  std::vector<int64_t> materials_;
  std::vector<bool> visited_;
  int64_t defaultMaterial_ = -1;
  size_t skippedPrimitives_ = 0;
  TextureFiles textures_{builder_};
};

const tinygltf::Accessor& GltfReader::accessor(int index, const std::string& where) const {
  if (index < 0 || size_t(index) >= model_.accessors.size())
    throw InputError(at(where), fmt::format("accessor {} does not exist", index));
  const tinygltf::Accessor& a = model_.accessors[size_t(index)];
  if (a.sparse.isSparse) throw InputError(at(where), "sparse accessors are not supported");
  return a;
}

const unsigned char* GltfReader::elements(const tinygltf::Accessor& a, size_t elementSize,
                                          size_t& stride, const std::string& where) const {
  if (a.bufferView < 0 || size_t(a.bufferView) >= model_.bufferViews.size())
    throw InputError(at(where), fmt::format("accessor has no valid bufferView ({})", a.bufferView));
  const tinygltf::BufferView& view = model_.bufferViews[size_t(a.bufferView)];
  if (view.buffer < 0 || size_t(view.buffer) >= model_.buffers.size())
    throw InputError(at(where), fmt::format("bufferView refers to missing buffer {}", view.buffer));
  const tinygltf::Buffer& buffer = model_.buffers[size_t(view.buffer)];
  stride = view.byteStride ? view.byteStride : elementSize;
  if (stride < elementSize)
    throw InputError(at(where), fmt::format("bufferView byteStride {} is smaller than an element "
                                            "({} bytes)",
                                            stride, elementSize));
  // Every offset, count and stride is the file's word: the arithmetic must not wrap.
  const std::optional<size_t> viewEnd = checkedAdd(view.byteOffset, view.byteLength);
  const std::optional<size_t> span =
      a.count == 0
          ? std::optional<size_t>(0)
          : checkedAdd(checkedMultiply(a.count - 1, stride).value_or(SIZE_MAX), elementSize);
  const std::optional<size_t> accessorEnd = span ? checkedAdd(a.byteOffset, *span) : std::nullopt;
  if (!viewEnd || *viewEnd > buffer.data.size() || !accessorEnd || *accessorEnd > view.byteLength)
    throw InputError(at(where), fmt::format("accessor of {} elements (offset {}, stride {}) runs "
                                            "past the end of its bufferView ({} bytes at offset {} "
                                            "of a {}-byte buffer)",
                                            a.count, a.byteOffset, stride, view.byteLength,
                                            view.byteOffset, buffer.data.size()));
  return buffer.data.data() + view.byteOffset + a.byteOffset;
}

std::vector<Vec3> GltfReader::positions(int index, const std::string& where) const {
  const tinygltf::Accessor& a = accessor(index, where);
  if (a.type != TINYGLTF_TYPE_VEC3 || a.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT)
    throw InputError(at(where), "POSITION must be a VEC3 of FLOAT");
  size_t stride = 0;
  const unsigned char* data = elements(a, 12, stride, where);
  std::vector<Vec3> out(a.count);
  for (size_t i = 0; i < a.count; ++i) std::memcpy(&out[i], data + i * stride, 12);
  return out;
}

// The bytes of one component of a FLOAT, or normalized UNSIGNED_SHORT or UNSIGNED_BYTE,
// accessor (`size` 4, 2 or 1) as a float.
float normalizedComponent(const unsigned char* p, size_t size) {
  if (size == 4) {
    float v;
    std::memcpy(&v, p, 4);
    return v;
  }
  if (size == 2) {
    uint16_t v;
    std::memcpy(&v, p, 2);
    return float(v) / 65535.0f;
  }
  return float(*p) / 255.0f;
}

// The component size of a FLOAT, or normalized UNSIGNED_SHORT or UNSIGNED_BYTE, accessor; 0 for
// any other.
size_t normalizedComponentSize(const tinygltf::Accessor& a) {
  const int type = a.componentType;
  const size_t size = type == TINYGLTF_COMPONENT_TYPE_FLOAT            ? 4
                      : type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT ? 2
                      : type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE  ? 1
                                                                       : 0;
  return size == 4 || a.normalized ? size : 0;
}

// TEXCOORD_n: FLOAT, or UNSIGNED_BYTE / UNSIGNED_SHORT normalized (glTF 2.0, 3.7.2.1).
std::vector<Vec2> GltfReader::texcoords(int index, const std::string& where) const {
  const tinygltf::Accessor& a = accessor(index, where);
  const size_t component = normalizedComponentSize(a);
  if (a.type != TINYGLTF_TYPE_VEC2 || component == 0)
    throw InputError(at(where),
                     "TEXCOORD must be a VEC2 of FLOAT, or of normalized unsigned "
                     "byte or short");
  size_t stride = 0;
  const unsigned char* data = elements(a, 2 * component, stride, where);
  std::vector<Vec2> out(a.count);
  for (size_t i = 0; i < a.count; ++i)
    for (size_t c = 0; c < 2; ++c)
      out[i][int(c)] = normalizedComponent(data + i * stride + c * component, component);
  return out;
}

// COLOR_0's alpha (1 for a VEC3): the colour itself is not read (materials are diffuse by their
// base colour alone). FLOAT, or UNSIGNED_BYTE / UNSIGNED_SHORT normalized (glTF 2.0, 3.7.2.1).
std::vector<float> GltfReader::colorAlpha(int index, const std::string& where) const {
  const tinygltf::Accessor& a = accessor(index, where);
  const size_t component = normalizedComponentSize(a);
  const bool rgba = a.type == TINYGLTF_TYPE_VEC4;
  if ((!rgba && a.type != TINYGLTF_TYPE_VEC3) || component == 0)
    throw InputError(at(where),
                     "COLOR_0 must be a VEC3 or VEC4 of FLOAT, or of normalized unsigned "
                     "byte or short");
  if (!rgba) return std::vector<float>(a.count, 1.0f);
  size_t stride = 0;
  const unsigned char* data = elements(a, 4 * component, stride, where);
  std::vector<float> out(a.count);
  for (size_t i = 0; i < a.count; ++i)
    out[i] = normalizedComponent(data + i * stride + 3 * component, component);
  return out;
}

TextureMap GltfReader::textureMap(const tinygltf::TextureInfo& info, const std::string& material,
                                  const std::string& where, int& texCoord) {
  texCoord = info.texCoord;
  if (info.index < 0) return {};
  if (size_t(info.index) >= model_.textures.size())
    throw InputError(at(where + "/index"), fmt::format("texture {} does not exist", info.index));
  const tinygltf::Texture& texture = model_.textures[size_t(info.index)];
  if (texture.source < 0 || size_t(texture.source) >= model_.images.size()) {
    builder_.warn(path_, fmt::format("texture {} has no image: material {} keeps its factor",
                                     info.index, quotedToken(material)));
    return {};
  }
  const tinygltf::Image& image = model_.images[size_t(texture.source)];
  const std::string key = fmt::format("{}#image{}", path_, texture.source);
  TextureMap map;
  // A URI is relative to the glTF file and percent-encoded (glTF 2.0, 3.3: URIs, RFC 3986).
  if (!image.uri.empty() && !isDataUri(image.uri))
    map.texture = textures_.file(
        resolvePath(parentDirectory(path_), tinygltf::dlib::urldecode(image.uri)), material, path_);
  else
    map.texture = textures_.encoded(image.image, key, material, path_);
  if (!map.texture) return {};
  if (texture.sampler >= 0 && size_t(texture.sampler) < model_.samplers.size()) {
    map.wrapU = wrapOf(model_.samplers[size_t(texture.sampler)].wrapS);
    map.wrapV = wrapOf(model_.samplers[size_t(texture.sampler)].wrapT);
  }
  if (auto ext = info.extensions.find("KHR_texture_transform"); ext != info.extensions.end()) {
    applyTextureTransform(ext->second, map);
    if (ext->second.Get("texCoord").IsInt())
      texCoord = ext->second.Get("texCoord").GetNumberAsInt();
  }
  return map;
}

std::vector<uint32_t> GltfReader::indices(int index, const std::string& where) const {
  const tinygltf::Accessor& a = accessor(index, where);
  size_t size = 0;
  switch (a.componentType) {
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      size = 1;
      break;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
      size = 2;
      break;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
      size = 4;
      break;
    default:
      throw InputError(at(where), "indices must be unsigned byte, short or int");
  }
  if (a.type != TINYGLTF_TYPE_SCALAR) throw InputError(at(where), "indices must be SCALAR");
  size_t stride = 0;
  const unsigned char* data = elements(a, size, stride, where);
  std::vector<uint32_t> out(a.count);
  for (size_t i = 0; i < a.count; ++i) {
    const unsigned char* p = data + i * stride;
    if (size == 1)
      out[i] = *p;
    else if (size == 2) {
      uint16_t v;
      std::memcpy(&v, p, 2);
      out[i] = v;
    } else
      std::memcpy(&out[i], p, 4);
  }
  return out;
}

uint32_t GltfReader::material(int index) {
  if (index < 0 || size_t(index) >= model_.materials.size()) {
    if (defaultMaterial_ < 0) {
      defaultMaterial_ = builder_.addMaterial({"default", Color(0.5f)});
      builder_.warn(path_, "primitives without a material use the default grey (rho 0.5)");
    }
    return uint32_t(defaultMaterial_);
  }
  materials_.resize(model_.materials.size(), -1);
  if (materials_[size_t(index)] >= 0) return uint32_t(materials_[size_t(index)]);
  const tinygltf::Material& m = model_.materials[size_t(index)];
  const std::string where = fmt::format("/materials/{}", index);
  Material mat;
  mat.name = m.name.empty() ? fmt::format("material{}", index) : m.name;
  const std::vector<double>& base = m.pbrMetallicRoughness.baseColorFactor;
  for (int c = 0; c < 3; ++c) {
    const double v = base.size() >= 3 ? base[size_t(c)] : 1.0;
    if (!(v >= 0.0 && v <= 1.0))
      throw InputError(at(where + "/pbrMetallicRoughness/baseColorFactor"),
                       fmt::format("component {} out of range [0, 1]", v));
    mat.rho[c] = float(v);  // 1 becomes kMaxReflectance in SceneBuilder::addMaterial
  }
  double strength = 1.0;
  if (auto it = m.extensions.find("KHR_materials_emissive_strength"); it != m.extensions.end()) {
    const tinygltf::Value& s = it->second.Get("emissiveStrength");
    if (s.IsNumber()) strength = s.GetNumberAsDouble();
    if (!(strength >= 0.0))
      throw InputError(at(where + "/extensions/KHR_materials_emissive_strength/emissiveStrength"),
                       fmt::format("{} must be >= 0", strength));
  }
  for (int c = 0; c < 3 && m.emissiveFactor.size() == 3; ++c)
    mat.emission[c] = float(m.emissiveFactor[size_t(c)] * strength);
  mat.twoSided = m.doubleSided;
  readCoverage(m, where, mat);
  int rhoSet = 0, emissionSet = 0;
  mat.rhoTexture = textureMap(m.pbrMetallicRoughness.baseColorTexture, mat.name,
                              where + "/pbrMetallicRoughness/baseColorTexture", rhoSet);
  mat.emissionTexture =
      textureMap(m.emissiveTexture, mat.name, where + "/emissiveTexture", emissionSet);
  // Only TEXCOORD_0 is read: a texture on another set shows its mean.
  for (auto [map, factor, set] : {std::tuple{&mat.rhoTexture, &mat.rho, rhoSet},
                                  std::tuple{&mat.emissionTexture, &mat.emission, emissionSet}}) {
    if (!*map || set == 0) continue;
    builder_.warn(path_, fmt::format("material {}: a texture on TEXCOORD_{} (only TEXCOORD_0 is "
                                     "read) shows its mean",
                                     quotedToken(mat.name), set));
    *factor *= map->texture->mean();
    if (map == &mat.rhoTexture) mat.alpha *= map->texture->meanAlpha();
    *map = {};
  }
  if (mat.alphaMode != AlphaMode::Opaque) mat.alphaTexture = mat.rhoTexture;
  materials_[size_t(index)] = builder_.addMaterial(std::move(mat));
  return uint32_t(materials_[size_t(index)]);
}

// Coverage (Material): alphaMode and alphaCutoff (glTF 2.0, 3.9.4), the base colour factor's
// alpha, and thin transmission (KHR_materials_transmission: its factor, times its texture's
// mean, the red channel's, where it has one: exact for a uniform one, the sRGB-decoded texels'
// mean encoded again for others; KHR_materials_ior does not change a thin surface).
void GltfReader::readCoverage(const tinygltf::Material& m, const std::string& where,
                              Material& mat) {
  if (m.alphaMode == "MASK")
    mat.alphaMode = AlphaMode::Mask;
  else if (m.alphaMode == "BLEND")
    mat.alphaMode = AlphaMode::Blend;
  else if (m.alphaMode != "OPAQUE")
    throw InputError(at(where + "/alphaMode"),
                     fmt::format("{} is not OPAQUE, MASK or BLEND", quotedToken(m.alphaMode)));
  mat.alphaCutoff = float(m.alphaCutoff);
  const std::vector<double>& base = m.pbrMetallicRoughness.baseColorFactor;
  if (base.size() == 4) mat.alpha = float(base[3]);
  const auto ext = m.extensions.find("KHR_materials_transmission");
  if (ext == m.extensions.end()) return;
  const tinygltf::Value& factor = ext->second.Get("transmissionFactor");
  if (factor.IsNumber()) mat.transmission = float(factor.GetNumberAsDouble());
  const tinygltf::Value& texture = ext->second.Get("transmissionTexture");
  if (!texture.IsObject() || !texture.Get("index").IsInt()) return;
  tinygltf::TextureInfo info;
  info.index = texture.Get("index").GetNumberAsInt();
  int set = 0;
  if (const TextureMap map = textureMap(info, mat.name,
                                        where + "/extensions/"
                                                "KHR_materials_transmission/transmissionTexture",
                                        set))
    mat.transmission *= linearToSrgb(map.texture->mean().r);  // the file's values are linear
}

void GltfReader::addMesh(int meshIndex, const glm::mat4& world, uint32_t object) {
  const tinygltf::Mesh& mesh = model_.meshes[size_t(meshIndex)];
  const bool mirrored = glm::determinant(glm::mat3(world)) < 0.0f;
  for (size_t p = 0; p < mesh.primitives.size(); ++p) {
    const tinygltf::Primitive& prim = mesh.primitives[p];
    const std::string where = fmt::format("/meshes/{}/primitives/{}", meshIndex, p);
    if (prim.mode != TINYGLTF_MODE_TRIANGLES && prim.mode != -1) {
      ++skippedPrimitives_;
      continue;
    }
    auto pos = prim.attributes.find("POSITION");
    if (pos == prim.attributes.end()) throw InputError(at(where), "primitive has no POSITION");
    const std::vector<Vec3> points = positions(pos->second, where + "/attributes/POSITION");
    std::vector<uint32_t> idx;
    if (prim.indices >= 0) {
      idx = indices(prim.indices, where + "/indices");
    } else {
      idx.resize(points.size());
      for (size_t i = 0; i < idx.size(); ++i) idx[i] = uint32_t(i);
    }
    if (idx.size() % 3 != 0)
      throw InputError(at(where), fmt::format("{} indices is not a multiple of 3", idx.size()));
    const uint32_t base = uint32_t(builder_.scene().positions.size());
    std::vector<Vec2> uv;
    if (auto t = prim.attributes.find("TEXCOORD_0"); t != prim.attributes.end()) {
      uv = texcoords(t->second, where + "/attributes/TEXCOORD_0");
      if (uv.size() != points.size())
        throw InputError(at(where + "/attributes/TEXCOORD_0"),
                         fmt::format("{} coordinates for {} positions", uv.size(), points.size()));
    }
    std::vector<float> alpha;
    if (auto c = prim.attributes.find("COLOR_0"); c != prim.attributes.end()) {
      alpha = colorAlpha(c->second, where + "/attributes/COLOR_0");
      if (alpha.size() != points.size())
        throw InputError(at(where + "/attributes/COLOR_0"),
                         fmt::format("{} colours for {} positions", alpha.size(), points.size()));
    }
    for (size_t i = 0; i < points.size(); ++i) {
      const Vec3 p(world * glm::vec4(points[i], 1.0f));
      const uint32_t v =
          uv.empty() ? builder_.addVertex(p, at(where)) : builder_.addVertex(p, uv[i], at(where));
      if (!alpha.empty()) builder_.setVertexAlpha(v, alpha[i], at(where + "/attributes/COLOR_0"));
    }
    for (size_t i = 0; i < idx.size(); ++i) {
      if (idx[i] >= points.size())
        throw InputError(at(where + "/indices"),
                         fmt::format("index {} out of range ({} vertices)", idx[i], points.size()));
      idx[i] += base;
    }
    if (mirrored)
      for (size_t t = 0; t < idx.size(); t += 3) std::swap(idx[t + 1], idx[t + 2]);
    builder_.addTriangleMesh(idx, material(prim.material), object, at(where));
  }
}

void GltfReader::visit(int nodeIndex, const glm::mat4& parent, int depth) {
  const std::string where = fmt::format("/nodes/{}", nodeIndex);
  if (nodeIndex < 0 || size_t(nodeIndex) >= model_.nodes.size())
    throw InputError(at(where), "node does not exist");
  if (depth > 256) throw InputError(at(where), "node hierarchy deeper than 256 levels");
  // glTF nodes form strict trees: a node reached twice is a cycle, or a shared subtree whose
  // instances could multiply exponentially with depth.
  visited_.resize(model_.nodes.size(), false);
  if (visited_[size_t(nodeIndex)])
    throw InputError(at(where),
                     "node is reached twice (a cycle, or a child of two parents); glTF "
                     "nodes must form strict trees");
  visited_[size_t(nodeIndex)] = true;
  const tinygltf::Node& node = model_.nodes[size_t(nodeIndex)];
  const glm::mat4 world = parent * localTransform(node);
  if (node.mesh >= 0) {
    if (size_t(node.mesh) >= model_.meshes.size())
      throw InputError(at(where + "/mesh"), fmt::format("mesh {} does not exist", node.mesh));
    std::string name = node.name;
    if (name.empty()) name = model_.meshes[size_t(node.mesh)].name;
    if (name.empty()) name = fmt::format("node{}", nodeIndex);
    addMesh(node.mesh, world, builder_.addObject(name));
  }
  if (node.camera >= 0) addCamera(node.camera, world, where + "/camera");
  addLight(node, world, where + "/extensions/KHR_lights_punctual");
  for (int child : node.children) visit(child, world, depth + 1);
}

// A perspective camera looks down its node's -z with +y up (glTF 2.0, 3.10); its yfov is the
// vertical field of view, its aspect ratio (when given) sets the height for our default width.
void GltfReader::addCamera(int cameraIndex, const glm::mat4& world, const std::string& where) {
  if (size_t(cameraIndex) >= model_.cameras.size())
    throw InputError(at(where), fmt::format("camera {} does not exist", cameraIndex));
  const tinygltf::Camera& c = model_.cameras[size_t(cameraIndex)];
  if (c.type != "perspective") {
    builder_.warn(path_,
                  fmt::format("camera {} is {}, not perspective: skipped", cameraIndex, c.type));
    return;
  }
  Camera camera;
  camera.eye = Vec3(world * glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
  camera.target = camera.eye + glm::normalize(glm::mat3(world) * Vec3(0.0f, 0.0f, -1.0f));
  camera.up = glm::normalize(glm::mat3(world) * Vec3(0.0f, 1.0f, 0.0f));
  const double fov = glm::degrees(c.perspective.yfov);
  if (!(fov > 0.0 && fov < 180.0))
    throw InputError(at(fmt::format("/cameras/{}/perspective/yfov", cameraIndex)),
                     fmt::format("{} rad is not a field of view in (0, pi)", c.perspective.yfov));
  camera.fovDeg = float(fov);
  if (c.perspective.aspectRatio > 0.0)
    camera.height = std::max(1, int(std::lround(camera.width / c.perspective.aspectRatio)));
  const std::string name = c.name.empty() ? fmt::format("camera{}", cameraIndex) : c.name;
  builder_.scene().cameras.emplace_back(name, camera);
}

// KHR_lights_punctual: point and spot lights at their node, shining down its -z; intensity in
// candela, converted to W/sr as IES files are (kWattsPerSrPerCandela), colour linear RGB.
// Directional lights shine down their node's -z too, their intensity an illuminance in lux (lm/m^2:
// glTF's unit is the metre), converted at the same efficacy.
void GltfReader::addLight(const tinygltf::Node& node, const glm::mat4& world,
                          const std::string& where) {
  const auto ext = node.extensions.find("KHR_lights_punctual");
  if (ext == node.extensions.end() || !ext->second.Get("light").IsInt()) return;
  const int index = ext->second.Get("light").GetNumberAsInt();
  if (index < 0 || size_t(index) >= model_.lights.size())
    throw InputError(at(where + "/light"), fmt::format("light {} does not exist", index));
  const tinygltf::Light& l = model_.lights[size_t(index)];
  Light light;
  if (l.type == "point") {
    light.type = LightType::Point;
  } else if (l.type == "spot") {
    light.type = LightType::Spot;
    light.innerAngleDeg = float(glm::degrees(l.spot.innerConeAngle));
    light.outerAngleDeg = float(glm::degrees(l.spot.outerConeAngle));
    if (!(light.innerAngleDeg >= 0.0f && light.innerAngleDeg <= light.outerAngleDeg &&
          light.outerAngleDeg > 0.0f && light.outerAngleDeg <= 90.0f))
      throw InputError(at(fmt::format("/extensions/KHR_lights_punctual/lights/{}/spot", index)),
                       "cone angles must satisfy 0 <= inner <= outer <= pi/2");
  } else if (l.type == "directional") {
    light.type = LightType::Directional;
  } else {
    throw InputError(at(fmt::format("/extensions/KHR_lights_punctual/lights/{}/type", index)),
                     fmt::format("unknown light type {} (expected point, spot or directional)",
                                 quotedToken(l.type)));
  }
  Color color(1.0f);
  for (int k = 0; k < 3 && l.color.size() == 3; ++k) color[k] = float(l.color[size_t(k)]);
  light.intensity = color * float(l.intensity * (light.positional() ? kWattsPerSrPerCandela
                                                                    : kWattsPerSquareMetrePerLux));
  if (!(minComponent(light.intensity) >= 0.0f) || !std::isfinite(maxComponent(light.intensity)))
    throw InputError(at(fmt::format("/extensions/KHR_lights_punctual/lights/{}", index)),
                     "intensity and colour must be finite and >= 0");
  light.position = Vec3(world * glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
  light.direction = glm::normalize(glm::mat3(world) * Vec3(0.0f, 0.0f, -1.0f));
  builder_.scene().lights.push_back(light);
}

void GltfReader::finish() {
  if (skippedPrimitives_ > 0)
    builder_.warn(path_, fmt::format("skipped {} non-triangle primitive{} (points or lines)",
                                     skippedPrimitives_, skippedPrimitives_ == 1 ? "" : "s"));
}

std::vector<int> rootNodes(const tinygltf::Model& model) {
  if (!model.scenes.empty()) {
    const int s = model.defaultScene >= 0 && size_t(model.defaultScene) < model.scenes.size()
                      ? model.defaultScene
                      : 0;
    return model.scenes[size_t(s)].nodes;
  }
  std::set<int> children;
  for (const tinygltf::Node& n : model.nodes) children.insert(n.children.begin(), n.children.end());
  std::vector<int> roots;
  for (int i = 0; i < int(model.nodes.size()); ++i)
    if (!children.count(i)) roots.push_back(i);
  return roots;
}

// The JSON of a glTF file: the whole text, or a GLB's first chunk (bounds checked).
std::string_view gltfJson(std::string_view bytes) {
  if (bytes.size() < 20 || bytes.substr(0, 4) != "glTF") return bytes;
  uint32_t chunkLength = 0;
  std::memcpy(&chunkLength, bytes.data() + 12, 4);
  return bytes.substr(20, chunkLength);
}

// External buffers are read with the same size limit as the file, and their URIs are taken
// as they are (tinygltf's default expands them as shell words).
bool readExternalFile(std::vector<unsigned char>* out, std::string* err, const std::string& path,
                      void*) {
  try {
    const std::string bytes = readTextFile(path, "glTF buffer");
    out->assign(bytes.begin(), bytes.end());
    return true;
  } catch (const InputError& e) {
    *err = e.what();
    return false;
  }
}

std::string pathAsWritten(const std::string& path, void*) {
  return path;
}

}  // namespace

void loadGltf(SceneBuilder& builder, const std::string& path, const glm::mat4& transform) {
  // tinygltf takes a 32-bit length.
  const std::string bytes = readTextFile(path, "glTF file", std::numeric_limits<uint32_t>::max());
  const std::string_view json = gltfJson(bytes);
  if (const std::optional<size_t> deep = jsonNestingOverflow(json))
    throw InputError(path, fmt::format("invalid glTF: JSON nested deeper than {} levels (at byte "
                                       "{})",
                                       kMaxJsonNesting, *deep));
  tinygltf::TinyGLTF loader;
  loader.SetImageLoader(&keepEncodedImage, nullptr);
  loader.SetFsCallbacks({&tinygltf::FileExists, &pathAsWritten, &readExternalFile,
                         &tinygltf::WriteWholeFile, nullptr});
  tinygltf::Model model;
  std::string err, warn;
  const bool binary = bytes.size() >= 4 && std::string_view(bytes).substr(0, 4) == "glTF";
  const std::string baseDir = parentDirectory(path);
  const bool ok =
      binary ? loader.LoadBinaryFromMemory(&model, &err, &warn,
                                           reinterpret_cast<const unsigned char*>(bytes.data()),
                                           unsigned(bytes.size()), baseDir)
             : loader.LoadASCIIFromString(&model, &err, &warn, bytes.data(), unsigned(bytes.size()),
                                          baseDir);
  if (!ok || !err.empty())
    throw InputError(path,
                     "invalid glTF: " + (err.empty() ? std::string("cannot parse") : oneLine(err)));
  if (!warn.empty()) builder.warn(path, oneLine(warn));
  GltfReader reader(builder, model, path);
  for (int root : rootNodes(model)) reader.visit(root, transform, 0);
  reader.finish();
}

}  // namespace rad
