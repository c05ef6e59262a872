#include "mesh_io.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/IO/polygon_soup_io.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include "error.h"

namespace rtbench {
namespace fs = std::filesystem;

namespace {

using Point = CGAL::Exact_predicates_inexact_constructions_kernel::Point_3;

std::string lowerExtension(const std::string& path) {
    std::string ext = fs::path(path).extension().string();
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return ext;
}

// Element counts a file's header declares, and the line of each element where it is known.
struct DeclaredCounts {
    bool known = false;
    std::size_t vertices = 0;
    std::size_t faces = 0;
    std::vector<std::size_t> elementLines;  // OFF: line of vertex i, then of face j at nv + j
};

// OFF (Shilane et al. / Geomview): optional letters before "OFF", then "nv nf ne", comments '#'.
DeclaredCounts readOffHeader(const std::string& path) {
    DeclaredCounts counts;
    std::ifstream in(path);
    std::string line;
    std::size_t lineNo = 0;
    std::vector<long long> numbers;  // header numbers collected so far
    bool sawKeyword = false;
    while (std::getline(in, line)) {
        ++lineNo;
        std::string text = line.substr(0, line.find('#'));
        std::istringstream tokens(text);
        std::string token;
        if (!(tokens >> token)) continue;  // blank or comment line
        if (!sawKeyword) {
            if (token.find("OFF") == std::string::npos) return counts;  // binary/odd: skip check
            if (token.find("n") == 0 || token == "OFF_BINARY" || text.find("BINARY") != std::string::npos)
                return counts;
            sawKeyword = true;
            long long value;
            while (tokens >> value) numbers.push_back(value);
        } else if (numbers.size() < 3) {
            std::istringstream again(text);
            long long value;
            while (numbers.size() < 3 && again >> value) numbers.push_back(value);
        } else {
            counts.elementLines.push_back(lineNo);
        }
    }
    if (numbers.size() < 2 || numbers[0] < 0 || numbers[1] < 0) return counts;
    counts.known = true;
    counts.vertices = static_cast<std::size_t>(numbers[0]);
    counts.faces = static_cast<std::size_t>(numbers[1]);
    return counts;
}

// PLY: "element vertex N" and "element face N" lines of the ASCII header (binary bodies too).
DeclaredCounts readPlyHeader(const std::string& path) {
    DeclaredCounts counts;
    std::ifstream in(path, std::ios::binary);
    std::string line;
    bool sawVertex = false, sawFace = false;
    while (std::getline(in, line)) {
        std::istringstream tokens(line);
        std::string word, element;
        std::size_t n = 0;
        tokens >> word;
        if (word == "end_header") break;
        if (word == "element" && tokens >> element >> n) {
            if (element == "vertex") counts.vertices = n, sawVertex = true;
            if (element == "face") counts.faces = n, sawFace = true;
            if (n > (std::size_t(1) << 40)) break;  // absurd: the size check refuses it
        }
    }
    counts.known = sawVertex && sawFace;
    return counts;
}

// CGAL's OFF reader fails without saying why; find the first element that explains it.
std::string diagnoseOff(const std::string& path, const DeclaredCounts& counts) {
    if (!counts.known) return path + ": not an ASCII OFF file (no 'OFF' header with vertex and face counts)";
    const std::size_t declared = counts.vertices + counts.faces;
    if (counts.elementLines.size() < declared)
        return path + ": truncated: the header declares " + std::to_string(counts.vertices) + " vertices and " +
               std::to_string(counts.faces) + " faces, the file holds " + std::to_string(counts.elementLines.size()) +
               " element lines";
    std::ifstream in(path);
    std::string line;
    std::size_t lineNo = 0, element = 0;
    while (std::getline(in, line) && element < declared) {
        ++lineNo;
        if (lineNo != counts.elementLines[element]) continue;
        std::istringstream tokens(line.substr(0, line.find('#')));
        const std::string at = path + ":" + std::to_string(lineNo) + ": ";
        if (element < counts.vertices) {
            std::string word;
            for (int k = 0; k < 3; ++k) {
                double value = 0.0;
                if (!(tokens >> word)) return at + "vertex " + std::to_string(element) + " has fewer than 3 coordinates";
                try {
                    value = std::stod(word);
                } catch (const std::exception&) {
                    return at + "vertex " + std::to_string(element) + ": '" + word + "' is not a number";
                }
                if (!std::isfinite(value))
                    return at + "vertex " + std::to_string(element) + " has a NaN or infinite coordinate";
            }
        } else {
            const std::size_t face = element - counts.vertices;
            long long n = 0, index = 0;
            if (!(tokens >> n) || n < 0) return at + "face " + std::to_string(face) + ": no vertex count";
            for (long long k = 0; k < n; ++k) {
                if (!(tokens >> index)) return at + "face " + std::to_string(face) + " lists fewer than " + std::to_string(n) + " vertices";
                if (index < 0 || static_cast<std::size_t>(index) >= counts.vertices)
                    return at + "face " + std::to_string(face) + " references vertex " + std::to_string(index) +
                           ", but the file has " + std::to_string(counts.vertices) + " vertices";
            }
        }
        ++element;
    }
    return "";
}

std::string where(const std::string& path, const DeclaredCounts& counts, std::size_t element) {
    if (element < counts.elementLines.size())
        return path + ":" + std::to_string(counts.elementLines[element]);
    return path;
}

}  // namespace

TriangleMesh readMeshFile(const std::string& path) {
    std::error_code ec;
    if (!fs::exists(path, ec)) throw Error(path + ": mesh file not found");
    if (!fs::is_regular_file(path, ec)) throw Error(path + ": not a regular file");
    {
        std::ifstream probe(path);
        if (!probe) throw Error(path + ": cannot open for reading");
    }
    const std::string ext = lowerExtension(path);
    if (ext != ".off" && ext != ".obj" && ext != ".ply" && ext != ".stl")
        throw Error(path + ": unknown mesh extension '" + ext +
                    "' (allowed: .off, .obj, .ply, .stl)");

    // A header may declare more elements than the file could hold; readers reserve memory for
    // what is declared, so refuse before reading (every element takes at least one byte).
    DeclaredCounts declared;
    if (ext == ".off") declared = readOffHeader(path);
    if (ext == ".ply") declared = readPlyHeader(path);
    const std::uintmax_t fileBytes = fs::file_size(path, ec);
    if (declared.vertices + declared.faces > fileBytes)
        throw Error(path + ": truncated: the header declares " + std::to_string(declared.vertices) +
                    " vertices and " + std::to_string(declared.faces) + " faces, but the file has only " +
                    std::to_string(fileBytes) + " bytes");

    std::vector<Point> points;
    std::vector<std::vector<std::size_t>> polygons;
    bool ok = false;
    std::ostringstream readerSaid;
    {
        // CGAL reports parse problems on std::cerr; capture them for the error message.
        std::streambuf* saved = std::cerr.rdbuf(readerSaid.rdbuf());
        try {
            ok = CGAL::IO::read_polygon_soup(path, points, polygons,
                                             CGAL::parameters::verbose(true));
        } catch (const std::exception& e) {
            readerSaid << e.what();
            ok = false;
        }
        std::cerr.rdbuf(saved);
    }
    std::string said = readerSaid.str();
    while (!said.empty() && (said.back() == '\n' || said.back() == ' ')) said.pop_back();
    for (char& c : said)
        if (c == '\n') c = ' ';
    if (!ok && ext == ".off")
        if (const std::string why = diagnoseOff(path, declared); !why.empty()) throw Error(why);
    if (!ok)
        throw Error(path + ": the CGAL reader failed" + (said.empty() ? "" : " (" + said + ")"));

    if (declared.known && (points.size() < declared.vertices || polygons.size() < declared.faces))
        throw Error(path + ": truncated: the header declares " + std::to_string(declared.vertices) +
                    " vertices and " + std::to_string(declared.faces) + " faces, the file holds " +
                    std::to_string(points.size()) + " and " + std::to_string(polygons.size()));

    TriangleMesh mesh;
    mesh.name = path;
    mesh.polygonsRead = polygons.size();
    mesh.vertices.reserve(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) {
        const Point& p = points[i];
        if (!std::isfinite(p.x()) || !std::isfinite(p.y()) || !std::isfinite(p.z()))
            throw Error(where(path, declared, i) + ": vertex " + std::to_string(i) +
                        " has a NaN or infinite coordinate");
        glm::vec3 v(static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z()));
        if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z))
            throw Error(where(path, declared, i) + ": vertex " + std::to_string(i) +
                        " overflows single precision");
        mesh.vertices.push_back(v);
    }
    for (std::size_t f = 0; f < polygons.size(); ++f) {
        const auto& poly = polygons[f];
        const std::string at = where(path, declared, points.size() + f);
        if (poly.size() < 3)
            throw Error(at + ": face " + std::to_string(f) + " has " + std::to_string(poly.size()) +
                        " vertices (at least 3 needed)");
        for (std::size_t index : poly)
            if (index >= points.size())
                throw Error(at + ": face " + std::to_string(f) + " references vertex " +
                            std::to_string(index) + ", but the file has " +
                            std::to_string(points.size()) + " vertices");
        for (std::size_t k = 1; k + 1 < poly.size(); ++k)  // fan triangulation
            mesh.triangles.emplace_back(poly[0], poly[k], poly[k + 1]);
    }
    if (mesh.triangles.empty()) throw Error(path + ": the mesh has no faces");
    return mesh;
}

