// The driver's own acceleration structure as a method's structure (structure.type = "driver"):
// built on the device by the Vulkan driver (device/acceleration_structure.h), traced only by the
// ray_query strategy. Its CPU side, which the runner and the workloads ask of every structure
// (the hits that make a later generation's rays, the cost model), is rtbench's BVH over the same
// triangles, so a driver run traces the rays every other method traces.
#pragma once
#include <memory>

#include "device/acceleration_structure.h"
#include "structures/structure.h"

namespace rtbench {

const StructureType& driverStructureType();

class DriverStructure final : public Structure {
public:
    DriverStructure(const TriangleMesh& mesh, std::unique_ptr<Structure> cpu);

    std::string kernelPrefix() const override { return "driver"; }  // rtbench has no kernels for it
    std::vector<StructureBuffer> buffers() const override { return {}; }
    std::vector<std::uint8_t> params() const override { return {}; }
    StructureCosts costs() const override { return {}; }  // the driver's traffic is not counted
    StructureKernels cpuKernels() const override { return cpu_->cpuKernels(); }
    WalkBounds walkBounds() const override { return cpu_->walkBounds(); }
    // The driver's traversal is not rtbench's to model: none (predicted_work_per_ray stays empty).
    double predictedWork(const std::vector<gpu::Ray>&) const override { return -1.0; }
    void writeColumns(Row& row) const override;
    void setArithmetic(const KernelArithmetic& arithmetic) override;
    const VertexLattice& vertexLattice() const override { return cpu_->vertexLattice(); }
    // The driver builds its structure: memoryBytes become its two levels' storage, buildMs the
    // builds' GPU time.
    void buildOnDevice(VulkanContext& vk) override;

    // Throws rtbench::Error before buildOnDevice.
    const DriverAccelerationStructure& accelerationStructure() const;
    std::uint64_t triangleCount() const { return triangles_.size(); }

private:
    std::vector<glm::vec3> vertices_;
    std::vector<glm::uvec3> triangles_;
    std::unique_ptr<Structure> cpu_;
    std::unique_ptr<DriverAccelerationStructure> device_;
};

}  // namespace rtbench
