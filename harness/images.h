// Images of a run: the shaded ray cast and a map of the rays whose hit differs from Embree.
// PNGs need OpenImageIO (a build option); without it a run keeps per-ray records (<run>.hits)
// and `rtbench images RESULTS_DIR` writes the PNGs later on a machine that has it.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "kernels/gpu_layout.h"
#include "structures/mesh.h"

namespace rtbench {

// Per pixel: how the kernel's hit compares with Embree's.
enum class HitDiff : std::uint8_t { BothMiss = 0, SameHit = 1, OtherPrimitive = 2, OnlyKernelHit = 3, OnlyEmbreeHit = 4 };

struct HitImage {
    std::uint32_t width = 0, height = 0;
    std::vector<float> shade;        // kernel's hit: |cos| between normal and ray; -1 on a miss
    std::vector<std::uint8_t> diff;  // HitDiff per pixel
};

// Shading of a hit: |cos| between triangle `primitive`'s normal and the ray; -1 for kNoHit.
float shadeHit(const TriangleMesh& mesh, std::uint32_t primitive, const gpu::Ray& ray);
// A hit's grey as the shaded PNG stores it, 8 bits: 40 + 215 shade, rounded; 0 for a miss (shade < 0),
// where the PNG draws its background colour instead.
std::uint8_t pixelGrey(float shade);

HitImage makeHitImage(std::uint32_t width, std::uint32_t height, const std::vector<gpu::Ray>& rays,
                      const TriangleMesh& mesh, const std::vector<gpu::HitRecord>& kernel,
                      const std::vector<gpu::HitRecord>& embree);

void writeHitRecords(const std::string& path, const HitImage& image);
HitImage readHitRecords(const std::string& path);

bool imagesSupported();  // built with OpenImageIO
// Writes <prefix>-shaded.png and <prefix>-diff.png; throws when built without OpenImageIO.
void writeImages(const std::string& prefix, const HitImage& image);

// For `rtbench images`: converts every *.hits file in a folder; returns how many.
int writeImagesForFolder(const std::string& folder);

}  // namespace rtbench
