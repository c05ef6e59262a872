#include "images.h"

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "structures/error.h"

#ifdef RTBENCH_WITH_OIIO
#include <OpenImageIO/imageio.h>
#endif

namespace rtbench {

namespace {
constexpr char kMagic[8] = {'R', 'T', 'B', 'H', 'I', 'T', 'S', '1'};
}

HitImage makeHitImage(std::uint32_t width, std::uint32_t height, const std::vector<gpu::Ray>& rays,
                      const TriangleMesh& mesh, const std::vector<gpu::HitRecord>& kernel,
                      const std::vector<gpu::HitRecord>& embree) {
    HitImage image;
    image.width = width;
    image.height = height;
    image.shade.assign(rays.size(), -1.0f);
    image.diff.assign(rays.size(), 0);
    for (std::size_t i = 0; i < rays.size(); ++i) {
        const bool hit = kernel[i].primitive != gpu::kNoHit, refHit = embree[i].primitive != gpu::kNoHit;
        HitDiff d = !hit && !refHit              ? HitDiff::BothMiss
                    : hit && !refHit             ? HitDiff::OnlyKernelHit
                    : !hit && refHit             ? HitDiff::OnlyEmbreeHit
                    : kernel[i].primitive == embree[i].primitive ? HitDiff::SameHit
                                                                 : HitDiff::OtherPrimitive;
        image.diff[i] = static_cast<std::uint8_t>(d);
        image.shade[i] = shadeHit(mesh, kernel[i].primitive, rays[i]);
    }
    return image;
}

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

void writeHitRecords(const std::string& path, const HitImage& image) {
    std::ofstream out(path + ".tmp", std::ios::binary | std::ios::trunc);
    if (!out) throw Error(path + ": cannot open for writing");
    out.write(kMagic, 8);
    out.write(reinterpret_cast<const char*>(&image.width), 4);
    out.write(reinterpret_cast<const char*>(&image.height), 4);
    out.write(reinterpret_cast<const char*>(image.shade.data()), image.shade.size() * 4);
    out.write(reinterpret_cast<const char*>(image.diff.data()), image.diff.size());
    out.close();
    if (!out) throw Error(path + ": write failed");
    std::filesystem::rename(path + ".tmp", path);
}

HitImage readHitRecords(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error(path + ": cannot open hit records");
    char magic[8];
    HitImage image;
    in.read(magic, 8);
    in.read(reinterpret_cast<char*>(&image.width), 4);
    in.read(reinterpret_cast<char*>(&image.height), 4);
    if (!in || std::memcmp(magic, kMagic, 8) != 0) throw Error(path + ": not an rtbench hit-record file");
    const std::size_t n = std::size_t(image.width) * image.height;
    image.shade.resize(n);
    image.diff.resize(n);
    in.read(reinterpret_cast<char*>(image.shade.data()), n * 4);
    in.read(reinterpret_cast<char*>(image.diff.data()), n);
    if (!in) throw Error(path + ": truncated hit-record file");
    return image;
}

bool imagesSupported() {
#ifdef RTBENCH_WITH_OIIO
    return true;
#else
    return false;
#endif
}

void writeImages(const std::string& prefix, const HitImage& image) {
#ifdef RTBENCH_WITH_OIIO
    const std::size_t n = std::size_t(image.width) * image.height;
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
    auto write = [&](const std::string& path, const std::vector<std::uint8_t>& pixels) {
        auto out = OIIO::ImageOutput::create(path);
        if (!out) throw Error(path + ": OpenImageIO cannot create a PNG writer: " + OIIO::geterror());
        OIIO::ImageSpec spec(static_cast<int>(image.width), static_cast<int>(image.height), 3, OIIO::TypeDesc::UINT8);
        if (!out->open(path, spec) || !out->write_image(OIIO::TypeDesc::UINT8, pixels.data()) || !out->close())
            throw Error(path + ": OpenImageIO write failed: " + out->geterror());
    };
    write(prefix + "-shaded.png", shaded);
    write(prefix + "-diff.png", diff);
#else
    (void)image;
    throw Error(prefix + ": built without OpenImageIO (RTBENCH_WITH_OIIO=OFF): keep hit records and run `rtbench images`");
#endif
}

int writeImagesForFolder(const std::string& folder) {
    if (!std::filesystem::is_directory(folder)) throw Error(folder + ": not a results folder");
    int count = 0;
    for (const auto& entry : std::filesystem::directory_iterator(folder)) {
        if (entry.path().extension() != ".hits") continue;
        const std::string prefix = (entry.path().parent_path() / entry.path().stem()).string();
        writeImages(prefix, readHitRecords(entry.path().string()));
        ++count;
    }
    return count;
}

}  // namespace rtbench
