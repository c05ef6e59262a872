#include "control_strategy.h"

#include <algorithm>
#include <cstring>

#include "device/embedded_kernels.h"
#include "core/error.h"
#include "strategies/dispatch_timer.h"
#include "scene/camera.h"
#include "strategies/branching/branching_strategy.h"
#include "strategies/control/kernels/control_layout.h"
#include "strategies/ray_query/ray_query_strategy.h"
#include "structures/uniform_grid/grid_layout.h"
#include "schema/column.h"

namespace rtbench {

std::uint64_t hitPointMismatches(const std::vector<gpu::HitRecord>& a, const std::vector<gpu::HitRecord>& b) {
    if (a.size() != b.size()) throw Error("hitPointMismatches: record streams of different lengths");
    std::uint64_t differing = 0;
    for (std::size_t i = 0; i < a.size(); ++i) differing += a[i].primitive != b[i].primitive || a[i].t != b[i].t;
    return differing;
}

std::uint64_t controlLoopBound(const std::vector<gpu::HitRecord>& cpu, unsigned width, unsigned height) {
    if (cpu.size() != std::size_t(width) * height) throw Error("controlLoopBound: records are not the image's");
    const unsigned tile = gpu::kControlTile, tilesX = (width + tile - 1) / tile;
    std::vector<std::uint64_t> perTile(std::size_t(tilesX) * ((height + tile - 1) / tile), 0);
    for (unsigned y = 0; y < height; ++y)
        for (unsigned x = 0; x < width; ++x) {
            const gpu::HitRecord& h = cpu[std::size_t(y) * width + x];
            perTile[std::size_t(y / tile) * tilesX + x / tile] += std::uint64_t(h.cellsVisited) + h.trianglesTested;
        }
    return perTile.empty() ? 0 : *std::max_element(perTile.begin(), perTile.end());
}

namespace {
// Whether `rays` are the frame's camera rays, bit for bit, row by row (the kernel makes them from it).
bool framesTheRays(const CameraFrame& frame, const std::vector<gpu::Ray>& rays) {
    if (rays.size() != std::size_t(frame.width()) * frame.height()) return false;
    for (unsigned y = 0; y < frame.height(); ++y) {
        for (unsigned x = 0; x < frame.width(); ++x) {
            const gpu::Ray made = primaryRay(frame, x, y);
            if (std::memcmp(&made, &rays[std::size_t(y) * frame.width() + x], sizeof made) != 0) return false;
        }
    }
    return true;
}

// Why the control cannot trace this batch over this structure ("" when it can).
std::string controlRefusal(const Structure& structure, const RayBatch& batch, const TimingOptions& timing) {
    if (!batch.camera) return "strategy.type = control makes the camera rays itself: rays.type = primary, without camera.tile";
    if (batch.query != gpu::kQueryClosest) return "rays.query = any: the control answers closest-hit queries only";
    if (structure.vertexLattice().bits) return "intersection.vertex_bits: the control reads float vertices (32)";
    if (structure.triangleTest() != gpu::kTriangleTestMollerTrumbore)
        return "intersection.test = watertight: the control tests Moller-Trumbore only";
    if (timing.workgroupSize != gpu::kControlTile * gpu::kControlTile)
        return "strategy.workgroup_size = " + std::to_string(timing.workgroupSize) +
               ": the control's workgroup is one 8 x 8 pixel tile (64)";
    return "";
}

// The control's buffers on the device and its kernel, for one image over one grid.
class ControlDispatch {
public:
    ControlDispatch(VulkanContext& vk, const Structure& grid, const CameraFrame& frame) : vk_(vk) {
        try {
            create(grid, frame);
        } catch (...) {
            release();  // what a failed setup made so far
            throw;
        }
    }
    ~ControlDispatch() { release(); }
    ControlDispatch(const ControlDispatch&) = delete;
    ControlDispatch& operator=(const ControlDispatch&) = delete;

    VulkanContext::DispatchCall call() const { return {&pipeline_, set_, &params_, invocations_}; }
    // The 8-byte records as hit records: no barycentrics, no work.
    std::vector<gpu::HitRecord> hits() const {
        std::vector<std::uint32_t> words(2 * pixels_);
        vk_.download(hits_, words.data(), words.size() * sizeof(std::uint32_t));
        std::vector<gpu::HitRecord> records(pixels_, gpu::HitRecord{});
        for (std::size_t i = 0; i < pixels_; ++i) {
            std::memcpy(&records[i].t, &words[2 * i], sizeof(float));
            records[i].primitive = words[2 * i + 1];
        }
        return records;
    }

private:
    Buffer uploaded(const void* data, std::uint64_t bytes, const std::string& what) {
        Buffer b = vk_.createStorageBuffer(std::max<std::uint64_t>(bytes, 4), what);
        if (bytes) vk_.upload(b, data, bytes);
        return b;
    }
    void create(const Structure& grid, const CameraFrame& frame);
    void release() {
        if (set_) vk_.destroy(set_);
        set_ = VK_NULL_HANDLE;
        vk_.destroy(pipeline_);
        for (Buffer* b : {&cells_, &list_, &triangles_, &camera_, &hits_}) vk_.destroy(*b);
    }