std::string resolveCgalMesh(const std::string& name) {
    if (name.empty() || name.find('/') != std::string::npos || name.find("..") != std::string::npos)
        throw Error("cgal:" + name + ": expected a mesh name such as cgal:bunny00");
    const fs::path archive = "/usr/share/doc/libcgal-demo/data.tar.gz";
    fs::path cache;
    if (const char* env = std::getenv("RTBENCH_CACHE"); env && *env)
        cache = env;
    else if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg)
        cache = fs::path(xdg) / "rtbench";
    else if (const char* home = std::getenv("HOME"); home && *home)
        cache = fs::path(home) / ".cache" / "rtbench";
    else
        cache = fs::temp_directory_path() / "rtbench-cache";
    const fs::path meshes = cache / "cgal-data" / "meshes";
    if (!fs::exists(meshes)) {
        if (!fs::exists(archive))
            throw Error("cgal:" + name + ": " + archive.string() +
                        " is missing (install Debian's libcgal-demo: scripts/setup.sh does)");
        fs::create_directories(cache);
        // Extract into a private folder, then rename: a concurrent or interrupted run never
        // sees a half-extracted cache.
        const fs::path staging = cache / ("cgal-data.tmp." + std::to_string(::getpid()));
        fs::remove_all(staging);
        fs::create_directories(staging);
        const std::string command = "tar -xzf '" + archive.string() + "' -C '" + staging.string() +
                                    "' data/meshes";
        std::cerr << "[rtbench] extracting CGAL's meshes once into " << meshes.parent_path()
                  << "\n";
        if (std::system(command.c_str()) != 0) {
            fs::remove_all(staging);
            throw Error("cgal:" + name + ": extracting " + archive.string() + " failed");
        }
        fs::create_directories(meshes.parent_path().parent_path());
        std::error_code ec;
        fs::rename(staging / "data", meshes.parent_path(), ec);  // loses a race harmlessly
        fs::remove_all(staging);
        if (!fs::exists(meshes)) throw Error("cgal:" + name + ": cache " + meshes.string() + " missing");
    }
    const fs::path file = meshes / (name + ".off");
    if (!fs::exists(file)) {
        std::string some;
        int n = 0;
        for (const auto& entry : fs::directory_iterator(meshes))
            if (entry.path().extension() == ".off" && n++ < 8) some += " " + entry.path().stem().string();
        throw Error("cgal:" + name + ": no such mesh in libcgal-demo (some that exist:" + some + ")");
    }
    return file.string();
}

}  // namespace rtbench
