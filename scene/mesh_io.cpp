#include "mesh_io.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/IO/OBJ.h>
#include <CGAL/IO/OFF.h>
#include <CGAL/IO/PLY.h>
#include <CGAL/IO/STL.h>
#include <archive.h>
#include <archive_entry.h>
#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <map>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include "core/error.h"
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
    const std::string bytes = readInputFile(path, kMaxMeshFileBytes, "mesh file");
    TriangleMesh mesh = readMeshBytes(bytes, path);
    mesh.inputs = {fingerprint(path, bytes)};
    return mesh;
}

namespace {

const fs::path kCgalArchive = "/usr/share/doc/libcgal-demo/data.tar.gz";
constexpr const char* kCgalManifest = ".extracted";  // "NAME.off HASH" per line: written last

fs::path cgalCache() {
    fs::path cache;
    if (const char* env = std::getenv("RTBENCH_CACHE"); env && *env)
        cache = env;
    else if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg)
        cache = fs::path(xdg) / "rtbench";
    else if (const char* home = std::getenv("HOME"); home && *home)
        cache = fs::path(home) / ".cache" / "rtbench";
    else
        cache = fs::temp_directory_path() / ("rtbench-cache-" + std::to_string(::getuid()));
    return cache / "cgal-data";
}

// Writes `bytes` to a new file `path` (never through a symlink, never over a file).
void writeNewFile(const fs::path& path, std::string_view bytes) {
    const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0644);
    if (fd < 0) throw Error(printable(path.string()) + ": cannot create: " + std::strerror(errno));
    std::size_t done = 0;
    while (done < bytes.size()) {
        const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) {
            const int why = errno;
            ::close(fd);
            throw Error(printable(path.string()) + ": write failed: " + std::strerror(why));
        }
        done += std::size_t(n);
    }
    if (::close(fd) != 0) throw Error(printable(path.string()) + ": write failed: " + std::strerror(errno));
}

// Extracts the archive's data/meshes/*.off (regular files with plain names only) into `into`
// with libarchive (no shell, no tar), and writes the manifest of their hashes last.
void extractCgalMeshes(const fs::path& into) {
    struct Reader {
        archive* a = archive_read_new();
        ~Reader() { archive_read_free(a); }
    } reader;
    archive_read_support_filter_gzip(reader.a);
    archive_read_support_format_tar(reader.a);
    if (archive_read_open_filename(reader.a, kCgalArchive.c_str(), 1 << 16) != ARCHIVE_OK)
        throw Error(kCgalArchive.string() + ": cannot open: " + archive_error_string(reader.a));
    std::error_code ec;
    if (!fs::create_directories(into / "meshes", ec) && ec)
        throw Error(printable((into / "meshes").string()) + ": cannot create: " + ec.message());
    std::string manifest;
    archive_entry* entry = nullptr;
    int status;
    while ((status = archive_read_next_header(reader.a, &entry)) == ARCHIVE_OK) {
        const std::string path = archive_entry_pathname(entry) ? archive_entry_pathname(entry) : "";
        const std::string prefix = "data/meshes/";
        if (path.rfind(prefix, 0) != 0 || archive_entry_filetype(entry) != AE_IFREG) continue;
        const std::string name = path.substr(prefix.size());
        if (name.empty() || name.find('/') != std::string::npos || name[0] == '.' ||
            fs::path(name).extension() != ".off")
            continue;
        const la_int64_t size = archive_entry_size(entry);
        if (size < 0 || std::uint64_t(size) > kMaxMeshFileBytes)
            throw Error(kCgalArchive.string() + ": " + path + ": size " + std::to_string(size) + " out of range");
        std::string bytes(std::size_t(size), '\0');
        if (archive_read_data(reader.a, bytes.data(), bytes.size()) != la_ssize_t(bytes.size()))
            throw Error(kCgalArchive.string() + ": " + path + ": cannot read: " + archive_error_string(reader.a));
        writeNewFile(into / "meshes" / name, bytes);
        manifest += name + " " + hex64(fnv1a64(bytes)) + "\n";
    }
    if (status != ARCHIVE_EOF)
        throw Error(kCgalArchive.string() + ": cannot read: " + archive_error_string(reader.a));
    if (manifest.empty()) throw Error(kCgalArchive.string() + ": holds no data/meshes/*.off");
    writeNewFile(into / kCgalManifest, manifest);
}

// The manifest of an extracted cache: file name -> hash; empty when the cache is not whole.
std::map<std::string, std::string> readCgalManifest(const fs::path& cache) {
    std::map<std::string, std::string> hashes;
    std::error_code ec;
    if (!fs::is_regular_file(cache / kCgalManifest, ec)) return hashes;
    std::istringstream lines(readInputFile((cache / kCgalManifest).string(), 1 << 20, "cache manifest"));
    std::string name, hash;
    while (lines >> name >> hash) hashes[name] = hash;
    return hashes;
}

