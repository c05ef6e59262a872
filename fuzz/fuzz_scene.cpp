// libFuzzer target for scene descriptions (scene/scene_description.h, readSceneDescription).
// Input: the description's text, written to a scratch folder beside a tetrahedron it may place.
// Expected: a mesh that keeps the reader's promises, or rtbench::Error (fuzz_bodies.h).
#include <unistd.h>

#include <cstdint>
#include <filesystem>
#include <string_view>

#include "fuzz_bodies.h"
#include "fuzz_common.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    static const std::string folder = [] {
        const std::filesystem::path dir = std::filesystem::temp_directory_path() / ("rtbench-fuzz-scene-" + std::to_string(getpid()));
        std::filesystem::create_directories(dir);
        return dir.string();
    }();
    const std::string problem = fuzz::sceneInput(std::string_view(reinterpret_cast<const char*>(data), size), folder);
    if (!problem.empty()) fuzz::finding("fuzz_scene", problem);
    return 0;
}
