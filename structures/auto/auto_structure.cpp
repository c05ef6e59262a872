#include "auto_structure.h"

#include <limits>

#include "methods/registry.h"
#include "core/error.h"
#include "schema/column.h"

namespace rtbench {

namespace {

// The choice and what the cost model predicted for each candidate.
struct AutoColumns {
    ColumnGroup group;
    Column<std::string> choice = group.add<std::string>({"auto_choice", ColumnKind::Exact, "", "auto: the structure chosen"});
    Column<std::string> predictions = group.add<std::string>(
        {"auto_predictions", ColumnKind::Exact, "operations", "auto: every candidate's predicted work per ray (predicted_work_per_ray), or refused"});
};

const AutoColumns& autoColumns() {
    static const AutoColumns columns;
    return columns;
}

// The chosen structure, with the record of the choice.
class AutoStructure final : public Structure {
public:
    AutoStructure(std::unique_ptr<Structure> chosen, std::string choice, std::string predictions, double buildMsAll)
        : chosen_(std::move(chosen)), choice_(std::move(choice)), predictions_(std::move(predictions)) {
        memoryBytes = chosen_->memoryBytes;
        buildMs = buildMsAll;  // the price of choosing: every candidate was built
    }
    std::string kernelPrefix() const override { return chosen_->kernelPrefix(); }
    std::vector<StructureBuffer> buffers() const override { return chosen_->buffers(); }
    std::vector<std::uint8_t> params() const override { return chosen_->params(); }
    StructureCosts costs() const override { return chosen_->costs(); }
    StructureKernels cpuKernels() const override { return chosen_->cpuKernels(); }
    WalkBounds walkBounds() const override { return chosen_->walkBounds(); }
    StepFunctions stepFunctions() const override { return chosen_->stepFunctions(); }
    double predictedWork(const std::vector<gpu::Ray>& rays) const override { return chosen_->predictedWork(rays); }
    const VertexLattice& vertexLattice() const override { return chosen_->vertexLattice(); }
    void setArithmetic(const KernelArithmetic& arithmetic) override {
        Structure::setArithmetic(arithmetic);
        chosen_->setArithmetic(arithmetic);
    }
    void writeColumns(Row& row) const override {
        chosen_->writeColumns(row);
        put(row, autoColumns().choice, choice_);
        put(row, autoColumns().predictions, predictions_);
    }
    const WalkColumns* walkColumns() const override { return chosen_->walkColumns(); }

private:
    std::unique_ptr<Structure> chosen_;
    std::string choice_, predictions_;
};

// The run as a candidate sees it: its structure.type, and its own keys at their defaults.
RunConfig candidateRun(const RunConfig& run, const StructureType& candidate) {
    RunConfig c = run;
    c.values["structure.type"] = candidate.name;
    for (const KeySpec& key : candidate.keys) {
        if (key.defaultValue)
            c.values[key.name] = *key.defaultValue;
        else if (key.groupDefault)
            c.values[key.name] = *key.groupDefault;
    }
    return c;
}

std::unique_ptr<Structure> buildAuto(const TriangleMesh& mesh, const std::vector<gpu::Ray>& rays, const RunConfig& run,
                                     const DeviceInfo& device) {
    std::unique_ptr<Structure> best;
    std::string bestName, predictions;
    double bestWork = std::numeric_limits<double>::infinity(), buildMs = 0.0;
    for (const StructureType* candidate : structureTypes()) {
        // Not itself, nor a structure only one strategy traces (the driver's: its cost is not
        // rtbench's to model), nor one that declares itself no candidate.
        if (candidate == &autoStructureType() || !candidate->onlyStrategy.empty() || !candidate->autoCandidate) continue;
        predictions += (predictions.empty() ? "" : " ") + candidate->name + "=";
        std::unique_ptr<Structure> built;
        try {
            built = candidate->build(mesh, rays, candidateRun(run, *candidate), device);
        } catch (const Error&) {
            predictions += "refused";  // e.g. brute force over structure.max_tests, a grid over the binding limit
            continue;
        }
        buildMs += built->buildMs;
        const double work = built->predictedWork(rays);
        predictions += formatNumber(work / double(std::max<std::size_t>(rays.size(), 1)));
        if (work < bestWork) bestWork = work, bestName = candidate->name, best = std::move(built);
    }
    if (!best) throw Error("structure.type = auto: every candidate was refused (" + predictions + ")");
    return std::make_unique<AutoStructure>(std::move(best), bestName, predictions, buildMs);
}

}  // namespace

const StructureType& autoStructureType() {
    static const StructureType type = [] {
        StructureType t;
        t.name = "auto";
        t.help = "the structure the cost model predicts the least work for (each candidate built with its default keys)";
        t.columns = autoColumns().group.specs();
        t.build = buildAuto;
        return t;
    }();
    return type;
}

}  // namespace rtbench
