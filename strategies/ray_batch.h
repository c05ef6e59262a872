// A batch of rays as a workload (rays/workload.h) hands it to a method: the rays, and the query
// they ask of the scene. The method knows no ray type; the query is all it needs of one (and, for
// a strategy that traces the whole path, the BatchPath beside it: the rays before the batch and
// the passes).
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "kernels/gpu_layout.h"

namespace rtbench {

struct CameraFrame;  // scene/camera.h

// One generation of the path a batch ends, as the CPU made it (rays/workload.h Generation):
// each ray, its hit by the run's structure, the ray of the generation before it came from, its
// path (the key of its random numbers) and weight. The camera rays have no parents, paths or
// weights (ray i: parent i, path i, weight 1); the batch has no hits (the method's to find).
struct PathGeneration {
    const std::vector<gpu::Ray>* rays = nullptr;
    const std::vector<gpu::HitRecord>* hits = nullptr;
    const std::vector<std::uint32_t>* parents = nullptr;
    const std::vector<std::uint32_t>* paths = nullptr;
    const std::vector<float>* weights = nullptr;
};

// How the batch came to be, for a strategy that traces the whole path on the device from the camera
// rays (StrategyType::TracePath: the wavefront, the path megakernel): the generations and the
// shading passes between.
struct BatchPath {
    std::vector<PathGeneration> generations;  // 0: the camera rays; back(): the batch
    std::vector<gpu::ShadingParams> passes;   // passes[g] made generation g + 1 from generation g
    std::vector<gpu::Triangle> triangles;     // the traced scene's vertices, as the passes read them
    gpu::Material material{};                 // every surface's
    // Why the passes read more than one material or any light ("" when they do not): the
    // whole-path strategies bind one material and no light (strategies/whole_path.h).
    std::string notUniform;
    // Rays in all the generations: what a strategy tracing the whole path traces.
    std::uint64_t rays() const {
        std::uint64_t n = 0;
        for (const PathGeneration& g : generations) n += g.rays->size();
        return n;
    }
};

struct RayBatch {
    std::vector<gpu::Ray> rays;
    std::uint32_t query = gpu::kQueryClosest;  // gpu::kQuery*: closest hit or any hit
    // The camera's frame when the batch is its camera rays in their order, row by row (null
    // otherwise): a strategy that makes the camera rays itself (the control) makes them from it.
    std::shared_ptr<const CameraFrame> camera;
};

// The batch's rays in another order (order[i]: the batch's ray that goes i-th), for a method that
// traces them so (camera.tile's tiles, the sorted strategy's coherent order); not the camera's
// rays in their order any more. inBatchOrder puts the records made so back.
inline RayBatch inOrder(const RayBatch& batch, const std::vector<std::uint32_t>& order) {
    RayBatch reordered;
    reordered.query = batch.query;
    reordered.rays.reserve(order.size());
    for (std::uint32_t i : order) reordered.rays.push_back(batch.rays.at(i));
    return reordered;
}

// Records made in `order`, back in the batch's order.
inline std::vector<gpu::HitRecord> inBatchOrder(const std::vector<gpu::HitRecord>& reordered,
                                                const std::vector<std::uint32_t>& order) {
    std::vector<gpu::HitRecord> hits(reordered.size());
    for (std::size_t i = 0; i < order.size(); ++i) hits.at(order[i]) = reordered.at(i);
    return hits;
}

// The query's name, as the rays.query column and the messages write it, and the query a name
// (a rays.query value other than "own") asks.
inline const char* queryName(std::uint32_t query) { return query == gpu::kQueryAny ? "any" : "closest"; }
inline std::uint32_t queryOfName(const std::string& name) { return name == "any" ? gpu::kQueryAny : gpu::kQueryClosest; }

// Whether the query's answer is the nearest hit (pbrt's Intersect, Embree's rtcIntersect: its
// distance and triangle are judged) or only whether something is hit (IntersectP, rtcOccluded:
// the first hit found ends the walk and is its record, so only hit or miss is judged). The
// references and the judges ask this, not the query's number.
inline bool answersNearest(std::uint32_t query) { return query != gpu::kQueryAny; }

}  // namespace rtbench
