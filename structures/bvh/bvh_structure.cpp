#include "bvh_structure.h"

#include "structures/cost_model.h"
#include "bvh_reference.h"
#include "structures/shared_source.h"
#include "structures/triangle_store.h"
#include "core/error.h"
#include "schema/column.h"

namespace rtbench {


namespace {

// The BVH's columns, each declared once, here, where its value is written.
struct BvhColumns {
    using K = ColumnKind;
    using U64 = std::uint64_t;
    ColumnGroup group;
    Column<U64> innerNodes = group.add<U64>({"bvh_inner_nodes", K::Exact, "nodes", "BVH inner nodes (80 bytes each)"});
    Column<U64> leaves = group.add<U64>({"bvh_leaves", K::Exact, "leaves", "BVH leaves"});
    Column<unsigned> depth = group.add<unsigned>({"bvh_depth", K::Exact, "levels", "deepest leaf's distance from the root"});
    Column<unsigned> largestLeaf = group.add<unsigned>({"bvh_largest_leaf", K::Exact, "triangles", "most triangles in one leaf"});
    Column<U64> references = group.add<U64>({"bvh_references", K::Exact, "references", "triangle-list entries (each triangle once)"});
    Column<double> sahCost = group.add<double>({"bvh_sah_cost", K::Exact, "", "SAH cost of the tree (traversal and intersection cost 1)"});
    WalkColumns walk{group, "nodes", "BVH inner nodes visited per ray", "bytes_node", "BVH nodes read"};
};

const BvhColumns& bvhColumns() {
    static const BvhColumns columns;
    return columns;
}

class BvhStructure final : public SharedSourceStructure<bvhref::BvhKernels> {
public:
    explicit BvhStructure(FlatBvh bvh) : bvh_(std::move(bvh)), vertices_(bvh_.triangles, bvh_.lattice) {
        memoryBytes = bvh_.stats.bytes;
        buildMs = bvh_.stats.buildMs;
    }

    std::string kernelPrefix() const override { return "bvh"; }

    std::vector<StructureBuffer> buffers() const override {
        return {{"BVH node (" + std::to_string(bvh_.nodes.size()) + " nodes)", bvh_.nodes.size() * sizeof(gpu::BvhNode),
                 bvh_.nodes.data()},
                {"BVH triangle list (" + std::to_string(bvh_.triangleList.size()) + " references)",
                 bvh_.triangleList.size() * 4, bvh_.triangleList.data()},
                vertices_.buffer()};
    }

    StructureCosts costs() const override {
        StructureCosts c;
        c.bytesPerCellVisit = sizeof(gpu::BvhNode);      // an inner node visited is one node read
        c.bytesPerStructureRead = sizeof(gpu::BvhNode);
        c.bytesPerListEntry = 4;
        c.traversalStateBytes = sizeof(gpu::BvhTraversalState);
        c.stackBytes = sizeof(gpu::BvhTraversalState::stack);
        c.bytesPerTriangle = triangleVertexBytes(vertexLattice());
        return c;
    }

    const VertexLattice& vertexLattice() const override { return vertices_.lattice(); }

    bvhref::BvhKernels kernels() const override {
        bvhref::BvhKernels k = bvhKernels(bvh_);
        vertices_.bind(k);
        return k;
    }

    // A ray visits each reference at most once: inner nodes + leaves bound its steps; a leaf holds
    // at most largestLeaf triangles.
    StepFunctions stepFunctions() const override { return {{"rtBvhChildren"}, /*perCellVisited=*/true}; }  // an inner node
    WalkBounds walkBounds() const override { return {bvh_.stats.innerNodes + bvh_.stats.leaves, bvh_.stats.largestLeaf}; }

    // The tree's SAH cost (FlatBvhWriter's, with both costs 1) per ray entering its box.
    double predictedWork(const std::vector<gpu::Ray>& rays) const override {
        return double(raysEnteringBox(rays, glm::vec3(bvh_.params.boundsMin), glm::vec3(bvh_.params.boundsMax))) *
               bvh_.stats.sahCost;
    }

    void writeColumns(Row& row) const override {
        const BvhStats& s = bvh_.stats;
        const BvhColumns& c = bvhColumns();
        put(row, c.innerNodes, s.innerNodes);
        put(row, c.leaves, s.leaves);
        put(row, c.depth, s.depth);
        put(row, c.largestLeaf, s.largestLeaf);
        put(row, c.references, s.references);
        put(row, c.sahCost, s.sahCost);
    }

    const WalkColumns* walkColumns() const override { return &bvhColumns().walk; }

private:
    FlatBvh bvh_;
    TriangleStore vertices_;  // over bvh_.triangles
};

BvhBuildOptions buildOptions(const RunConfig& run) {
    BvhBuildOptions o;
    o.maxLeafSize = unsigned(run.getInt("structure.leaf_size"));
    o.quality = run.getString("structure.quality");
    o.embreeConfig = run.getString("baseline.embree_config");
    return o;
}

std::unique_ptr<Structure> buildBvhStructure(const TriangleMesh& mesh, const std::vector<gpu::Ray>&, const RunConfig& run,
                                             const DeviceInfo& device) {
    refuseBvhOverBindings(mesh, device);
    return bvhStructure(buildBvh(mesh, buildOptions(run)));
}

}  // namespace

bvhref::BvhKernels bvhKernels(const FlatBvh& bvh) {
    bvhref::BvhKernels k{};
    k.nodes = bvh.nodes.data();
    k.triangleList = bvh.triangleList.data();
    k.triangles = bvh.triangles.data();
    k.packedTriangles = nullptr;
    k.params = bvh.params;
    return k;
}

std::vector<gpu::HitRecord> traceBvhReference(const FlatBvh& bvh, const std::vector<gpu::Ray>& rays) {
    return traceAll(bvhKernels(bvh), rays);
}

std::unique_ptr<Structure> bvhStructure(FlatBvh bvh) { return std::make_unique<BvhStructure>(std::move(bvh)); }

void refuseBvhOverBindings(const TriangleMesh& mesh, const DeviceInfo& device) {
    // What the device must hold is known before the build but for the node count (at most
    // 2n - 1 for n triangles; checked again at upload).
    const std::uint64_t n = mesh.triangles.size();
    checkBindingSize(device, "triangle vertex (" + std::to_string(n) + " triangles)", n * triangleVertexBytes(mesh.lattice));
    checkBindingSize(device, "BVH triangle list (" + std::to_string(n) + " references)", n * 4);
}

std::vector<ColumnSpec> bvhColumnSpecs() { return bvhColumns().group.specs(); }

KeySpec bvhLeafSizeKey() {
    return {"structure.leaf_size", ValueType::Int, "BVH and median BVH: most triangles per leaf (bvh: Embree's maxLeafSize)", std::int64_t(4), false, 1,
            double(gpu::kBvhMaxLeafSize)};
}

const StructureType& bvhStructureType() {
    static const StructureType type = [] {
        StructureType t;
        t.name = "bvh";
        t.help = "binary BVH from Embree's builder (rtcBuildBVH), both child boxes per node (Aila & Laine 2009)";
        t.keys = {
            bvhLeafSizeKey(),
            {"structure.quality", ValueType::String, "BVH: medium (binned SAH) or low (Morton codes: faster build, worse tree)", std::string("medium"), false, -1e300, 1e300, {"medium", "low"}},
        };
        t.columns = bvhColumnSpecs();
        t.build = buildBvhStructure;
        return t;
    }();
    return type;
}

}  // namespace rtbench
