// What a fuzz input may do at each reader rtbench exposes to files it did not write: return a
// value that keeps the reader's promises, or throw rtbench::Error. Each body returns "" then, and
// the finding otherwise (another exception, a broken promise). The libFuzzer targets (fuzz_*.cpp)
// abort on a finding; tests/fuzz/test_mutations.cpp runs the same bodies on mutated seeds in CI.
#pragma once
#include <cmath>
#include <exception>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>
#include <typeinfo>

#include "harness/check.h"
#include "harness/columns.h"
#include "harness/config.h"
#include "harness/samples_check.h"
#include "harness/timing_rounds.h"
#include "harness/writers.h"
#include "core/error.h"
#include "scene/mesh_io.h"
#include "scene/scene_description.h"

namespace fuzz {

// "" when `body` returns or throws rtbench::Error; else what escaped `entry`.
template <class Body>
std::string onlyRtbenchErrors(const char* entry, Body&& body) {
    try {
        body();
    } catch (const rtbench::Error&) {
    } catch (const std::exception& e) {
        return std::string("exception other than rtbench::Error from ") + entry + ": " + typeid(e).name() + ": " + e.what();
    } catch (...) {
        return std::string("a non-std exception escaped ") + entry;
    }
    return "";
}

// A mesh's promises (scene/mesh_io.h): a triangle at least, indices in range, finite vertices.
inline std::string meshProblem(const rtbench::TriangleMesh& mesh) {
    if (mesh.triangles.empty()) return "a mesh without triangles was accepted";
    for (const auto& t : mesh.triangles)
        for (int i = 0; i < 3; ++i)
            if (t[i] >= mesh.vertices.size())
                return "triangle index " + std::to_string(t[i]) + " >= " + std::to_string(mesh.vertices.size()) + " vertices";
    for (const auto& v : mesh.vertices)
        for (int i = 0; i < 3; ++i)
            if (!std::isfinite(v[i])) return "a non-finite vertex coordinate was accepted";
    return "";
}

// A mesh file's bytes; the first byte picks the reader (byte % 4: .off .obj .ply .stl).
inline std::string meshInput(std::string_view input) {
    if (input.empty()) return "";
    static const char* const kExtensions[] = {".off", ".obj", ".ply", ".stl"};
    std::string problem;
    const std::string error = onlyRtbenchErrors("readMeshBytes", [&] {
        problem = meshProblem(rtbench::readMeshBytes(input.substr(1), std::string("input") + kExtensions[static_cast<unsigned char>(input[0]) % 4]));
    });
    return error.empty() ? problem : error;
}

// An experiment config's text.
inline std::string configInput(std::string_view input) {
    return onlyRtbenchErrors("loadExperimentText", [&] {
        const rtbench::ExperimentPlan plan = rtbench::loadExperimentText(std::string(input), "fuzz.toml", "/nonexistent-rtbench-fuzz");
        for (const rtbench::RunConfig& run : plan.runs) {
            (void)run.canonical();
            (void)run.hash();
            (void)run.label();
        }
    });
}

// A results folder's file, as check, compare, merge and resume read it; the first byte picks
// which (byte % 3: runs.csv, samples.csv, context.json).
inline std::string resultsInput(std::string_view input) {
    if (input.empty()) return "";
    const std::string text(input.substr(1));
    switch (static_cast<unsigned char>(input[0]) % 3) {
        case 0:
            return onlyRtbenchErrors("parseRunsCsv", [&] {
                int schema = 0;
                for (const rtbench::Row& row : rtbench::parseRunsCsv(text, "runs.csv", &schema))
                    for (const auto& [column, cell] : row) (void)rtbench::cellNumber(cell);
            });
        case 1:
            return onlyRtbenchErrors("parseSamplesCsv", [&] {
                const std::vector<rtbench::Row> samples = rtbench::parseSamplesCsv(text, "samples.csv");
                const auto byRun = rtbench::samplesByRun(samples);
                for (const rtbench::Row& s : samples)  // each sample's run as an ok row of 3 repetitions
                    (void)rtbench::samplesProblem({{"run", s.at("run")}, {"config_hash", s.at("config_hash")}, {"status", "ok"},
                                                   {"timing_repetitions", "3"}, {"kernel_ms_median", "1"}},
                                                  byRun);
            });
        default:
            return onlyRtbenchErrors("recordedPlan", [&] {
                (void)rtbench::recordedPlan(rtbench::parseJson(text, "context.json"), "context.json");
            });
    }
}

// A scene description's text, written to `folder`/scene.toml beside a tetrahedron (tetra.off)
// it may place; read as `scene.source` reads it.
inline std::string sceneInput(std::string_view input, const std::string& folder) {
    const std::string path = folder + "/scene.toml";
    {
        std::ofstream tetra(folder + "/tetra.off", std::ios::trunc);
        tetra << "OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 1 2\n3 0 1 3\n3 0 2 3\n3 1 2 3\n";
        std::ofstream out(path, std::ios::binary | std::ios::trunc);
        out.write(input.data(), std::streamsize(input.size()));
        if (!out || !tetra) return "cannot write the scratch files in " + folder;
    }
    std::string problem;
    const std::string error = onlyRtbenchErrors("readSceneDescription", [&] {
        problem = meshProblem(rtbench::readSceneDescription(path).mesh);
    });
    return error.empty() ? problem : error;
}

}  // namespace fuzz
