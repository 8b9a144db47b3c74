// Ray queries on Embree 3 (Wald et al., "Embree: A Kernel Framework for Efficient CPU Ray
// Tracing", SIGGRAPH 2014). One triangle geometry, high-quality BVH, robust (watertight) mode;
// in a scene with materials that are not opaque, their triangles are a second geometry whose
// filter functions let rays through where the coverage says (CoverageFilter), so that the
// opaque triangles keep Embree's plain path.
#include <embree3/rtcore.h>
#include <fmt/format.h>
#include <radiosity/ray_caster.h>
#include <spdlog/spdlog.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/info.h>

#include <algorithm>
#include <array>
#include <cstring>
#include <mutex>
#include <new>
#include <stdexcept>
#include <string>
#include <vector>

#include "geometry/coverage_filter.h"

namespace rad {

namespace {

// Embree calls this from inside its C API, where an exception must not unwind; the message is
// kept and thrown by the caller (checkDevice) once Embree has returned.
struct ErrorLog {
  std::mutex mutex;
  std::string message;
};

void onEmbreeError(void* userPtr, RTCError code, const char* text) {
  auto* log = static_cast<ErrorLog*>(userPtr);
  spdlog::error("Embree error {}: {}", int(code), text ? text : "");
  std::lock_guard lock(log->mutex);
  if (log->message.empty()) log->message = fmt::format("Embree error {}: {}", int(code), text);
}

RTCRay toEmbree(const Ray& r) {
  RTCRay e;
  e.org_x = r.origin.x;
  e.org_y = r.origin.y;
  e.org_z = r.origin.z;
  e.tnear = r.tNear;
  e.dir_x = r.direction.x;
  e.dir_y = r.direction.y;
  e.dir_z = r.direction.z;
  e.time = 0.0f;
  e.tfar = r.tFar;
  e.mask = ~0u;
  e.id = 0;
  e.flags = 0;
  return e;
}

RTCRayHit toEmbreeHit(const Ray& r) {
  RTCRayHit e;
  e.ray = toEmbree(r);
  e.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  e.hit.primID = RTC_INVALID_GEOMETRY_ID;
  e.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  return e;
}

// Batches go to Embree in chunks that fit on the stack.
constexpr size_t kChunk = 256;

// Embree's filter for the geometry of triangles that are not opaque (both queries): a hit the
// coverage lets through is no hit, and the traversal goes on.
void coverageFilter(const RTCFilterFunctionNArguments* args) {
  const auto* filter = static_cast<const CoverageFilter*>(args->geometryUserPtr);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] != -1) continue;
    RTCRayN* r = args->ray;
    RTCHitN* h = args->hit;
    const unsigned n = args->N;
    const Vec3 origin(RTCRayN_org_x(r, n, i), RTCRayN_org_y(r, n, i), RTCRayN_org_z(r, n, i));
    const Vec3 direction(RTCRayN_dir_x(r, n, i), RTCRayN_dir_y(r, n, i), RTCRayN_dir_z(r, n, i));
    const Vec2 b(RTCHitN_u(h, n, i), RTCHitN_v(h, n, i));
    if (!filter->meets(RTCHitN_primID(h, n, i), b, origin, direction)) args->valid[i] = 0;
  }
}

}  // namespace

struct RayCaster::Impl {
  ErrorLog errors;
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  std::vector<Vec3> normals;
  /// In a scene with coverage: the scene triangle of each primitive, by geometry (0: the opaque
  /// ones, 1: the others); empty: one geometry of every triangle in order.
  std::array<std::vector<uint32_t>, 2> triangleOf;
  bool mapped = false;
  std::unique_ptr<CoverageFilter> coverage;
  tbb::enumerable_thread_specific<uint64_t, tbb::cache_aligned_allocator<uint64_t>,
                                  tbb::ets_key_per_instance>
      rays{uint64_t(0)};

  ~Impl() {
    if (scene) rtcReleaseScene(scene);
    if (device) rtcReleaseDevice(device);
  }

  void checkDevice(const char* step) {
    const RTCError code = rtcGetDeviceError(device);
    std::lock_guard lock(errors.mutex);
    if (code == RTC_ERROR_NONE && errors.message.empty()) return;
    throw std::runtime_error(fmt::format(
        "ray caster: {} failed: {}", step,
        errors.message.empty() ? "Embree error " + std::to_string(int(code)) : errors.message));
  }

  void build(const Scene& s);
  void attach(const Scene& s, std::span<const uint32_t> triangles, unsigned id);
  Hit toHit(const RTCRayHit& e, const Vec3& direction) const;
};

// The triangle geometry `id` of `triangles` of the scene (all of them, in order, where empty),
// with the coverage filter where it is geometry 1.
void RayCaster::Impl::attach(const Scene& s, std::span<const uint32_t> triangles, unsigned id) {
  const size_t count = triangles.empty() ? s.triangles.size() : triangles.size();
  RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
  rtcSetGeometryBuildQuality(geometry, RTC_BUILD_QUALITY_HIGH);
  // Embree-owned copies: they carry the padding Embree's vector loads need.
  auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(
      geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, sizeof(Vec3), s.positions.size()));
  auto* indices = static_cast<UVec3*>(rtcSetNewGeometryBuffer(
      geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, sizeof(UVec3), count));
  checkDevice("allocating the geometry");
  std::memcpy(vertices, s.positions.data(), s.positions.size() * sizeof(Vec3));
  if (triangles.empty())
    std::memcpy(indices, s.triangles.data(), count * sizeof(UVec3));
  else
    for (size_t k = 0; k < count; ++k) indices[k] = s.triangles[triangles[k]];
  if (id == 1) {
    coverage = std::make_unique<CoverageFilter>(s, triangles);
    rtcSetGeometryUserData(geometry, coverage.get());
    rtcSetGeometryIntersectFilterFunction(geometry, coverageFilter);
    rtcSetGeometryOccludedFilterFunction(geometry, coverageFilter);
  }
  rtcCommitGeometry(geometry);
  rtcAttachGeometryByID(scene, geometry, id);
  rtcReleaseGeometry(geometry);
}

