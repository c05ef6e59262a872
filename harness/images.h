// Images of a run: the shaded ray cast (or, for rays after the first hit, the camera's pixels as
// those rays change them) and a map of the rays whose hit differs from Embree.
// PNGs need OpenImageIO (a build option); without it a run keeps per-ray records (<run>.hits)
// and `rtbench images RESULTS_DIR` writes the PNGs later on a machine that has it.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "kernels/gpu_layout.h"
#include "scene/mesh.h"

namespace rtbench {

// Per pixel: how the kernel's hit compares with Embree's.
enum class HitDiff : std::uint8_t { BothMiss = 0, SameHit = 1, OtherPrimitive = 2, OnlyKernelHit = 3, OnlyEmbreeHit = 4 };

struct HitImage {
    std::uint32_t width = 0, height = 0;
    std::vector<float> shade;        // kernel's hit: |cos| between normal and ray; -1 on a miss
    std::vector<std::uint8_t> diff;  // HitDiff per pixel
    // What a .hits file says of the run it belongs to (readHitRecords): its number ("007", as
    // runs.csv's `run`) and config hash (`config_hash`); empty for a version-1 file.
    std::string run, configHash;
    int fileVersion = 0;  // 1 or 2 when read from a file
};

// Shading of a hit: |cos| between triangle `primitive`'s normal and the ray; -1 for kNoHit.
float shadeHit(const TriangleMesh& mesh, std::uint32_t primitive, const gpu::Ray& ray);
// A hit's grey as the shaded PNG stores it, 8 bits: 40 + 215 shade, rounded; 0 for a miss (shade < 0),
// where the PNG draws its background colour instead.
std::uint8_t pixelGrey(float shade);

// The rays' own hits, ray i at pixel pixels[i] (empty: ray i is pixel i; a pixel with no ray is
// background and BothMiss), shaded by shadeHit; the diff map against Embree's hits.
HitImage makeHitImage(std::uint32_t width, std::uint32_t height, const std::vector<gpu::Ray>& rays,
                      const TriangleMesh& mesh, const std::vector<gpu::HitRecord>& kernel,
                      const std::vector<gpu::HitRecord>& embree, const std::vector<std::uint32_t>& pixels = {});

// A batch of rays after the first hit (rays/workload.h), in the camera's pixels: each pixel
// is shaded as its camera ray's hit (cameraHits), times kUnlitShade where its batch ray hit (a
// shadow ray: occluded) or where it has none (a hit the light does not face); a pixel of several
// rays (ambient occlusion) gets kUnlitShade + (1 - kUnlitShade) x the fraction of them that hit
// nothing. The diff map compares the batch rays' hit or miss with Embree's (BothMiss where a
// pixel has none; a disagreement of any of a pixel's rays shows). pixels[i] is the camera ray
// batch ray i continues.
constexpr float kUnlitShade = 0.3f;
// A camera hit's shade (-1: a miss, kept) with a fraction `lit` of its batch rays unoccluded, as
// makeBatchImage shades it.
float litShade(float shade, float lit);
HitImage makeBatchImage(std::uint32_t width, std::uint32_t height, const std::vector<gpu::Ray>& cameraRays,
                        const std::vector<gpu::HitRecord>& cameraHits, const TriangleMesh& mesh,
                        const std::vector<std::uint32_t>& pixels, const std::vector<gpu::HitRecord>& kernel,
                        const std::vector<gpu::HitRecord>& embree);

// The .hits format, version 2 (all integers little-endian):
//   "RTBHITS2", uint32 width, uint32 height, uint16 n + n bytes of the run number,
//   uint16 m + m bytes of the config hash, width*height float32 shades, width*height HitDiff bytes.
// Version 1 ("RTBHITS1", width, height, shades, diffs) carries no run and no hash; it is still read.
constexpr std::uint32_t kHitsMaxSide = 16384;            // camera.width / camera.height allow no more
constexpr std::size_t kHitsMaxIdBytes = 64;              // run number, config hash
constexpr std::uint64_t kHitsMaxHeaderBytes = 8 + 8 + 2 + kHitsMaxIdBytes + 2 + kHitsMaxIdBytes;
constexpr std::uint64_t kHitsMaxFileBytes =              // the largest file a run can write
    kHitsMaxHeaderBytes + std::uint64_t(kHitsMaxSide) * kHitsMaxSide * 5;

// Writes `path` (version 2) through writeFileAtomically (harness/writers.h): never through a link.
void writeHitRecords(const std::string& path, const HitImage& image, const std::string& run,
                     const std::string& configHash);
// Reads a version 1 or 2 file. Before allocating anything it checks the file (a regular file, not
// a link, at most kHitsMaxFileBytes), the magic, the sides (1 to kHitsMaxSide), the identity
// strings and that the size is exactly the header's plus width*height*5 bytes; then every pixel
// (shade finite in [-1, 1.001], diff 0 to 4). Throws rtbench::Error "PATH: why".
HitImage readHitRecords(const std::string& path);

bool imagesSupported();  // built with OpenImageIO
// Encodes a PNG of width x height RGB8 pixels in memory (throws when built without OpenImageIO).
std::string encodePng(std::uint32_t width, std::uint32_t height, const std::vector<std::uint8_t>& rgb,
                      const std::string& nameForErrors);
// Encodes an OpenEXR image of width x height float values, one channel "Y", in memory (throws
// when built without OpenImageIO).
std::string encodeExr(std::uint32_t width, std::uint32_t height, const std::vector<float>& grey,
                      const std::string& nameForErrors);
// Writes <prefix>-shaded.png and <prefix>-diff.png, and with `exr` <prefix>-shaded.exr (the
// shades in float, a miss 0), each encoded in memory and written through writeFileAtomically;
// throws when built without OpenImageIO.
void writeImages(const std::string& prefix, const HitImage& image, bool exr = false);

// For `rtbench images`: converts every run-NNN.hits file of a folder, in name order. Each file is
// checked against the row of run NNN in the folder's runs.csv (camera_width, camera_height,
// config_hash, and for version 2 the run number it records); a bad file is listed in `failures`
// ("PATH: why") and the others go on. Throws rtbench::Error for what stops them all: not a
// folder, no or unreadable runs.csv, built without OpenImageIO.
struct ImagesReport {
    int written = 0;                    // runs whose two PNGs were written
    std::vector<std::string> failures;  // "PATH: why", one per bad file
    std::vector<std::string> warnings;  // "PATH: what" (version-1 files: no identity to check)
    int hitsFiles() const { return written + int(failures.size()); }
};
ImagesReport imagesForFolder(const std::string& folder);
// The same, all or nothing for the caller: how many runs' PNGs were written, or rtbench::Error
// listing every bad file when one failed (the good ones are written all the same).
int writeImagesForFolder(const std::string& folder);

}  // namespace rtbench
