// The BVH as a method's structure (structures/structure.h): Embree's builder, flattened to the
// layout of bvh_layout.h, traversed per ray with a stack (bvh_traversal.glsl).
#pragma once
#include <memory>

#include "bvh_build.h"
#include "structures/structure.h"

namespace rtbench {

const StructureType& bvhStructureType();

// What every tree of the BVH's layout writes and reads: its columns (bvh_*) and structure.leaf_size.
std::vector<ColumnSpec> bvhColumnSpecs();
KeySpec bvhLeafSizeKey();
// Throws rtbench::Error when the device could not bind a tree of the mesh's triangles.
void refuseBvhOverBindings(const TriangleMesh& mesh, const DeviceInfo& device);

// A built BVH as a Structure (tests run strategies on trees they build themselves).
std::unique_ptr<Structure> bvhStructure(FlatBvh bvh);

// The CPU reference on its own: every ray through bvh_traversal.glsl compiled as C++.
std::vector<gpu::HitRecord> traceBvhReference(const FlatBvh& bvh, const std::vector<gpu::Ray>& rays);

}  // namespace rtbench
