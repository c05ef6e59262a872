#include "embree_reference.h"

#include <tbb/blocked_range.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>

#include <chrono>
#include <cstring>
#include <limits>

#include "core/error.h"
#include "scene/scene_limits.h"
#include "strategies/ray_batch.h"

namespace rtbench {

namespace {
const char* errorName(RTCError e) {
    switch (e) {
        case RTC_ERROR_NONE: return "RTC_ERROR_NONE";
        case RTC_ERROR_UNKNOWN: return "RTC_ERROR_UNKNOWN";
        case RTC_ERROR_INVALID_ARGUMENT: return "RTC_ERROR_INVALID_ARGUMENT";
        case RTC_ERROR_INVALID_OPERATION: return "RTC_ERROR_INVALID_OPERATION";
        case RTC_ERROR_OUT_OF_MEMORY: return "RTC_ERROR_OUT_OF_MEMORY";
        case RTC_ERROR_UNSUPPORTED_CPU: return "RTC_ERROR_UNSUPPORTED_CPU";
        case RTC_ERROR_CANCELLED: return "RTC_ERROR_CANCELLED";
    }
    return "RTC_ERROR(?)";
}

gpu::HitRecord toHit(float tfar, unsigned primID, float u, float v, unsigned geomID) {
    gpu::HitRecord h{};
    if (geomID == RTC_INVALID_GEOMETRY_ID) {
        h.t = gpu::kNoHitT;
        h.primitive = gpu::kNoHit;
    } else {
        h.t = tfar;
        h.primitive = primID;
        h.u = u;
        h.v = v;
    }
    return h;
}
}  // namespace

void EmbreeReference::checkDevice(const char* what) const {
    const RTCError e = rtcGetDeviceError(device_);
    if (e != RTC_ERROR_NONE) throw Error(std::string("Embree: ") + what + " failed: " + errorName(e));
}

EmbreeReference::EmbreeReference(const TriangleMesh& mesh, const std::string& deviceConfig) {
    validateSceneRange(mesh);  // Embree silently drops vertices beyond 1.844e18 (FLT_LARGE)
    device_ = rtcNewDevice(deviceConfig.empty() ? nullptr : deviceConfig.c_str());
    if (!device_)
        throw Error("Embree: rtcNewDevice(\"" + deviceConfig + "\") failed: " +
                    errorName(rtcGetDeviceError(nullptr)));
    const auto start = std::chrono::steady_clock::now();
    scene_ = buildScene(mesh);
    buildMs_ = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

RTCScene EmbreeReference::buildScene(const TriangleMesh& mesh) const {
    RTCScene scene = rtcNewScene(device_);
    rtcSetSceneFlags(scene, RTC_SCENE_FLAG_ROBUST);
    RTCGeometry geometry = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(
        geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), mesh.vertices.size()));
    auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
        geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), mesh.triangles.size()));
    checkDevice("rtcSetNewGeometryBuffer");
    std::memcpy(vertices, mesh.vertices.data(), mesh.vertices.size() * sizeof(glm::vec3));
    std::memcpy(indices, mesh.triangles.data(), mesh.triangles.size() * sizeof(glm::uvec3));
    rtcCommitGeometry(geometry);
    rtcAttachGeometry(scene, geometry);
    rtcReleaseGeometry(geometry);
    rtcCommitScene(scene);
    checkDevice("rtcCommitScene");
    return scene;
}

double EmbreeReference::timeBuild(const TriangleMesh& mesh) const {
    const auto start = std::chrono::steady_clock::now();
    RTCScene scene = buildScene(mesh);
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    rtcReleaseScene(scene);
    return ms;
}

EmbreeReference::~EmbreeReference() {
    if (scene_) rtcReleaseScene(scene_);
    if (device_) rtcReleaseDevice(device_);
}

int EmbreeReference::threads() const { return tbb::info::default_concurrency(); }

std::string EmbreeReference::isa() const {
    // Embree 3 exposes no ISA name; its native packet widths tell SSE (4), AVX/AVX2 (8), AVX-512 (16).
    if (rtcGetDeviceProperty(device_, RTC_DEVICE_PROPERTY_NATIVE_RAY16_SUPPORTED)) return "native ray16 (AVX-512)";
    if (rtcGetDeviceProperty(device_, RTC_DEVICE_PROPERTY_NATIVE_RAY8_SUPPORTED)) return "native ray8 (AVX/AVX2)";
    if (rtcGetDeviceProperty(device_, RTC_DEVICE_PROPERTY_NATIVE_RAY4_SUPPORTED)) return "native ray4 (SSE)";
    return "no native packets";
}

