#include "exact_reference.h"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Gmpq.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>

#include "strategies/ray_batch.h"

namespace rtbench {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;  // exact predicates
using Rational = CGAL::Gmpq;                                          // exact distances

// Exact 3-vectors of rationals; floats convert to them without rounding.
struct Vec {
    Rational x, y, z;
    const Rational& operator[](int i) const { return i == 0 ? x : i == 1 ? y : z; }
};
Vec exact(glm::vec3 v) { return {Rational(double(v.x)), Rational(double(v.y)), Rational(double(v.z))}; }
Vec operator-(const Vec& a, const Vec& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
Rational dot(const Vec& a, const Vec& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
Vec cross(const Vec& a, const Vec& b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }

// The distances at which a ray in the triangle's plane meets the triangle: an interval
// [enter, exit] of t >= 0. Worked in the plane's projection that drops the normal's largest axis.
std::pair<Rational, Rational> coplanarInterval(const Vec& o, const Vec& d, const Vec (&v)[3], const Vec& n) {
    int drop = 0;
    for (int a = 1; a < 3; ++a)
        if (CGAL::abs(n[a]) > CGAL::abs(n[drop])) drop = a;
    const int i = (drop + 1) % 3, j = (drop + 2) % 3;
    auto cross2 = [&](const Vec& a, const Vec& b) { return a[i] * b[j] - a[j] * b[i]; };
    auto dot2 = [&](const Vec& a, const Vec& b) { return a[i] * b[i] + a[j] * b[j]; };
    std::vector<Rational> ts;
    // The origin inside the closed triangle: the interval starts at 0.
    int negative = 0, positive = 0;
    for (int e = 0; e < 3; ++e) {
        const int s = CGAL::sign(cross2(v[(e + 1) % 3] - v[e], o - v[e]));
        negative += s < 0;
        positive += s > 0;
    }
    if (negative == 0 || positive == 0) ts.push_back(Rational(0));
    for (int e = 0; e < 3; ++e) {
        const Vec& p = v[e];
        const Vec r = v[(e + 1) % 3] - p;
        const Vec po = p - o;
        const Rational denom = cross2(d, r);
        if (denom != 0) {  // the ray's line crosses the edge's line
            const Rational t = cross2(po, r) / denom, s = cross2(po, d) / denom;
            if (s >= 0 && s <= 1 && t >= 0) ts.push_back(t);
        } else if (cross2(po, d) == 0) {  // collinear: the edge's end points
            const Rational dd = dot2(d, d);
            for (const Vec& end : {p, v[(e + 1) % 3]}) {
                const Rational t = dot2(end - o, d) / dd;
                if (t >= 0) ts.push_back(t);
            }
        }
    }
    if (ts.empty()) return {Rational(-1), Rational(-1)};  // CGAL said it hits; never reached
    return {*std::min_element(ts.begin(), ts.end()), *std::max_element(ts.begin(), ts.end())};
}

}  // namespace

struct ExactReference::Tree {
    using Triangles = std::vector<Kernel::Triangle_3>;
    using Primitive = CGAL::AABB_triangle_primitive<Kernel, Triangles::const_iterator>;
    using AabbTree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;
    Triangles triangles;
    std::vector<std::uint32_t> ids;  // mesh triangle of triangles[i]
    std::vector<Vec> vertices;       // the mesh's vertices, exactly
    const TriangleMesh* mesh;
    AabbTree tree;
};

ExactReference::ExactReference(const TriangleMesh& mesh) : tree_(std::make_unique<Tree>()) {
    Tree& t = *tree_;
    t.mesh = &mesh;
    t.vertices.reserve(mesh.vertices.size());
    for (glm::vec3 v : mesh.vertices) t.vertices.push_back(exact(v));
    auto point = [&](std::uint32_t i) {
        const glm::vec3 v = mesh.vertices[i];
        return Kernel::Point_3(double(v.x), double(v.y), double(v.z));
    };
    for (std::uint32_t i = 0; i < mesh.triangles.size(); ++i) {
        const glm::uvec3 tri = mesh.triangles[i];
        Kernel::Triangle_3 triangle(point(tri.x), point(tri.y), point(tri.z));
        if (triangle.is_degenerate()) continue;  // exact collinearity test
        t.triangles.push_back(triangle);
        t.ids.push_back(i);
    }
    t.tree.insert(t.triangles.cbegin(), t.triangles.cend());
    t.tree.build();  // now, not lazily inside concurrent queries
}

ExactReference::~ExactReference() = default;

ExactHit ExactReference::trace(const gpu::Ray& ray, std::vector<std::uint32_t>& ties) const {
    const Tree& tree = *tree_;
    const glm::vec3 origin(ray.originTMin), direction(ray.directionTMax);
    const Kernel::Ray_3 query(Kernel::Point_3(origin.x, origin.y, origin.z),
                              Kernel::Vector_3(direction.x, direction.y, direction.z));
    std::vector<Tree::Triangles::const_iterator> candidates;
    tree.tree.all_intersected_primitives(query, std::back_inserter(candidates));

    const Vec o = exact(origin), d = exact(direction);
    const Rational tMin(double(ray.originTMin.w)), tMax(double(ray.directionTMax.w));
    std::optional<Rational> best;
    std::vector<std::uint32_t> bestIds;
    for (const auto& it : candidates) {
        const std::uint32_t id = tree.ids[std::size_t(it - tree.triangles.cbegin())];
        const glm::uvec3 tri = tree.mesh->triangles[id];
        const Vec v[3] = {tree.vertices[tri.x], tree.vertices[tri.y], tree.vertices[tri.z]};
        const Vec n = cross(v[1] - v[0], v[2] - v[0]);
        const Rational den = dot(n, d);
        Rational t;
        if (den != 0) {
            t = dot(n, v[0] - o) / den;  // the ray meets the plane once, inside the triangle
            if (t < tMin) continue;
        } else {  // the ray lies in the triangle's plane: the first point at or after tMin
            const auto [enter, exit] = coplanarInterval(o, d, v, n);
            if (exit < tMin) continue;
            t = enter < tMin ? tMin : enter;
        }
        if (t >= tMax) continue;
        if (!best || t < *best) {
            best = t;
            bestIds.assign(1, id);
        } else if (t == *best) {
            bestIds.push_back(id);
        }
    }
    ExactHit hit;
    if (!best) return hit;
    std::sort(bestIds.begin(), bestIds.end());
    hit.t = CGAL::to_double(*best);
    hit.primitive = bestIds.front();
    hit.tieCount = std::uint32_t(bestIds.size());
    hit.tieFirst = std::uint32_t(ties.size());
    ties.insert(ties.end(), bestIds.begin(), bestIds.end());
    return hit;
}

ExactHits ExactReference::trace(const std::vector<gpu::Ray>& rays, const std::vector<std::uint32_t>& sample) const {
    const auto start = std::chrono::steady_clock::now();
    ExactHits out;
    out.rays = sample;
    out.hits.resize(sample.size());
    // Ties per chunk, joined in order afterwards: the result does not depend on the scheduling.
    constexpr std::size_t kChunk = 256;
    std::vector<std::vector<std::uint32_t>> chunkTies((sample.size() + kChunk - 1) / kChunk);
    tbb::parallel_for(std::size_t(0), chunkTies.size(), [&](std::size_t c) {
        for (std::size_t i = c * kChunk; i < std::min(sample.size(), (c + 1) * kChunk); ++i)
            out.hits[i] = trace(rays[sample[i]], chunkTies[c]);
    });
    for (std::size_t c = 0; c < chunkTies.size(); ++c) {
        const std::uint32_t offset = std::uint32_t(out.ties.size());
        for (std::size_t i = c * kChunk; i < std::min(sample.size(), (c + 1) * kChunk); ++i)
            if (out.hits[i].tieCount) out.hits[i].tieFirst += offset;
        out.ties.insert(out.ties.end(), chunkTies[c].begin(), chunkTies[c].end());
    }
    out.ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    return out;
}

bool ExactHits::isFirstHit(std::size_t i, std::uint32_t primitive) const {
    const ExactHit& h = hits[i];
    const auto first = ties.begin() + h.tieFirst, last = first + h.tieCount;
    return std::binary_search(first, last, primitive);
}

ExactHits::Verdict ExactHits::judge(std::size_t i, std::uint32_t primitive, bool primitivesCompared) const {
    const bool hit = primitive != gpu::kNoHit, exactHit = hits[i].primitive != gpu::kNoHit;
    if (hit != exactHit) return hit ? Verdict::FalseHit : Verdict::FalseMiss;
    if (hit && primitivesCompared && !isFirstHit(i, primitive)) return Verdict::WrongPrimitive;
    return Verdict::Right;
}

std::vector<std::uint32_t> sampleRays(std::size_t rayCount, std::uint64_t maxRays) {
    const std::size_t stride = maxRays == 0 || maxRays >= rayCount ? 1 : std::size_t((rayCount + maxRays - 1) / maxRays);
    std::vector<std::uint32_t> sample;
    sample.reserve(rayCount / stride + 1);
    for (std::size_t i = 0; i < rayCount; i += stride) sample.push_back(std::uint32_t(i));
    return sample;
}

ExactAccuracy compareExact(const std::vector<gpu::HitRecord>& hits, const ExactHits& exact, bool sameTriangles,
                           std::uint32_t query) {
    ExactAccuracy a;
    a.rays = exact.rays.size();
    a.distancesCompared = answersNearest(query);
    a.primitivesCompared = sameTriangles && a.distancesCompared;
    double errorSum = 0.0;
    std::uint64_t errorCount = 0;
    for (std::size_t i = 0; i < exact.rays.size(); ++i) {
        const gpu::HitRecord& h = hits[exact.rays[i]];
        const ExactHit& e = exact.hits[i];
        a.ties += e.tieCount > 1;
        const ExactHits::Verdict verdict = exact.judge(i, h.primitive, a.primitivesCompared);
        if (verdict == ExactHits::Verdict::FalseHit) ++a.falseHits;
        if (verdict == ExactHits::Verdict::FalseMiss) ++a.falseMisses;
        if (verdict == ExactHits::Verdict::WrongPrimitive) ++a.wrongPrimitive;
        if (h.primitive == gpu::kNoHit || e.primitive == gpu::kNoHit) continue;
        if (a.distancesCompared && e.t > 0.0) {
            const double error = std::abs(double(h.t) - e.t) / e.t;
            errorSum += error;
            ++errorCount;
            a.distanceErrorMax = std::max(a.distanceErrorMax, error);
        }
    }
    if (errorCount) a.distanceErrorMean = errorSum / double(errorCount);
    return a;
}

}  // namespace rtbench
