#include "driver_structure.h"

#include "structures/bvh/bvh_structure.h"
#include "core/error.h"
#include "schema/column.h"

namespace rtbench {

DriverStructure::DriverStructure(const TriangleMesh& mesh, std::unique_ptr<Structure> cpu)
    : vertices_(mesh.vertices), triangles_(mesh.triangles), cpu_(std::move(cpu)) {}

void DriverStructure::setArithmetic(const KernelArithmetic& arithmetic) {
    Structure::setArithmetic(arithmetic);
    cpu_->setArithmetic(arithmetic);
}

void DriverStructure::buildOnDevice(VulkanContext& vk) {
    device_ = std::make_unique<DriverAccelerationStructure>(vk, vertices_, triangles_);
    memoryBytes = device_->bottomLevelBytes() + device_->topLevelBytes();
    buildMs = device_->buildMs();
}

const DriverAccelerationStructure& DriverStructure::accelerationStructure() const {
    if (!device_) throw Error("the driver's acceleration structure is not built yet (Structure::buildOnDevice)");
    return *device_;
}

namespace {

// The driver's acceleration structure's storage, as the driver sized it (results schema 14).
struct DriverColumns {
    ColumnGroup group;
    Column<std::uint64_t> blas = bytes("driver_blas_bytes", "driver: the bottom level's storage, as the driver sized it");
    Column<std::uint64_t> tlas = bytes("driver_tlas_bytes", "driver: the top level's storage (one instance)");
    Column<std::uint64_t> scratch = bytes("driver_scratch_bytes", "driver: the larger build's scratch (freed after the build)");
    Column<std::uint64_t> input = bytes("driver_input_bytes", "driver: vertices, indices and the instance uploaded for the build");

private:
    Column<std::uint64_t> bytes(std::string name, std::string help) {
        return group.add<std::uint64_t>({std::move(name), ColumnKind::Exact, "bytes", std::move(help), 0.0, false, {}, 14});
    }
};

const DriverColumns& driverColumns() {
    static const DriverColumns columns;
    return columns;
}

}  // namespace

void DriverStructure::writeColumns(Row& row) const {
    if (!device_) return;
    const DriverColumns& c = driverColumns();
    put(row, c.blas, device_->bottomLevelBytes());
    put(row, c.tlas, device_->topLevelBytes());
    put(row, c.scratch, device_->scratchBytes());
    put(row, c.input, device_->inputBytes());
}

namespace {

std::unique_ptr<Structure> buildDriverStructure(const TriangleMesh& mesh, const std::vector<gpu::Ray>&, const RunConfig& run,
                                                const DeviceInfo& device) {
    if (!device.rayQuery) throw Error(device.name + " lacks VK_KHR_ray_query (missing: " + device.rayQueryMissing + ")");
    BvhBuildOptions cpu;  // the CPU side: rtbench's BVH at its defaults, from Embree's builder
    cpu.embreeConfig = run.getString("baseline.embree_config");
    return std::make_unique<DriverStructure>(mesh, bvhStructure(buildBvh(mesh, cpu)));
}

}  // namespace

const StructureType& driverStructureType() {
    static const StructureType type = [] {
        StructureType t;
        t.name = "driver";
        t.help = "the Vulkan driver's own acceleration structure (VK_KHR_acceleration_structure), built on the device; "
                 "traced by strategy.type = ray_query only";
        t.onlyStrategy = "ray_query";
        t.columns = driverColumns().group.specs();
        t.build = buildDriverStructure;
        return t;
    }();
    return type;
}

}  // namespace rtbench
