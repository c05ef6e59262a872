// The exact reference: the first hit of each float ray against the float triangles, computed in
// exact arithmetic (CGAL). Every method is judged against it, Embree too. Candidates come from
// CGAL's AABB tree with exact predicates (the ray meets the closed triangle, boundary included);
// their distances are exact rationals (GMP), so triangles hit at exactly the same distance
// (shared edges and vertices) are ties, and each of them is a correct answer.
#pragma once
#include <cstdint>
#include <memory>
#include <vector>

#include "kernels/gpu_layout.h"
#include "scene/mesh.h"

namespace rtbench {

struct ExactHit {
    double t = 0.0;                         // the exact first-hit distance, rounded to double (0: miss)
    std::uint32_t primitive = gpu::kNoHit;  // the lowest-numbered triangle hit at that distance
    std::uint32_t tieCount = 0;             // triangles hit at exactly that distance (1: no tie)
    std::uint32_t tieFirst = 0;             // their ids, increasing: ExactHits::ties[tieFirst, +tieCount)
};

struct ExactHits {
    std::vector<std::uint32_t> rays;   // the sampled ray indices, increasing
    std::vector<ExactHit> hits;        // hits[i] belongs to ray rays[i]
    std::vector<std::uint32_t> ties;   // triangle ids of every hit's tie set
    double ms = 0.0;                   // wall time of the exact tracing

    // Whether `primitive` is one of the triangles sample i's ray hits first.
    bool isFirstHit(std::size_t i, std::uint32_t primitive) const;
    // A closest-hit answer `primitive` (kNoHit: a miss) for sample i's ray, judged: right, or which
    // way wrong. primitivesCompared false: by hit or miss alone (an any-hit answer, a simplified scene).
    enum class Verdict { Right, FalseMiss, FalseHit, WrongPrimitive };
    Verdict judge(std::size_t i, std::uint32_t primitive, bool primitivesCompared) const;
};

// A deterministic sample of ray indices: every ray if maxRays is 0 or at least rayCount, else
// maxRays rays at an even stride (ceil(rayCount / maxRays)) from ray 0, spread over the image.
std::vector<std::uint32_t> sampleRays(std::size_t rayCount, std::uint64_t maxRays);

class ExactReference {
public:
    // Builds CGAL's AABB tree over the triangles that are not degenerate in exact arithmetic
    // (collinear vertices: a segment, which no method hits either).
    explicit ExactReference(const TriangleMesh& mesh);
    ~ExactReference();
    ExactReference(const ExactReference&) = delete;
    ExactReference& operator=(const ExactReference&) = delete;

    // The exact first hit of one ray in [tMin, tMax); appends its tie set to `ties`.
    ExactHit trace(const gpu::Ray& ray, std::vector<std::uint32_t>& ties) const;
    // The rays of `sample`, in parallel.
    ExactHits trace(const std::vector<gpu::Ray>& rays, const std::vector<std::uint32_t>& sample) const;

private:
    struct Tree;
    std::unique_ptr<Tree> tree_;
};

// A method's hit records judged against the exact reference, on the sampled rays.
struct ExactAccuracy {
    std::uint64_t rays = 0;            // sampled rays
    std::uint64_t falseMisses = 0;     // the exact ray hits; the method missed (a leak)
    std::uint64_t falseHits = 0;       // the exact ray misses; the method hit
    std::uint64_t wrongPrimitive = 0;  // both hit; the method's triangle is not among the exact first hits
    bool primitivesCompared = true;    // false: the method traced other triangles (a simplified scene)
    bool distancesCompared = true;     // false: an any-hit query (its hit is any, not the first)
    std::uint64_t ties = 0;            // rays whose exact first hit is shared by several triangles
    double distanceErrorMean = 0.0;    // |t - t_exact| / t_exact over rays both hit (t_exact > 0)
    double distanceErrorMax = 0.0;

    std::uint64_t wrong() const { return falseMisses + falseHits + wrongPrimitive; }
    double wrongPerMillion() const { return rays ? 1e6 * double(wrong()) / double(rays) : 0.0; }
};

// sameTriangles: the method's triangle i is the reference scene's triangle i (false for a
// simplified scene: then no ray counts as a wrong primitive, and only hit or miss and distance count).
// An any-hit query (gpu::kQueryAny) is judged by hit or miss alone: the ray hits something in
// [tMin, tMax) exactly when its exact first hit there exists; its record names no nearest triangle.
ExactAccuracy compareExact(const std::vector<gpu::HitRecord>& hits, const ExactHits& exact, bool sameTriangles = true,
                           std::uint32_t query = gpu::kQueryClosest);

}  // namespace rtbench