void RayCaster::Impl::build(const Scene& s) {
  // Embree schedules its BVH build on TBB; give it as many threads as TBB would use.
  const std::string config = fmt::format("threads={}", tbb::info::default_concurrency());
  device = rtcNewDevice(config.c_str());
  if (!device) {
    // Without memory for its thread pool Embree fails here: the run is out of memory.
    if (rtcGetDeviceError(nullptr) == RTC_ERROR_OUT_OF_MEMORY) throw std::bad_alloc();
    throw std::runtime_error("ray caster: cannot create the Embree device");
  }
  rtcSetDeviceErrorFunction(device, onEmbreeError, &errors);

  scene = rtcNewScene(device);
  rtcSetSceneFlags(scene, RTC_SCENE_FLAG_ROBUST);
  rtcSetSceneBuildQuality(scene, RTC_BUILD_QUALITY_HIGH);
  if (!s.hasCoverage()) {
    if (!s.triangles.empty()) attach(s, {}, 0);
  } else {
    mapped = true;
    for (uint32_t t = 0; t < s.triangles.size(); ++t)
      triangleOf[s.materialOf(t).opaque() ? 0 : 1].push_back(t);
    for (unsigned g = 0; g < 2; ++g)
      if (!triangleOf[g].empty()) attach(s, triangleOf[g], g);
  }
  rtcCommitScene(scene);
  checkDevice("building the BVH");

  normals.resize(s.triangles.size());
  for (uint32_t t = 0; t < s.triangles.size(); ++t) normals[t] = s.triangleNormal(t);
}

Hit RayCaster::Impl::toHit(const RTCRayHit& e, const Vec3& direction) const {
  Hit hit;
  if (e.hit.geomID == RTC_INVALID_GEOMETRY_ID) return hit;
  hit.triangle = mapped ? triangleOf[e.hit.geomID][e.hit.primID] : e.hit.primID;
  hit.distance = e.ray.tfar;
  hit.barycentric = Vec2(e.hit.u, e.hit.v);
  hit.geometricNormal = normals[hit.triangle];
  hit.frontFace = glm::dot(direction, hit.geometricNormal) < 0.0f;
  return hit;
}

RayCaster::RayCaster(const Scene& scene) : impl_(std::make_unique<Impl>()) {
  impl_->build(scene);
}
RayCaster::~RayCaster() = default;
RayCaster::RayCaster(RayCaster&&) noexcept = default;
RayCaster& RayCaster::operator=(RayCaster&&) noexcept = default;

Hit RayCaster::intersect(const Ray& ray) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit e = toEmbreeHit(ray);
  rtcIntersect1(impl_->scene, &context, &e);
  ++impl_->rays.local();
  return impl_->toHit(e, ray.direction);
}

bool RayCaster::occluded(const Ray& ray) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRay e = toEmbree(ray);
  rtcOccluded1(impl_->scene, &context, &e);
  ++impl_->rays.local();
  // Embree marks an occluded ray by setting tfar to -inf.
  return e.tfar < 0.0f;
}

void RayCaster::intersect(std::span<const Ray> rays, std::span<Hit> hits) const {
  if (rays.size() != hits.size())
    throw std::invalid_argument("RayCaster::intersect: rays and hits differ in length");
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  std::array<RTCRayHit, kChunk> chunk;
  for (size_t first = 0; first < rays.size(); first += kChunk) {
    const size_t n = std::min(kChunk, rays.size() - first);
    for (size_t i = 0; i < n; ++i) chunk[i] = toEmbreeHit(rays[first + i]);
    rtcIntersect1M(impl_->scene, &context, chunk.data(), unsigned(n), sizeof(RTCRayHit));
    for (size_t i = 0; i < n; ++i)
      hits[first + i] = impl_->toHit(chunk[i], rays[first + i].direction);
  }
  impl_->rays.local() += rays.size();
}

void RayCaster::occluded(std::span<const Ray> rays, std::span<uint8_t> occluded) const {
  if (rays.size() != occluded.size())
    throw std::invalid_argument("RayCaster::occluded: rays and results differ in length");
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  std::array<RTCRay, kChunk> chunk;
  for (size_t first = 0; first < rays.size(); first += kChunk) {
    const size_t n = std::min(kChunk, rays.size() - first);
    for (size_t i = 0; i < n; ++i) chunk[i] = toEmbree(rays[first + i]);
    rtcOccluded1M(impl_->scene, &context, chunk.data(), unsigned(n), sizeof(RTCRay));
    for (size_t i = 0; i < n; ++i) occluded[first + i] = chunk[i].tfar < 0.0f ? 1 : 0;
  }
  impl_->rays.local() += rays.size();
}

uint64_t RayCaster::raysCast() const {
  return impl_->rays.combine([](uint64_t a, uint64_t b) { return a + b; });
}

}  // namespace rad
