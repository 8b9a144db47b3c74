// Wavefront OBJ/MTL reader on top of tinyobjloader. tinyobjloader accepts almost anything
// (a bad number reads as 0), so both files are first checked line by line here, so that every
// malformed statement is reported with its file and line instead of becoming silent geometry.

#include "scene/io/obj_loader.h"

#include <fmt/format.h>
#include <radiosity/error.h>
#include <radiosity/message_text.h>
#include <tiny_obj_loader.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>
#include <glm/vec4.hpp>
#include <map>
#include <set>

#include "scene/io/text_file.h"
#include "scene/io/texture_files.h"

namespace rad {

namespace {

constexpr size_t kMaxFaceCorners = 255;
// A material library of a million materials is a few hundred MB less than this.
constexpr size_t kMaxMtlFileBytes = size_t(256) << 20;

std::string at(const std::string& path, size_t line) {
  return fmt::format("{}:{}", path, line);
}

/// Line numbers of the statements the geometry is built from, in file order.
struct ObjScan {
  std::vector<size_t> vertexLines;
  std::vector<size_t> faceLines;
  std::vector<std::string> mtllibs;
};

/// Line by line, with the statement's words; comments and blank lines skipped.
template <typename F>
void forEachStatement(const std::string& text, F&& visit) {
  size_t lineNo = 0, start = 0;
  while (start <= text.size()) {
    size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    ++lineNo;
    std::string_view line(text.data() + start, end - start);
    const size_t hash = line.find('#');
    if (hash != std::string_view::npos) line = line.substr(0, hash);
    const std::vector<std::string_view> words = splitWords(line);
    if (!words.empty()) visit(lineNo, words);
    start = end + 1;
  }
}

/// Checks that words[1..] are between minCount and maxCount finite numbers.
std::vector<double> numbers(const std::vector<std::string_view>& words, size_t minCount,
                            size_t maxCount, const std::string& where,
                            const std::string& expected) {
  const size_t count = words.size() - 1;
  if (count < minCount || count > maxCount)
    throw InputError(where, fmt::format("'{}' has {} value{}, expected {}", words[0], count,
                                        count == 1 ? "" : "s", expected));
  std::vector<double> values;
  for (size_t i = 1; i < words.size(); ++i) {
    const std::optional<double> v = parseNumber(words[i]);
    if (!v)
      throw InputError(where, fmt::format("{} is not a number in {} (expected {})",
                                          quotedToken(words[i]), quotedToken(words[0]), expected));
    // The geometry and materials are kept in 32-bit floats: 1e39 is finite only as a double.
    if (!std::isfinite(*v) || !std::isfinite(float(*v)))
      throw InputError(where, fmt::format("'{}' value {} is not finite as a 32-bit float (expected "
                                          "{})",
                                          words[0], quotedToken(words[i]), expected));
    values.push_back(*v);
  }
  return values;
}

/// One index of a face corner: a non-zero integer, negative counting back from the last.
void checkIndex(std::string_view token, size_t available, const std::string& kind,
                const std::string& where) {
  long value = 0;
  auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
  if (ec != std::errc() || end != token.data() + token.size())
    throw InputError(where,
                     fmt::format("face {} index {} is not an integer", kind, quotedToken(token)));
  if (value == 0)
    throw InputError(where,
                     fmt::format("face {} index 0 is invalid (OBJ indices start at 1)", kind));
  const long n = long(available);
  if (value > n || value < -n)
    throw InputError(where, fmt::format("face {} index {} out of range (1..{} or -1..-{} so far)",
                                        kind, value, n, n));
}

void checkFace(const std::vector<std::string_view>& words, size_t v, size_t vt, size_t vn,
               const std::string& where) {
  if (words.size() < 4)
    throw InputError(where,
                     fmt::format("face has {} corners, expected at least 3", words.size() - 1));
  // tinyobjloader keeps a face's corner count in one byte: a longer face would come out mangled.
  if (words.size() - 1 > kMaxFaceCorners)
    throw InputError(where, fmt::format("face has {} corners, at most {} are supported (split or "
                                        "triangulate it in the exporter)",
                                        words.size() - 1, kMaxFaceCorners));
  for (size_t i = 1; i < words.size(); ++i) {
    std::vector<std::string_view> parts;
    std::string_view ref = words[i];
    for (size_t slash; (slash = ref.find('/')) != std::string_view::npos;) {
      parts.push_back(ref.substr(0, slash));
      ref.remove_prefix(slash + 1);
    }
    parts.push_back(ref);
    if (parts.size() > 3)
      throw InputError(where, fmt::format("face corner {} is not v, v/vt, v//vn or v/vt/vn",
                                          quotedToken(words[i])));
    checkIndex(parts[0], v, "vertex", where);
    if (parts.size() > 1 && !parts[1].empty()) checkIndex(parts[1], vt, "texture", where);
    if (parts.size() > 2) checkIndex(parts[2], vn, "normal", where);
  }
}

ObjScan scanObj(const std::string& text, const std::string& path) {
  ObjScan scan;
  size_t vt = 0, vn = 0;
  forEachStatement(text, [&](size_t line, const std::vector<std::string_view>& w) {
    const std::string where = at(path, line);
    if (w[0] == "v") {
      numbers(w, 3, 7, where, "3 finite coordinates (x y z [w] or x y z r g b)");
      scan.vertexLines.push_back(line);
    } else if (w[0] == "vn") {
      numbers(w, 3, 3, where, "3 finite normal components");
      ++vn;
    } else if (w[0] == "vt") {
      numbers(w, 1, 3, where, "1 to 3 finite texture coordinates");
      ++vt;
    } else if (w[0] == "f") {
      checkFace(w, scan.vertexLines.size(), vt, vn, where);
      scan.faceLines.push_back(line);
    } else if (w[0] == "mtllib") {
      if (w.size() < 2) throw InputError(where, "'mtllib' needs a file name");
      for (size_t i = 1; i < w.size(); ++i) scan.mtllibs.emplace_back(w[i]);
    }
  });
  return scan;
}

/// What the MTL libraries say beyond tinyobjloader's reading: which materials state a Kd, and
/// the library of each (its texture paths are relative to it).
struct MtlScan {
  std::set<std::string> withKd;
  std::map<std::string, std::string> directoryOf;
};

/// Checks an MTL library and adds what it says to `scan`.
void scanMtl(const std::string& text, const std::string& path, MtlScan& scan) {
  std::set<std::string>& withKd = scan.withKd;
  std::string current;
  forEachStatement(text, [&](size_t line, const std::vector<std::string_view>& w) {
    const std::string where = at(path, line);
    const std::string key(w[0]);
    if (key == "newmtl") {
      if (w.size() != 2) throw InputError(where, "'newmtl' needs exactly one material name");
      current = std::string(w[1]);
      scan.directoryOf[current] = parentDirectory(path);
    } else if (key == "Ka" || key == "Kd" || key == "Ks" || key == "Ke" || key == "Tf") {
      if (w.size() > 1 && (w[1] == "spectral" || w[1] == "xyz"))
        throw InputError(where, fmt::format("'{} {}' is not supported (expected r g b)", key,
                                            std::string(w[1])));
      const std::vector<double> c = numbers(w, 1, 3, where, "1 or 3 finite numbers (r g b)");
      if (c.size() == 2)
        throw InputError(where, fmt::format("'{}' has 2 values, expected 1 or 3 (r g b)", key));
      for (double x : c) {
        if (key == "Kd" && !(x >= 0.0 && x <= 1.0))
          throw InputError(where, fmt::format("rho (Kd) {} of material {} must be in [0, 1]", x,
                                              quotedToken(current)));
        if (key == "Ke" && x < 0.0)
          throw InputError(where, fmt::format("emission (Ke) {} of material {} must be >= 0", x,
                                              quotedToken(current)));
      }
      if (key == "Kd") withKd.insert(current);
    } else if (key == "Ns" || key == "Ni" || key == "d" || key == "Tr" || key == "illum") {
      numbers(w, 1, 1, where, "1 finite number");
    }
  });
}

// OBJ texture coordinates put v = 0 at the image's bottom; textures here put it at the top: a
// vertex's v is flipped as it is read, and the -o / -s options are turned to act on flipped
// coordinates (v' = s v + o in OBJ's is 1 - v' = s (1 - v) + o in ours).
TextureMap objTextureMap(std::shared_ptr<const Texture> texture,
                         const tinyobj::texture_option_t& option) {
  TextureMap map;
  map.texture = std::move(texture);
  if (option.clamp) map.wrapU = map.wrapV = TextureWrap::ClampToEdge;
  const float su = float(option.scale[0]), sv = float(option.scale[1]);
  map.transform[0] = su;
  map.transform[3] = sv;
  map.transform[4] = float(option.origin_offset[0]);
  map.transform[5] = 1.0f - sv - float(option.origin_offset[1]);
  return map;
}

// Coverage from the MTL's dissolve (Material): `d` (or `Tr`, 1 - d, as tinyobjloader reads it)
// below 1 covers that share of the surface (Blend); a `map_d` cuts out where d times its value
// is below one half (Mask: the cut-out leaves and fences it is made for). The map's alpha
// channel where the image has one (the base colour's RGBA, as exporters often name), else its
// grey level.
void readDissolve(const tinyobj::material_t& m, TextureMap map, Material& mat) {
  mat.alpha = std::clamp(float(m.dissolve), 0.0f, 1.0f);
  if (mat.alpha < 1.0f) mat.alphaMode = AlphaMode::Blend;
  if (!map) return;
  if (!map.texture->hasAlpha()) map.texture = map.texture->greyAsAlpha();
  mat.alphaMode = AlphaMode::Mask;
  mat.alphaTexture = std::move(map);
}

}  // namespace

void loadObj(SceneBuilder& builder, const std::string& path, const glm::mat4& transform) {
  const std::string objText = readTextFile(path, "OBJ file");
  const ObjScan scan = scanObj(objText, path);
  std::string mtlText;
  MtlScan mtl;
  for (const std::string& lib : scan.mtllibs) {
    const std::string mtlPath = resolvePath(parentDirectory(path), lib);
    const std::string text = readTextFile(mtlPath, "MTL file", kMaxMtlFileBytes);
    scanMtl(text, mtlPath, mtl);
    mtlText += text + "\n";
  }
  const std::set<std::string>& withKd = mtl.withKd;

  tinyobj::ObjReaderConfig config;
  config.triangulate = false;
  config.vertex_color = false;
  tinyobj::ObjReader reader;
  if (!reader.ParseFromString(objText, mtlText, config))
    throw InputError(path, "cannot parse OBJ: " + reader.Error());

  const tinyobj::attrib_t& attrib = reader.GetAttrib();
  auto positionOf = [&](size_t i) {
    const glm::vec4 p = transform * glm::vec4(attrib.vertices[3 * i], attrib.vertices[3 * i + 1],
                                              attrib.vertices[3 * i + 2], 1.0f);
    return Vec3(p) / p.w;
  };
  auto lineOf = [&](size_t i) {
    return at(path, i < scan.vertexLines.size() ? scan.vertexLines[i] : 0);
  };
  const uint32_t base = uint32_t(builder.scene().positions.size());
  const bool mapped = !attrib.texcoords.empty();
  if (!mapped)
    for (size_t i = 0; 3 * i + 2 < attrib.vertices.size(); ++i)
      builder.addVertex(positionOf(i), lineOf(i));
  // With texture coordinates a vertex is a (v, vt) pair: one position may carry several (a
  // seam), so vertices are made as the faces name them.
  std::map<std::pair<int, int>, uint32_t> pairVertex;
  auto vertexOf = [&](const tinyobj::index_t& index) -> uint32_t {
    if (!mapped) return base + uint32_t(index.vertex_index);
    const std::pair<int, int> key{index.vertex_index, index.texcoord_index};
    if (auto it = pairVertex.find(key); it != pairVertex.end()) return it->second;
    const size_t i = size_t(index.vertex_index);
    // The scan checked every index; a guard all the same before reading the arrays.
    const bool badVertex = index.vertex_index < 0 || 3 * i + 2 >= attrib.vertices.size();
    const bool badTexcoord = index.texcoord_index >= 0 &&
                             2 * size_t(index.texcoord_index) + 1 >= attrib.texcoords.size();
    if (badVertex || badTexcoord)
      throw InputError(path, "a face's vertex or texture index is out of range");
    const uint32_t v =
        index.texcoord_index < 0
            ? builder.addVertex(positionOf(i), lineOf(i))
            : builder.addVertex(positionOf(i),
                                Vec2(attrib.texcoords[2 * size_t(index.texcoord_index)],
                                     1.0f - attrib.texcoords[2 * size_t(index.texcoord_index) + 1]),
                                lineOf(i));
    pairVertex.emplace(key, v);
    return v;
  };
  TextureFiles textures(builder);
  auto textureMap = [&](const tinyobj::material_t& m, const std::string& name,
                        const tinyobj::texture_option_t& option) {
    if (name.empty()) return TextureMap{};
    const auto dir = mtl.directoryOf.find(m.name);
    const std::string file =
        resolvePath(dir != mtl.directoryOf.end() ? dir->second : parentDirectory(path), name);
    std::shared_ptr<const Texture> texture = textures.file(file, m.name, path);
    return texture ? objTextureMap(std::move(texture), option) : TextureMap{};
  };

  const std::vector<tinyobj::material_t>& mtls = reader.GetMaterials();
  std::vector<int64_t> sceneMaterial(mtls.size(), -1);
  int64_t defaultMaterial = -1;
  size_t facesWithoutMaterial = 0;
  auto materialFor = [&](int id) -> uint32_t {
    if (id < 0 || size_t(id) >= mtls.size()) {
      ++facesWithoutMaterial;
      if (defaultMaterial < 0) defaultMaterial = builder.addMaterial({"default", Color(0.5f)});
      return uint32_t(defaultMaterial);
    }
    if (sceneMaterial[size_t(id)] < 0) {
      const tinyobj::material_t& m = mtls[size_t(id)];
      Material mat;
      mat.name = m.name;
      mat.rho =
          withKd.count(m.name) ? Color(m.diffuse[0], m.diffuse[1], m.diffuse[2]) : Color(0.5f);
      mat.emission = Color(m.emission[0], m.emission[1], m.emission[2]);
      mat.rhoTexture = textureMap(m, m.diffuse_texname, m.diffuse_texopt);
      mat.emissionTexture = textureMap(m, m.emissive_texname, m.emissive_texopt);
      // A texture whose factor the file leaves out multiplies white (MTL: map_Kd scales Kd).
      if (mat.rhoTexture && !withKd.count(m.name)) mat.rho = Color(1.0f);
      readDissolve(m, textureMap(m, m.alpha_texname, m.alpha_texopt), mat);
      sceneMaterial[size_t(id)] = builder.addMaterial(std::move(mat));
    }
    return uint32_t(sceneMaterial[size_t(id)]);
  };

  const bool mirrored = glm::determinant(glm::mat3(transform)) < 0.0f;
  std::map<std::string, uint32_t> objects;
  size_t faceIndex = 0;
  std::vector<uint32_t> corners;
  for (const tinyobj::shape_t& shape : reader.GetShapes()) {
    const std::string name = shape.name.empty() ? fileStem(path) : shape.name;
    auto [it, added] = objects.try_emplace(name, 0);
    if (added) it->second = builder.addObject(name);
    size_t offset = 0;
    for (size_t f = 0; f < shape.mesh.num_face_vertices.size(); ++f) {
      const size_t n = shape.mesh.num_face_vertices[f];
      corners.clear();
      for (size_t k = 0; k < n; ++k) corners.push_back(vertexOf(shape.mesh.indices[offset + k]));
      offset += n;
      if (mirrored) std::reverse(corners.begin(), corners.end());
      const size_t line = faceIndex < scan.faceLines.size() ? scan.faceLines[faceIndex] : 0;
      ++faceIndex;
      const int id = f < shape.mesh.material_ids.size() ? shape.mesh.material_ids[f] : -1;
      builder.addPolygon(corners, materialFor(id), it->second, at(path, line));
    }
  }
  if (facesWithoutMaterial > 0)
    builder.warn(path, fmt::format("{} face{} without a material use the default grey (rho 0.5)",
                                   facesWithoutMaterial, facesWithoutMaterial == 1 ? "" : "s"));
  const size_t noKd = std::count_if(mtls.begin(), mtls.end(), [&](const tinyobj::material_t& m) {
    return !withKd.count(m.name) && m.diffuse_texname.empty();
  });
  if (noKd > 0)
    builder.warn(path,
                 fmt::format("{} material{} without Kd use rho 0.5", noKd, noKd == 1 ? "" : "s"));
}

}  // namespace rad
