// libFuzzer target for the mesh readers (scene/mesh_io.h, readMeshFile).
// Input: the first byte picks the extension (byte % 4: 0 .off, 1 .obj, 2 .ply, 3 .stl; the seeds
// use the characters '0'..'3'), the rest is the file's content. It is written to a file in
// /dev/shm (else $TMPDIR, else /tmp) and read through readMeshFile, the path the harness takes.
// Expected: a TriangleMesh that keeps the reader's promises (at least one triangle, indices in
// range, finite single-precision vertices, nothing written to stdout) or rtbench::Error. Anything else is a finding:
// another exception (reported, then abort), a crash, a sanitizer report, a leak, a hang
// (-timeout) or an allocation beyond -malloc_limit_mb (-rss_limit_mb by default).
#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>
#include <typeinfo>

#include "fuzz_bodies.h"
#include "fuzz_common.h"
#include "core/error.h"
#include "scene/mesh_io.h"

namespace {

const char* const kExtensions[] = {".off", ".obj", ".ply", ".stl"};

std::string scratchFolder() {
    namespace fs = std::filesystem;
    fs::path base = "/dev/shm";
    std::error_code ec;
    if (!fs::is_directory(base, ec) || access(base.c_str(), W_OK) != 0) {
        const char* tmp = std::getenv("TMPDIR");
        base = tmp && *tmp ? tmp : "/tmp";
    }
    // libFuzzer may leave with _Exit (no destructors): sweep the folders of dead processes first.
    const std::string stem = "rtbench-fuzz-mesh-";
    for (const auto& entry : fs::directory_iterator(base, ec)) {
        const std::string name = entry.path().filename().string();
        if (name.rfind(stem, 0) != 0) continue;
        const long pid = std::strtol(name.c_str() + stem.size(), nullptr, 10);
        if (pid > 0 && kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH) fs::remove_all(entry.path(), ec);
    }
    const fs::path dir = base / (stem + std::to_string(getpid()));
    fs::create_directories(dir);
    return dir.string();
}

struct Scratch {
    std::string dir = scratchFolder();
    // stdout goes to this file while the reader runs: mesh_io.h promises no output (a binary STL
    // header printed by a reader, say). stderr is left alone: sanitizer reports go there.
    int stdoutFile = open((dir + "/stdout").c_str(), O_RDWR | O_CREAT | O_TRUNC, 0600);
    ~Scratch() {
        if (stdoutFile >= 0) close(stdoutFile);
        std::error_code ec;
        std::filesystem::remove_all(dir, ec);
    }
};

[[noreturn]] void finding(const std::string& what) { fuzz::finding("fuzz_mesh", what); }

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    static Scratch scratch;  // removed at exit
    if (size < 1) return 0;
    const std::string path = scratch.dir + "/input" + kExtensions[data[0] % 4];
    {
        std::ofstream out(path, std::ios::binary | std::ios::trunc);
        out.write(reinterpret_cast<const char*>(data + 1), static_cast<std::streamsize>(size - 1));
        if (!out) finding("cannot write the scratch file " + path);
    }
    std::fflush(stdout);
    const int savedStdout = dup(1);
    if (scratch.stdoutFile < 0 || savedStdout < 0 || ftruncate(scratch.stdoutFile, 0) != 0 ||
        dup2(scratch.stdoutFile, 1) < 0)
        finding("cannot redirect stdout");
    auto restoreStdout = [&] {
        std::fflush(stdout);
        std::cout.flush();
        dup2(savedStdout, 1);
        close(savedStdout);
        struct stat st {};
        if (fstat(scratch.stdoutFile, &st) == 0 && st.st_size > 0)
            finding("the reader wrote " + std::to_string(st.st_size) + " bytes to stdout");
    };
    fuzz::expectOnlyRtbenchErrors("fuzz_mesh", "readMeshFile", [&] {
        rtbench::TriangleMesh mesh;
        try {
            mesh = rtbench::readMeshFile(path);
        } catch (...) {
            restoreStdout();
            throw;
        }
        restoreStdout();
        if (const std::string problem = fuzz::meshProblem(mesh); !problem.empty()) finding(problem);
    });
    std::remove(path.c_str());
    return 0;
}
