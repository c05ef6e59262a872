// The files a run reads (configs, meshes, scene descriptions, results being resumed or checked):
// read safely and fingerprinted. A file is read only when it is a regular file within a stated
// size limit (a FIFO would hang, /dev/zero would read until memory runs out, a folder is not a
// config), and the bytes read are the bytes hashed, so a run's identity covers what it used.
#pragma once
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace rtbench {

// FNV-1a 64 of bytes: config hashes, the fingerprint of a run's rays and of its input files.
std::uint64_t fnv1a64(std::string_view bytes);
// As 16 lower-case hex digits.
std::string hex64(std::uint64_t value);

// One input file as a run used it.
struct InputFile {
    std::string path;     // as opened (a cgal: mesh: its file in the cache)
    std::uint64_t bytes = 0;
    std::string hash;     // hex64(fnv1a64(contents))
};

// Size limits, named in the errors that enforce them.
constexpr std::uint64_t kMaxConfigBytes = 4ull << 20;          // a config file: 4 MiB
constexpr std::uint64_t kMaxResultsFileBytes = 4ull << 30;     // runs.csv, context.json: 4 GiB
constexpr std::uint64_t kMaxMeshFileBytes = 8ull << 30;        // a mesh file: 8 GiB

// Reads the whole of `path` (`what` names it in errors: "config file", "mesh file", ...). Throws
// rtbench::Error naming the path and why: not found, a symlink loop, not a regular file (a
// folder, a FIFO, a device), larger than `maxBytes` (the limit named), unreadable. Opens with
// O_NONBLOCK so a FIFO never blocks the open, and checks the opened file, not the name.
std::string readInputFile(const std::string& path, std::uint64_t maxBytes, const std::string& what);

// The bytes of a file as read, fingerprinted.
InputFile fingerprint(const std::string& path, std::string_view bytes);

// One hash over the contents of several inputs, in order (not their paths: the same files
// elsewhere are the same inputs).
std::string inputsHash(const std::vector<InputFile>& inputs);

}  // namespace rtbench
