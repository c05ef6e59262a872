#include "mesh_io.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/IO/OBJ.h>
#include <CGAL/IO/OFF.h>
#include <CGAL/IO/PLY.h>
#include <CGAL/IO/STL.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include "error.h"
#include "mesh_validate.h"
#include "polygon_triangulation.h"

namespace rtbench {
namespace fs = std::filesystem;

namespace {

using Point = CGAL::Exact_predicates_inexact_constructions_kernel::Point_3;

// Sends whatever a reader prints (CGAL's verbose messages, binary STL headers) into buffers for
// the scope's lifetime: nothing from a mesh file reaches stdout or stderr.
class CaptureStdStreams {
  public:
    CaptureStdStreams()
        : savedOut_(std::cout.rdbuf(out_.rdbuf())), savedErr_(std::cerr.rdbuf(err_.rdbuf())) {}
    ~CaptureStdStreams() {
        std::cout.rdbuf(savedOut_);
        std::cerr.rdbuf(savedErr_);
    }
    CaptureStdStreams(const CaptureStdStreams&) = delete;
    CaptureStdStreams& operator=(const CaptureStdStreams&) = delete;
    std::string errors() const { return err_.str(); }

  private:
    std::ostringstream out_, err_;
    std::streambuf* savedOut_;
    std::streambuf* savedErr_;
};

// CGAL's reader for the validated format, on the file's bytes or their normalized copy.
bool readWithCgal(std::string_view bytes, const ValidatedMesh& source, std::vector<Point>& points,
                  std::vector<std::vector<std::size_t>>& polygons) {
    std::istringstream in(source.normalized.empty() ? std::string(bytes) : source.normalized,
                          std::ios::in | std::ios::binary);
    const auto verbose = CGAL::parameters::verbose(true);
    switch (source.format) {
        case MeshFormat::Off:
            return CGAL::IO::read_OFF(in, points, polygons, verbose);
        case MeshFormat::Obj:
            return CGAL::IO::read_OBJ(in, points, polygons, verbose);
        case MeshFormat::PlyAscii:
        case MeshFormat::PlyBinary:
            return CGAL::IO::read_PLY(in, points, polygons, verbose);
        // CGAL::IO::read_STL guesses the mode from the first 6 bytes and takes "solid\tname"
        // for binary; validation decided the mode, so call that mode's parser.
        case MeshFormat::StlAscii:
            return CGAL::IO::internal::parse_ASCII_STL(in, points, polygons, true);
        case MeshFormat::StlBinary:
            return CGAL::IO::internal::parse_binary_STL(in, points, polygons, true);
    }
    return false;
}

}  // namespace

TriangleMesh readMeshBytes(std::string_view bytes, const std::string& nameWithExtension) {
    const std::string& name = nameWithExtension;
    const ValidatedMesh source = validateMesh(bytes, name);
    std::vector<Point> points;
    std::vector<std::vector<std::size_t>> polygons;
    bool ok = false;
    std::string said;
    {
        CaptureStdStreams capture;
        try {
            ok = readWithCgal(bytes, source, points, polygons);
        } catch (const std::exception& e) {
            said = e.what();
        }
        said += capture.errors();
    }
    while (!said.empty() && (said.back() == '\n' || said.back() == ' ')) said.pop_back();
    for (char& c : said)
        if (c == '\n') c = ' ';
    // Validation accepted the file, so the reader must read exactly what validation counted.
    const bool stl =
        source.format == MeshFormat::StlAscii || source.format == MeshFormat::StlBinary;
    if (!ok || polygons.size() != source.faces || (!stl && points.size() != source.vertices))
        throw Error(printable(name) +
                    ": the CGAL reader failed on a file that passed validation (it read " +
                    std::to_string(points.size()) + " vertices and " +
                    std::to_string(polygons.size()) + " faces where validation found " +
                    std::to_string(source.vertices) + " and " + std::to_string(source.faces) + ")" +
                    (said.empty() ? "" : ": " + printable(said)));

    TriangleMesh mesh;
    mesh.name = name;
    mesh.polygonsRead = polygons.size();
    mesh.elementsSkipped = source.elementsSkipped;
    mesh.elementsSkippedWhat = source.skippedWhat;
    mesh.vertices.reserve(points.size());
    for (const Point& p : points)  // validation: finite, within single precision
        mesh.vertices.emplace_back(static_cast<float>(p.x()), static_cast<float>(p.y()),
                                   static_cast<float>(p.z()));
    mesh.triangles.reserve(polygons.size());
    for (std::size_t f = 0; f < polygons.size(); ++f)
        if (const std::string why = triangulatePolygon(mesh.vertices, polygons[f], mesh.triangles);
            !why.empty())
            throw Error(printable(source.faceLocation(name, f)) + ": face " + std::to_string(f) +
                        " (" + std::to_string(polygons[f].size()) +
                        " vertices) cannot be triangulated: " + why);
    return mesh;
}

TriangleMesh readMeshFile(const std::string& path) {
    std::error_code ec;
    if (!fs::exists(path, ec)) throw Error(printable(path) + ": mesh file not found");
    if (!fs::is_regular_file(path, ec)) throw Error(printable(path) + ": not a regular file");
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error(printable(path) + ": cannot open for reading");
    std::ostringstream bytes;
    bytes << in.rdbuf();
    if (in.bad()) throw Error(printable(path) + ": read error");
    return readMeshBytes(bytes.view(), path);
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
        const std::string command =
            "tar -xzf '" + archive.string() + "' -C '" + staging.string() + "' data/meshes";
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
        if (!fs::exists(meshes))
            throw Error("cgal:" + name + ": cache " + meshes.string() + " missing");
    }
    const fs::path file = meshes / (name + ".off");
    if (!fs::exists(file)) {
        std::string some;
        int n = 0;
        for (const auto& entry : fs::directory_iterator(meshes))
            if (entry.path().extension() == ".off" && n++ < 8)
                some += " " + entry.path().stem().string();
        throw Error("cgal:" + name + ": no such mesh in libcgal-demo (some that exist:" + some +
                    ")");
    }
    return file.string();
}

}  // namespace rtbench
