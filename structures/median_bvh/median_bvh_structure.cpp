#include "median_bvh_structure.h"

#include "median_bvh_build.h"
#include "structures/bvh/bvh_structure.h"

namespace rtbench {

namespace {

std::unique_ptr<Structure> buildMedianBvhStructure(const TriangleMesh& mesh, const std::vector<gpu::Ray>&,
                                                   const RunConfig& run, const DeviceInfo& device) {
    refuseBvhOverBindings(mesh, device);
    return bvhStructure(buildMedianBvh(mesh, unsigned(run.getInt("structure.leaf_size"))));
}

}  // namespace

const StructureType& medianBvhStructureType() {
    static const StructureType type = [] {
        StructureType t;
        t.name = "median_bvh";
        t.help = "binary BVH split at the median centroid along the longest axis (no cost model), in the BVH's layout and "
                 "traced by its kernels: a cheap build of a worse tree than bvh's SAH";
        t.keys = {bvhLeafSizeKey()};
        t.columns = bvhColumnSpecs();
        // Not among auto's candidates: an SAH build of the same layout (bvh) is built beside it.
        t.autoCandidate = false;
        t.build = buildMedianBvhStructure;
        return t;
    }();
    return type;
}

}  // namespace rtbench
