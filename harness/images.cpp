#include "images.h"

#include "output_folder.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <map>

#include "harness/writers.h"
#include "core/error.h"
#include "core/text.h"

#ifdef RTBENCH_WITH_OIIO
#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>
#endif

namespace rtbench {

namespace fs = std::filesystem;

namespace {
constexpr char kMagicV1[8] = {'R', 'T', 'B', 'H', 'I', 'T', 'S', '1'};
constexpr char kMagicV2[8] = {'R', 'T', 'B', 'H', 'I', 'T', 'S', '2'};
constexpr float kMaxShade = 1.001f;  // |cos| of a hit, with room for its float rounding

void putU16(std::string& out, std::uint16_t v) {
    out += char(v & 0xff);
    out += char(v >> 8);
}
void putU32(std::string& out, std::uint32_t v) {
    for (int k = 0; k < 4; ++k) out += char((v >> (8 * k)) & 0xff);
}
std::uint32_t getU32(const unsigned char* p) {
    return std::uint32_t(p[0]) | std::uint32_t(p[1]) << 8 | std::uint32_t(p[2]) << 16 | std::uint32_t(p[3]) << 24;
}
std::uint16_t getU16(const unsigned char* p) {
    return std::uint16_t(p[0] | p[1] << 8);
}

// A run number or config hash as the header holds it: at most kHitsMaxIdBytes printable ASCII
// bytes, neither empty.
bool plainId(const std::string& s) {
    return !s.empty() && s.size() <= kHitsMaxIdBytes &&
           std::all_of(s.begin(), s.end(), [](char c) { return c > ' ' && c < 127; });
}

// "run-NNN.hits" -> "NNN" (digits only), else "".
std::string runOfFileName(const std::string& fileName) {
    const std::string prefix = "run-", suffix = ".hits";
    if (fileName.size() <= prefix.size() + suffix.size() || fileName.rfind(prefix, 0) != 0 ||
        fileName.compare(fileName.size() - suffix.size(), suffix.size(), suffix) != 0)
        return "";
    const std::string digits = fileName.substr(prefix.size(), fileName.size() - prefix.size() - suffix.size());
    if (digits.size() > 9 || !std::all_of(digits.begin(), digits.end(), [](char c) { return c >= '0' && c <= '9'; }))
        return "";
    return digits;
}

// Reads exactly `size` bytes at the file's current offset; false at an early end.
bool readFully(int fd, void* data, std::size_t size) {
    auto* p = static_cast<char*>(data);
    while (size > 0) {
        const ssize_t got = ::read(fd, p, std::min<std::size_t>(size, std::size_t(1) << 30));
        if (got < 0 && errno == EINTR) continue;
        if (got <= 0) return false;
        p += got;
        size -= std::size_t(got);
    }
    return true;
}

struct FileDescriptor {
    int fd = -1;
    ~FileDescriptor() {
        if (fd >= 0) ::close(fd);
    }
};

}  // namespace

HitImage makeHitImage(std::uint32_t width, std::uint32_t height, const std::vector<gpu::Ray>& rays,
                      const TriangleMesh& mesh, const std::vector<gpu::HitRecord>& kernel,
                      const std::vector<gpu::HitRecord>& embree, const std::vector<std::uint32_t>& pixels) {
    HitImage image;
    image.width = width;
    image.height = height;
    image.shade.assign(std::size_t(width) * height, -1.0f);
    image.diff.assign(std::size_t(width) * height, static_cast<std::uint8_t>(HitDiff::BothMiss));
    for (std::size_t i = 0; i < rays.size(); ++i) {
        const bool hit = kernel[i].primitive != gpu::kNoHit, refHit = embree[i].primitive != gpu::kNoHit;
        HitDiff d = !hit && !refHit              ? HitDiff::BothMiss
                    : hit && !refHit             ? HitDiff::OnlyKernelHit
                    : !hit && refHit             ? HitDiff::OnlyEmbreeHit
                    : kernel[i].primitive == embree[i].primitive ? HitDiff::SameHit
                                                                 : HitDiff::OtherPrimitive;
        const std::size_t pixel = pixels.empty() ? i : pixels[i];
        image.diff[pixel] = static_cast<std::uint8_t>(d);
        image.shade[pixel] = shadeHit(mesh, kernel[i].primitive, rays[i]);
    }
    return image;
}

HitImage makeBatchImage(std::uint32_t width, std::uint32_t height, const std::vector<gpu::Ray>& cameraRays,
                        const std::vector<gpu::HitRecord>& cameraHits, const TriangleMesh& mesh,
                        const std::vector<std::uint32_t>& pixels, const std::vector<gpu::HitRecord>& kernel,
                        const std::vector<gpu::HitRecord>& embree) {
    HitImage image;
    image.width = width;
    image.height = height;
    image.shade.assign(cameraRays.size(), -1.0f);
    image.diff.assign(cameraRays.size(), static_cast<std::uint8_t>(HitDiff::BothMiss));
    // Per pixel: its batch rays, and those that hit nothing (lit, unoccluded).
    std::vector<std::uint32_t> raysAt(cameraRays.size(), 0), litAt(cameraRays.size(), 0);
    for (std::size_t i = 0; i < pixels.size(); ++i) {
        const bool hit = kernel[i].primitive != gpu::kNoHit, refHit = embree[i].primitive != gpu::kNoHit;
        const HitDiff d = hit == refHit ? (hit ? HitDiff::SameHit : HitDiff::BothMiss)
                                        : (hit ? HitDiff::OnlyKernelHit : HitDiff::OnlyEmbreeHit);
        std::uint8_t& diff = image.diff[pixels[i]];
        const bool agreed = diff == static_cast<std::uint8_t>(HitDiff::SameHit) || diff == static_cast<std::uint8_t>(HitDiff::BothMiss);
        if (agreed) diff = static_cast<std::uint8_t>(d);  // a pixel of several rays shows a disagreement of any
        ++raysAt[pixels[i]];
        litAt[pixels[i]] += !hit;
    }
    for (std::size_t p = 0; p < cameraRays.size(); ++p) {
        const float shade = shadeHit(mesh, cameraHits[p].primitive, cameraRays[p]);
        image.shade[p] = litShade(shade, raysAt[p] ? float(litAt[p]) / float(raysAt[p]) : 0.0f);
    }
    return image;
}

float litShade(float shade, float lit) { return shade < 0.0f ? shade : shade * (kUnlitShade + (1.0f - kUnlitShade) * lit); }

float shadeHit(const TriangleMesh& mesh, std::uint32_t primitive, const gpu::Ray& ray) {
    if (primitive == gpu::kNoHit) return -1.0f;
    const glm::uvec3 t = mesh.triangles[primitive];
    const glm::vec3 v0 = mesh.vertices[t.x], v1 = mesh.vertices[t.y], v2 = mesh.vertices[t.z];
    const glm::vec3 n = glm::cross(v1 - v0, v2 - v0);
    const glm::vec3 dir(ray.directionTMax);
    const float len = glm::length(n) * glm::length(dir);
    return len > 0.0f ? std::abs(glm::dot(n, dir)) / len : 0.0f;
}

std::uint8_t pixelGrey(float shade) {
    return shade < 0.0f ? 0 : static_cast<std::uint8_t>(std::lround(40.0f + 215.0f * shade));
}

void writeHitRecords(const std::string& path, const HitImage& image, const std::string& run,
                     const std::string& configHash) {
    const std::string at = printable(path) + ": ";
    if (image.width == 0 || image.height == 0 || image.width > kHitsMaxSide || image.height > kHitsMaxSide)
        throw Error(at + "cannot write hit records of " + std::to_string(image.width) + " x " +
                    std::to_string(image.height) + " pixels (allowed: 1 to " + std::to_string(kHitsMaxSide) + " a side)");
    const std::size_t n = std::size_t(image.width) * image.height;
    if (image.shade.size() != n || image.diff.size() != n)
        throw Error(at + "hit records of " + std::to_string(image.width) + " x " + std::to_string(image.height) +
                    " pixels with " + std::to_string(image.shade.size()) + " shades and " +
                    std::to_string(image.diff.size()) + " diffs");
    if (!plainId(run) || !plainId(configHash))
        throw Error(at + "the run number '" + printable(run) + "' and config hash '" + printable(configHash) +
                    "' must be 1 to " + std::to_string(kHitsMaxIdBytes) + " printable characters");
    std::string bytes(kMagicV2, 8);
    bytes.reserve(kHitsMaxHeaderBytes + n * 5);
    putU32(bytes, image.width);
    putU32(bytes, image.height);
    putU16(bytes, std::uint16_t(run.size()));
    bytes += run;
    putU16(bytes, std::uint16_t(configHash.size()));
    bytes += configHash;
    for (float s : image.shade) {
        std::uint32_t bits;
        std::memcpy(&bits, &s, 4);
        putU32(bytes, bits);
    }
    bytes.append(reinterpret_cast<const char*>(image.diff.data()), n);
    writeFileAtomically(path, bytes);
}

namespace {

// The hit-record file opened for reading: a regular file (never through a link), of a size a
// hit-record file can have.
std::uint64_t openHitRecords(const std::string& path, const std::string& at, FileDescriptor& file) {
    // O_NOFOLLOW: a link is refused (ELOOP); O_NONBLOCK: a FIFO does not block the open.
    file.fd = ::open(path.c_str(), O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC);
    if (file.fd < 0)
        throw Error(at + (errno == ELOOP ? std::string("is a symbolic link (hit records are read only from regular files)")
                                         : "cannot open hit records: " + std::string(std::strerror(errno))));
    struct stat st {};
    if (::fstat(file.fd, &st) != 0) throw Error(at + "cannot stat hit records: " + std::strerror(errno));
    if (!S_ISREG(st.st_mode)) throw Error(at + "not a regular file");
    const std::uint64_t size = std::uint64_t(st.st_size);
    if (size > kHitsMaxFileBytes)
        throw Error(at + "hit-record file of " + std::to_string(size) + " bytes, more than the " +
                    std::to_string(kHitsMaxFileBytes) + " of the largest image (" + std::to_string(kHitsMaxSide) +
                    " x " + std::to_string(kHitsMaxSide) + ")");
    if (size < 16)
        throw Error(at + "truncated: " + std::to_string(size) + " bytes, shorter than a hit-record header (16 bytes)");
    return size;
}

// Version 2's two length-prefixed strings after the 16 fixed bytes: the run number, the config
// hash. Returns the header's length.
std::uint64_t readHeaderIds(const unsigned char* header, std::size_t headerRead, const std::string& at, HitImage& image) {
    std::uint64_t headerBytes = 16;
    for (std::string* id : {&image.run, &image.configHash}) {
        const char* what = id == &image.run ? "run number" : "config hash";
        if (headerBytes + 2 > headerRead) throw Error(at + "truncated: the file ends in the header, before its " + what);
        const std::uint16_t length = getU16(header + headerBytes);
        headerBytes += 2;
        if (length == 0 || length > kHitsMaxIdBytes)
            throw Error(at + "the header's " + what + " has " + std::to_string(length) + " bytes (allowed: 1 to " +
                        std::to_string(kHitsMaxIdBytes) + ")");
        if (headerBytes + length > headerRead) throw Error(at + "truncated: the file ends in the header, inside its " + what);
        id->assign(reinterpret_cast<const char*>(header + headerBytes), length);
        headerBytes += length;
        if (!plainId(*id)) throw Error(at + "the header's " + what + " '" + printable(*id) + "' is not printable ASCII");
    }
    return headerBytes;
}

// The header: magic, size and (version 2) ids into `image`. Returns the header's length.
std::uint64_t readHitHeader(int fd, std::uint64_t size, const std::string& at, HitImage& image) {
    unsigned char header[kHitsMaxHeaderBytes];
    const std::size_t headerRead = std::size_t(std::min<std::uint64_t>(size, kHitsMaxHeaderBytes));
    if (!readFully(fd, header, headerRead)) throw Error(at + "read error in the header");
    if (std::memcmp(header, kMagicV2, 8) == 0)
        image.fileVersion = 2;
    else if (std::memcmp(header, kMagicV1, 8) == 0)
        image.fileVersion = 1;
    else
        throw Error(at + "not an rtbench hit-record file (its first 8 bytes are '" +
                    printable(std::string_view(reinterpret_cast<const char*>(header), 8)) +
                    "', expected 'RTBHITS2' or 'RTBHITS1')");
    image.width = getU32(header + 8);
    image.height = getU32(header + 12);
    if (image.width == 0 || image.height == 0 || image.width > kHitsMaxSide || image.height > kHitsMaxSide)
        throw Error(at + "the header claims " + std::to_string(image.width) + " x " + std::to_string(image.height) +
                    " pixels (allowed: 1 to " + std::to_string(kHitsMaxSide) + " a side, as camera.width and camera.height)");
    return image.fileVersion == 2 ? readHeaderIds(header, headerRead, at, image) : 16;
}

// The pixels after the header (the file's size known to match): shades and diffs, each in range.
void readHitPixels(int fd, std::uint64_t headerBytes, const std::string& at, HitImage& image) {
    if (::lseek(fd, off_t(headerBytes), SEEK_SET) != off_t(headerBytes))
        throw Error(at + "cannot seek past the header: " + std::strerror(errno));
    const std::size_t n = std::size_t(image.width) * image.height;
    std::vector<unsigned char> raw(n * 4);
    image.shade.resize(n);
    image.diff.resize(n);
    if (!readFully(fd, raw.data(), raw.size()) || !readFully(fd, image.diff.data(), n))
        throw Error(at + "truncated while reading (did the file change?)");
    auto pixel = [&](std::size_t i) {
        return "pixel " + std::to_string(i) + " (x " + std::to_string(i % image.width) + ", y " + std::to_string(i / image.width) + ")";
    };
    for (std::size_t i = 0; i < n; ++i) {
        const std::uint32_t bits = getU32(raw.data() + 4 * i);
        std::memcpy(&image.shade[i], &bits, 4);
        const float s = image.shade[i];
        if (!(s >= -1.0f && s <= kMaxShade))
            throw Error(at + pixel(i) + " has shade " + std::to_string(s) + " (allowed: -1 for a miss, 0 to 1 for a hit)");
        if (image.diff[i] > std::uint8_t(HitDiff::OnlyEmbreeHit))
            throw Error(at + pixel(i) + " has diff value " + std::to_string(image.diff[i]) + " (allowed: 0 to 4)");
    }
}

}  // namespace

HitImage readHitRecords(const std::string& path) {
    const std::string at = printable(path) + ": ";
    FileDescriptor file;
    const std::uint64_t size = openHitRecords(path, at, file);
    HitImage image;
    const std::uint64_t headerBytes = readHitHeader(file.fd, size, at, image);
    const std::uint64_t pixels = std::uint64_t(image.width) * image.height;
    const std::uint64_t expected = headerBytes + pixels * 5;
    if (size != expected)
        throw Error(at + (size < expected ? "truncated: " : "wrong size: ") + std::to_string(size) +
                    " bytes, but a header of " + std::to_string(image.width) + " x " + std::to_string(image.height) +
                    " pixels needs exactly " + std::to_string(headerBytes) + " + 5 x " + std::to_string(pixels) +
                    " = " + std::to_string(expected));
    // Only now, with the size known to match, the pixels.
    readHitPixels(file.fd, headerBytes, at, image);
    return image;
}

bool imagesSupported() {
#ifdef RTBENCH_WITH_OIIO
    return true;
#else
    return false;
#endif
}

#ifdef RTBENCH_WITH_OIIO
namespace {

// `pixels` (spec's size, channels and type) encoded by OpenImageIO's `format` writer into memory
// (an IOVecOutput proxy): the file is written by writeFileAtomically, never here. `kind` names
// the format in messages ("PNG", "OpenEXR").
std::string encodeInMemory(const char* format, const char* kind, const OIIO::ImageSpec& spec, const void* pixels,
                           const std::string& nameForErrors) {
    const std::string at = printable(nameForErrors) + ": ";
    std::vector<unsigned char> bytes;
    OIIO::Filesystem::IOVecOutput memory(bytes);
    auto out = OIIO::ImageOutput::create(format, &memory);
    if (!out) throw Error(at + "OpenImageIO cannot create a " + kind + " writer: " + OIIO::geterror());
    if (!out->supports("ioproxy")) throw Error(at + "OpenImageIO's " + kind + " writer cannot write into memory");
    if (!out->open(nameForErrors, spec) || !out->write_image(spec.format, pixels) || !out->close())
        throw Error(at + "OpenImageIO's " + kind + " encoding failed: " + out->geterror());
    if (bytes.empty()) throw Error(at + "OpenImageIO's " + kind + " encoding wrote nothing");
    return std::string(reinterpret_cast<const char*>(bytes.data()), bytes.size());
}

}  // namespace
#endif

std::string encodePng(std::uint32_t width, std::uint32_t height, const std::vector<std::uint8_t>& rgb,
                      const std::string& nameForErrors) {
#ifdef RTBENCH_WITH_OIIO
    if (rgb.size() != std::size_t(width) * height * 3)
        throw Error(printable(nameForErrors) + ": a PNG of " + std::to_string(width) + " x " + std::to_string(height) +
                    " needs " + std::to_string(std::size_t(width) * height * 3) + " bytes of RGB, given " +
                    std::to_string(rgb.size()));
    return encodeInMemory("png", "PNG", OIIO::ImageSpec(int(width), int(height), 3, OIIO::TypeDesc::UINT8), rgb.data(),
                          nameForErrors);
#else
    (void)width, (void)height, (void)rgb;
    throw Error(printable(nameForErrors) + ": built without OpenImageIO (RTBENCH_WITH_OIIO=OFF): cannot encode PNGs");
#endif
}

std::string encodeExr(std::uint32_t width, std::uint32_t height, const std::vector<float>& grey,
                      const std::string& nameForErrors) {
#ifdef RTBENCH_WITH_OIIO
    if (grey.size() != std::size_t(width) * height)
        throw Error(printable(nameForErrors) + ": an EXR of " + std::to_string(width) + " x " + std::to_string(height) +
                    " needs " + std::to_string(std::size_t(width) * height) + " values, given " + std::to_string(grey.size()));
    OIIO::ImageSpec spec(int(width), int(height), 1, OIIO::TypeDesc::FLOAT);
    spec.channelnames = {"Y"};  // one luminance channel: the grey shade
    return encodeInMemory("openexr", "OpenEXR", spec, grey.data(), nameForErrors);
#else
    (void)width, (void)height, (void)grey;
    throw Error(printable(nameForErrors) + ": built without OpenImageIO (RTBENCH_WITH_OIIO=OFF): cannot encode EXRs");
#endif
}

void writeImages(const std::string& prefix, const HitImage& image, bool exr) {
#ifdef RTBENCH_WITH_OIIO
    const std::size_t n = std::size_t(image.width) * image.height;
    if (image.shade.size() != n || image.diff.size() != n)
        throw Error(printable(prefix) + ": an image of " + std::to_string(image.width) + " x " +
                    std::to_string(image.height) + " pixels with " + std::to_string(image.shade.size()) +
                    " shades and " + std::to_string(image.diff.size()) + " diffs");
    std::vector<std::uint8_t> shaded(n * 3), diff(n * 3);
    for (std::size_t i = 0; i < n; ++i) {
        const float s = image.shade[i];
        const std::uint8_t grey = pixelGrey(s);
        const std::uint8_t bg[3] = {24, 28, 40};
        for (int c = 0; c < 3; ++c) shaded[i * 3 + c] = s < 0.0f ? bg[c] : grey;
        // Agreeing pixels are dimmed; disagreements in colour: red = only the kernel hit,
        // blue = only Embree hit, yellow = both hit different triangles.
        std::uint8_t rgb[3];
        switch (static_cast<HitDiff>(image.diff[i])) {
            case HitDiff::OnlyKernelHit: rgb[0] = 255, rgb[1] = 0, rgb[2] = 0; break;
            case HitDiff::OnlyEmbreeHit: rgb[0] = 0, rgb[1] = 128, rgb[2] = 255; break;
            case HitDiff::OtherPrimitive: rgb[0] = 255, rgb[1] = 220, rgb[2] = 0; break;
            default: rgb[0] = rgb[1] = rgb[2] = static_cast<std::uint8_t>(s < 0.0f ? 0 : grey / 3);
        }
        std::memcpy(&diff[i * 3], rgb, 3);
    }
    // Every file encoded before any is written: a failed encoding leaves none half-made.
    const std::string shadedPath = prefix + "-shaded.png", diffPath = prefix + "-diff.png", exrPath = prefix + "-shaded.exr";
    const std::string shadedPng = encodePng(image.width, image.height, shaded, shadedPath);
    const std::string diffPng = encodePng(image.width, image.height, diff, diffPath);
    std::string shadedExr;
    if (exr) {
        std::vector<float> grey(n);
        for (std::size_t i = 0; i < n; ++i) grey[i] = std::max(image.shade[i], 0.0f);  // a miss: 0
        shadedExr = encodeExr(image.width, image.height, grey, exrPath);
    }
    writeFileAtomically(shadedPath, shadedPng);
    writeFileAtomically(diffPath, diffPng);
    if (exr) writeFileAtomically(exrPath, shadedExr);
#else
    (void)image, (void)exr;
    throw Error(prefix + ": built without OpenImageIO (RTBENCH_WITH_OIIO=OFF): keep hit records and run `rtbench images`");
#endif
}

ImagesReport imagesForFolder(const std::string& folder) {
    const std::string name = printable(folder);
    std::error_code ec;
    if (!fs::exists(folder, ec)) throw Error(name + ": not a results folder (no such folder)");
    if (!fs::is_directory(folder, ec)) throw Error(name + ": not a results folder (not a folder)");
    if (!imagesSupported())
        throw Error(name + ": built without OpenImageIO (RTBENCH_WITH_OIIO=OFF): `rtbench images` needs it");
    const fs::path csv = fs::path(folder) / "runs.csv";
    if (!fs::exists(csv, ec))
        throw Error(name + ": no runs.csv to check the hit records against (for shards: rtbench merge first)");
    // It writes the folder as a run does: never through a link, not while a run writes it.
    refuseSymlinks(folder);
    const OutputFolderLock lock(folder);
    // The runs.csv row of each run: by run number, each once.
    std::map<std::string, Row> rows;
    std::map<std::string, int> seen;
    for (Row& row : readCsv(csv.string()))
        if (auto r = row.find("run"); r != row.end()) {
            ++seen[r->second];
            rows[r->second] = std::move(row);
        }
    std::vector<fs::path> hits;
    for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec))
        if (it->path().extension() == ".hits") hits.push_back(it->path());
    if (ec) throw Error(name + ": cannot list the folder: " + ec.message());
    std::sort(hits.begin(), hits.end());
    if (hits.empty())
        throw Error(name + ": no .hits files (a run keeps them with output.hit_records = true, or when built "
                           "without OpenImageIO)");

    ImagesReport report;
    for (const fs::path& path : hits) {
        const std::string file = path.string(), at = printable(file) + ": ";
        try {
            const std::string run = runOfFileName(path.filename().string());
            if (run.empty()) throw Error(at + "not named run-NNN.hits (the run number names its runs.csv row)");
            if (!rows.count(run)) throw Error(at + "runs.csv has no row for run " + run);
            if (seen[run] > 1)
                throw Error(at + "runs.csv has " + std::to_string(seen[run]) + " rows for run " + run);
            const Row& row = rows[run];
            auto column = [&](const std::string& key) {
                const auto c = row.find(key);
                if (c == row.end() || c->second.empty())
                    throw Error(at + "runs.csv's row of run " + run + " has no " + key);
                return c->second;
            };
            const std::string width = column("camera_width"), height = column("camera_height"),
                              hash = column("config_hash");
            const HitImage image = readHitRecords(file);
            if (std::to_string(image.width) != width || std::to_string(image.height) != height)
                throw Error(at + "holds " + std::to_string(image.width) + " x " + std::to_string(image.height) +
                            " pixels, but run " + run + " of runs.csv is " + width + " x " + height);
            if (image.fileVersion >= 2) {
                if (image.run != run)
                    throw Error(at + "holds the hit records of run " + printable(image.run) + ", not of run " + run);
                if (image.configHash != hash)
                    throw Error(at + "holds hit records of config hash " + printable(image.configHash) + ", but run " +
                                run + " of runs.csv has config hash " + hash + " (from another sweep?)");
            } else {
                report.warnings.push_back(at + "a version 1 file (RTBHITS1): it records no run or config hash, so only "
                                               "its name and size were checked against runs.csv");
            }
            writeImages((path.parent_path() / path.stem()).string(), image);
            ++report.written;
        } catch (const std::exception& e) {
            const std::string what = e.what();
            // Every message names the file; one from elsewhere (e.g. the file system) gets it here.
            report.failures.push_back(what.rfind(printable(file), 0) == 0 ? what : at + what);
        }
    }
    return report;
}

int writeImagesForFolder(const std::string& folder) {
    const ImagesReport report = imagesForFolder(folder);
    if (report.failures.empty()) return report.written;
    std::string message = std::to_string(report.failures.size()) + " of " + std::to_string(report.hitsFiles()) +
                          " hit-record files failed";
    for (const std::string& f : report.failures) message += "\n  " + f;
    throw Error(message);
}

}  // namespace rtbench
