#include "driver_structure.h"

#include "structures/bvh/bvh_structure.h"
#include "core/error.h"

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

void DriverStructure::writeColumns(Row& row) const {
    if (!device_) return;
    row["driver_blas_bytes"] = std::to_string(device_->bottomLevelBytes());
    row["driver_tlas_bytes"] = std::to_string(device_->topLevelBytes());
    row["driver_scratch_bytes"] = std::to_string(device_->scratchBytes());
    row["driver_input_bytes"] = std::to_string(device_->inputBytes());
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
        const int since = 14;
        t.columns = {
            {"driver_blas_bytes", ColumnKind::Exact, "bytes", "driver: the bottom level's storage, as the driver sized it", 0.0, false, {}, since},
            {"driver_tlas_bytes", ColumnKind::Exact, "bytes", "driver: the top level's storage (one instance)", 0.0, false, {}, since},
            {"driver_scratch_bytes", ColumnKind::Exact, "bytes", "driver: the larger build's scratch (freed after the build)", 0.0, false, {}, since},
            {"driver_input_bytes", ColumnKind::Exact, "bytes", "driver: vertices, indices and the instance uploaded for the build", 0.0, false, {}, since}};
        t.build = buildDriverStructure;
        return t;
    }();
    return type;
}

}  // namespace rtbench