namespace {

// An any-hit answer: tfar is -inf when the ray is occluded (rtcOccluded).
gpu::HitRecord toOcclusion(float tfar) {
    gpu::HitRecord h{};
    const bool occluded = tfar == -std::numeric_limits<float>::infinity();
    h.t = occluded ? 0.0f : gpu::kNoHitT;
    h.primitive = occluded ? kOccluded : gpu::kNoHit;
    return h;
}

}  // namespace

double EmbreeReference::trace(const std::vector<gpu::Ray>& rays, EmbreeMode mode,
                              std::vector<gpu::HitRecord>& hits, std::uint32_t query) {
    validateRays(rays);  // Embree asserts (and aborts the process) on origins beyond 1.844e18
    hits.resize(rays.size());
    const std::size_t n = rays.size();
    const bool anyHit = !answersNearest(query);
    const auto start = std::chrono::steady_clock::now();
    if (mode == EmbreeMode::Intersect1) {
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 1024), [&](const auto& range) {
            RTCIntersectContext context;
            rtcInitIntersectContext(&context);
            for (std::size_t i = range.begin(); i != range.end(); ++i) {
                const gpu::Ray& r = rays[i];
                RTCRayHit rh{};
                rh.ray.org_x = r.originTMin.x;
                rh.ray.org_y = r.originTMin.y;
                rh.ray.org_z = r.originTMin.z;
                rh.ray.tnear = r.originTMin.w;
                rh.ray.dir_x = r.directionTMax.x;
                rh.ray.dir_y = r.directionTMax.y;
                rh.ray.dir_z = r.directionTMax.z;
                rh.ray.tfar = r.directionTMax.w;
                rh.ray.mask = 0xFFFFFFFFu;
                rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
                if (anyHit) {
                    rtcOccluded1(scene_, &context, &rh.ray);
                    hits[i] = toOcclusion(rh.ray.tfar);
                } else {
                    rtcIntersect1(scene_, &context, &rh);
                    hits[i] = toHit(rh.ray.tfar, rh.hit.primID, rh.hit.u, rh.hit.v, rh.hit.geomID);
                }
            }
        });
    } else {
        const std::size_t packets = (n + 15) / 16;
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, packets, 64), [&](const auto& range) {
            RTCIntersectContext context;
            rtcInitIntersectContext(&context);
            alignas(64) RTCRayHit16 rh;
            alignas(64) int valid[16];
            for (std::size_t p = range.begin(); p != range.end(); ++p) {
                for (int k = 0; k < 16; ++k) {
                    const std::size_t i = p * 16 + k;
                    valid[k] = i < n ? -1 : 0;
                    const gpu::Ray& r = rays[i < n ? i : n - 1];
                    rh.ray.org_x[k] = r.originTMin.x;
                    rh.ray.org_y[k] = r.originTMin.y;
                    rh.ray.org_z[k] = r.originTMin.z;
                    rh.ray.tnear[k] = r.originTMin.w;
                    rh.ray.dir_x[k] = r.directionTMax.x;
                    rh.ray.dir_y[k] = r.directionTMax.y;
                    rh.ray.dir_z[k] = r.directionTMax.z;
                    rh.ray.tfar[k] = r.directionTMax.w;
                    rh.ray.time[k] = 0.0f;
                    rh.ray.mask[k] = 0xFFFFFFFFu;
                    rh.ray.id[k] = 0;
                    rh.ray.flags[k] = 0;
                    rh.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
                }
                if (anyHit)
                    rtcOccluded16(valid, scene_, &context, &rh.ray);
                else
                    rtcIntersect16(valid, scene_, &context, &rh);
                for (int k = 0; k < 16; ++k) {
                    const std::size_t i = p * 16 + k;
                    if (i >= n) continue;
                    hits[i] = anyHit ? toOcclusion(rh.ray.tfar[k])
                                     : toHit(rh.ray.tfar[k], rh.hit.primID[k], rh.hit.u[k], rh.hit.v[k], rh.hit.geomID[k]);
                }
            }
        });
    }
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    checkDevice(anyHit ? "rtcOccluded" : "rtcIntersect");
    return ms;
}

}  // namespace rtbench
