// The CPU baseline: Embree 3 in robust mode tracing the bit-identical rays the kernels trace.
#pragma once
#include <embree3/rtcore.h>

#include <string>
#include <vector>

#include "kernels/gpu_layout.h"
#include "scene/mesh.h"

namespace rtbench {

enum class EmbreeMode { Intersect1, Intersect16 };  // one ray at a time, or packets of 16

// An any-hit record from Embree: the ray is occluded by a triangle it does not name.
constexpr std::uint32_t kOccluded = gpu::kNoHit - 1;

class EmbreeReference {
public:
    // deviceConfig: Embree's device config string, e.g. "isa=avx2" (Debian's 3.13 crashes with
    // its default ISA on some AVX-512 machines). Builds a RTC_SCENE_FLAG_ROBUST scene. Throws
    // rtbench::Error for a scene outside the range of scene/scene_limits.h.
    EmbreeReference(const TriangleMesh& mesh, const std::string& deviceConfig);
    ~EmbreeReference();
    EmbreeReference(const EmbreeReference&) = delete;
    EmbreeReference& operator=(const EmbreeReference&) = delete;

    // Traces all rays (TBB parallel_for over chunks); returns wall time in ms. The closest-hit
    // query (rtcIntersect1/16): hits[i] gets t, primitive and barycentrics (work counters 0); t =
    // kNoHitT, primitive = kNoHit on a miss. The any-hit query (rtcOccluded1/16): an occluded
    // ray gets primitive kOccluded (Embree names no triangle), t = 0. Throws rtbench::Error,
    // before tracing, for a ray outside the range of scene_limits.h.
    double trace(const std::vector<gpu::Ray>& rays, EmbreeMode mode, std::vector<gpu::HitRecord>& hits,
                 std::uint32_t query = gpu::kQueryClosest);

    double buildMs() const { return buildMs_; }
    // Builds the same kind of scene of `mesh` again on this device, apart from the one it traces,
    // and releases it: its build time in ms, as buildMs() measures it (experiment.build_rounds).
    double timeBuild(const TriangleMesh& mesh) const;
    int threads() const;
    // What Embree reports of the ISA it chose: the widest native packet ("native ray16" ...).
    std::string isa() const;
    static std::string version() { return RTC_VERSION_STRING; }

private:
    void checkDevice(const char* what) const;
    RTCScene buildScene(const TriangleMesh& mesh) const;  // committed, RTC_SCENE_FLAG_ROBUST
    RTCDevice device_ = nullptr;
    RTCScene scene_ = nullptr;
    double buildMs_ = 0.0;
};

}  // namespace rtbench