    VulkanContext& vk_;
    std::size_t pixels_ = 0;
    std::uint64_t invocations_ = 0;
    Buffer cells_, list_, triangles_, camera_, hits_;
    gpu::ControlParams params_{};
    ComputePipeline pipeline_{};
    VkDescriptorSet set_ = VK_NULL_HANDLE;
};

void ControlDispatch::create(const Structure& grid, const CameraFrame& frame) {
    // The grid's buffers (structures/uniform_grid/grid_layout.h): cell offsets, list, vertices.
    const std::vector<StructureBuffer> buffers = grid.buffers();
    const auto* offsets = static_cast<const std::uint32_t*>(buffers.at(0).data);
    std::vector<std::uint32_t> cells;  // (first, count) per voxel
    for (std::uint64_t c = 0; c + 1 < buffers[0].bytes / 4; ++c) {
        cells.push_back(offsets[c]);
        cells.push_back(offsets[c + 1] - offsets[c]);
    }
    cells_ = uploaded(cells.data(), cells.size() * 4, "control voxel (" + std::to_string(cells.size() / 2) + " cells)");
    list_ = uploaded(buffers.at(1).data, buffers[1].bytes, buffers[1].what);
    triangles_ = uploaded(buffers.at(2).data, buffers[2].bytes, buffers[2].what);
    // The camera frame, then the column and row offsets.
    gpu::ControlCamera camera{glm::vec4(frame.eye, 0.0f), glm::vec4(frame.forward, 0.0f), glm::vec4(frame.right, 0.0f),
                              glm::vec4(frame.down, 0.0f)};
    std::vector<std::uint8_t> cameraBytes(sizeof camera + 4 * (frame.width() + frame.height()));
    std::memcpy(cameraBytes.data(), &camera, sizeof camera);
    std::memcpy(cameraBytes.data() + sizeof camera, frame.columnOffsets.data(), 4 * frame.width());
    std::memcpy(cameraBytes.data() + sizeof camera + 4 * frame.width(), frame.rowOffsets.data(), 4 * frame.height());
    camera_ = uploaded(cameraBytes.data(), cameraBytes.size(), "control camera");
    pixels_ = std::size_t(frame.width()) * frame.height();
    hits_ = vk_.createStorageBuffer(8 * pixels_, "control hit (" + std::to_string(pixels_) + " rays)");
    // The push constants: the grid's box and cells (GridParams), the image in tiles.
    gpu::GridParams gridParams{};
    const std::vector<std::uint8_t> bytes = grid.params();
    if (bytes.size() != sizeof gridParams) throw Error("the control traces a uniform grid (its GridParams)");
    std::memcpy(&gridParams, bytes.data(), sizeof gridParams);
    const unsigned tile = gpu::kControlTile, tilesX = (frame.width() + tile - 1) / tile;
    const unsigned tilesY = (frame.height() + tile - 1) / tile;
    params_ = {gridParams.boundsMin, glm::vec4(glm::vec3(gridParams.boundsMax) - glm::vec3(gridParams.boundsMin), 0.0f),
               gridParams.cellSize, gridParams.invCellSize, gridParams.resolution,
               glm::uvec4(frame.width(), frame.height(), tilesX, 0u)};
    invocations_ = std::uint64_t(tilesX) * tilesY * tile * tile;
    pipeline_ = vk_.createComputePipeline(embeddedKernel("control_grid"), gpu::kControlBindings, sizeof params_,
                                          tile * tile, {});
    set_ = vk_.createDescriptorSet(pipeline_, {&cells_, &list_, &triangles_, &camera_, &hits_});
}

// Rays the control's hits differ from the CPU reference's on (results schema 26).
const Column<std::uint64_t>& controlCpuDiffering() {
    static const Column<std::uint64_t> column(
        {"control_cpu_differing", ColumnKind::Exact, "rays",
         "control: rays whose hit (t, triangle) differs from the CPU reference's, which divides exactly (0 "
         "where the device's division is IEEE's, as on llvmpipe; counted, not failed)", 0.0, false, {}, 26});
    return column;
}

StrategyRun runControl(VulkanContext& vk, const Structure& structure, const RayBatch& batch, const RunConfig&,
                       const TimingOptions& timing, Row& row) {
    if (const std::string why = controlRefusal(structure, batch, timing); !why.empty()) throw Error(why);
    const CameraFrame& frame = *batch.camera;
    if (!framesTheRays(frame, batch.rays)) throw Error("the control: the camera frame does not make the batch's rays");
    // llvmpipe ends an invocation's loops after a limit (DeviceInfo::loopIterationLimit), silently.
    const std::vector<gpu::HitRecord> cpu = structure.trace(batch.rays, gpu::kQueryClosest);
    const std::uint64_t bound = controlLoopBound(cpu, frame.width(), frame.height());
    if (const std::uint64_t budget = loopIterationBudget(vk.info()); budget && bound > budget)
        throw Error("the control: an 8 x 8 tile of this run may need " + std::to_string(bound) + " loop iterations and " +
                    vk.info().name + " ends a kernel invocation after " + std::to_string(vk.info().loopIterationLimit) +
                    " (a finer grid or the branching kernel stay within it)");
    auto dispatch = std::make_unique<ControlDispatch>(vk, structure, frame);
    vk.dispatchAll({dispatch->call()});
    StrategyRun run;
    run.hits = dispatch->hits();
    put(row, controlCpuDiffering(), hitPointMismatches(run.hits, cpu));
    run.timer = std::make_unique<DispatchTimer<ControlDispatch>>(vk, std::move(dispatch), run.hits, "control kernel");
    judgeByTheExactReference(batch.rays, run, "the control kernel");
    return run;
}

}  // namespace

const StrategyType& controlStrategyType() {
    static const StrategyType type = [] {
        StrategyType t;
        t.name = "control";
        t.help = "a plain grid ray caster (issue 47 §1): the branching kernel's walk and test without its generality, "
                 "camera rays made in 8 x 8 pixel tiles, 8-byte hits, the device's division; what the branching kernel's "
                 "speed is judged against; judged against the exact reference, no work counted";
        t.onlyStructure = "uniform_grid";
        t.columns = {controlCpuDiffering().spec()};
        t.trace = runControl;
        return t;
    }();
    return type;
}

}  // namespace rtbench