// The extracted cache, extracting it when it is missing or not whole (no manifest: emptied, or
// made by an older rtbench): into a private folder, then renamed, so a concurrent or
// interrupted run never sees a half-extracted cache.
std::map<std::string, std::string> cgalMeshes(const std::string& source) {
    const fs::path cache = cgalCache();
    std::map<std::string, std::string> manifest = readCgalManifest(cache);
    if (!manifest.empty()) return manifest;
    std::error_code ec;
    // One extraction at a time (shards on one cache); a whole cache is never replaced, and it
    // appears by one rename, so readers need no lock.
    fs::create_directories(cache.parent_path(), ec);
    const std::string lockPath = (cache.parent_path() / ".cgal-data.lock").string();
    struct Lock {
        int fd;
        ~Lock() {
            if (fd >= 0) ::close(fd);
        }
    } lock{::open(lockPath.c_str(), O_RDWR | O_CREAT | O_NOFOLLOW | O_CLOEXEC, 0644)};
    if (lock.fd < 0 || ::flock(lock.fd, LOCK_EX) != 0)
        throw Error(source + ": cannot lock " + printable(lockPath) + ": " + std::strerror(errno));
    manifest = readCgalManifest(cache);
    if (!manifest.empty()) return manifest;  // another process extracted it meanwhile
    if (!fs::exists(kCgalArchive, ec))
        throw Error(source + ": " + kCgalArchive.string() + " is missing (install Debian's libcgal-demo: scripts/setup.sh does)");
    std::string pattern = (cache.parent_path() / "cgal-data.tmp.XXXXXX").string();
    if (!::mkdtemp(pattern.data()))
        throw Error(source + ": cannot create a folder in " + printable(cache.parent_path().string()) + ": " +
                    std::strerror(errno));
    const fs::path staging = pattern;
    fs::permissions(staging, fs::perms(0755), ec);  // mkdtemp's 0700: a cache others may read
    std::cerr << "[rtbench] extracting CGAL's meshes once into " << cache << "\n";
    try {
        extractCgalMeshes(staging);
        if (fs::exists(fs::symlink_status(cache, ec))) {  // not whole (emptied, interrupted): replaced
            const fs::path aside = staging.string() + ".old";
            fs::rename(cache, aside, ec);
            fs::remove_all(aside, ec);
        }
        fs::rename(staging, cache, ec);
    } catch (...) {
        fs::remove_all(staging, ec);
        throw;
    }
    fs::remove_all(staging, ec);
    manifest = readCgalManifest(cache);
    if (manifest.empty()) throw Error(source + ": cache " + printable(cache.string()) + " is not whole after extracting");
    return manifest;
}

void checkCgalName(const std::string& name) {
    if (name.empty() || name.find('/') != std::string::npos || name.find("..") != std::string::npos || name[0] == '.')
        throw Error("cgal:" + printable(name) + ": expected a mesh name such as cgal:bunny00");
}

}  // namespace

std::vector<std::string> cgalMeshNames() {
    std::vector<std::string> names;
    for (const auto& [file, hash] : cgalMeshes("cgal:"))
        if (fs::path(file).parent_path().empty() && fs::path(file).extension() == ".off") names.push_back(fs::path(file).stem().string());
    return names;
}

std::size_t editDistance(const std::string& a, const std::string& b) {
    std::vector<std::size_t> row(b.size() + 1);
    for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
    for (std::size_t i = 1; i <= a.size(); ++i) {
        std::size_t diagonal = row[0];
        row[0] = i;
        for (std::size_t j = 1; j <= b.size(); ++j) {
            const std::size_t up = row[j];
            row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
            diagonal = up;
        }
    }
    return row[b.size()];
}

std::vector<std::string> nearestNames(const std::string& name, const std::vector<std::string>& names, std::size_t count) {
    auto lower = [](std::string s) {
        std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return char(std::tolower(c)); });
        return s;
    };
    // Edit distance, case ignored; a name that contains the query comes first.
    const std::string query = lower(name);
    std::vector<std::pair<std::size_t, std::string>> ranked;
    for (const std::string& n : names) {
        const std::string candidate = lower(n);
        ranked.push_back({candidate.find(query) != std::string::npos ? 0 : 1 + editDistance(query, candidate), n});
    }
    std::sort(ranked.begin(), ranked.end());
    std::vector<std::string> nearest;
    for (std::size_t i = 0; i < ranked.size() && i < count; ++i) nearest.push_back(ranked[i].second);
    return nearest;
}

std::string resolveCgalMesh(const std::string& name) {
    checkCgalName(name);
    const std::map<std::string, std::string> manifest = cgalMeshes("cgal:" + name);
    if (!manifest.count(name + ".off")) {
        const std::vector<std::string> names = cgalMeshNames();
        std::string nearest;
        for (const std::string& n : nearestNames(name, names, 5)) nearest += (nearest.empty() ? "" : ", ") + n;
        throw Error("cgal:" + printable(name) + ": no such mesh in libcgal-demo (" + std::to_string(names.size()) +
                    " meshes; nearest: " + nearest + "; `rtbench meshes` lists them)");
    }
    return (cgalCache() / "meshes" / (name + ".off")).string();
}

TriangleMesh readCgalMesh(const std::string& name) {
    const std::string path = resolveCgalMesh(name);
    const std::string bytes = readInputFile(path, kMaxMeshFileBytes, "mesh file");
    const std::string expected = cgalMeshes("cgal:" + name).at(name + ".off");
    if (hex64(fnv1a64(bytes)) != expected)
        throw Error("cgal:" + printable(name) + ": " + printable(path) +
                    " differs from the file extracted from libcgal-demo (changed since); remove " +
                    printable(cgalCache().string()) + " to extract it again");
    TriangleMesh mesh = readMeshBytes(bytes, path);
    mesh.name = "cgal:" + name;
    mesh.inputs = {fingerprint(path, bytes)};
    return mesh;
}

}  // namespace rtbench
