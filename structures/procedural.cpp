#include "procedural.h"

#include "error.h"

namespace rtbench {

void appendBox(TriangleMesh& mesh, glm::vec3 lo, glm::vec3 hi, bool inward) {
    const unsigned base = static_cast<unsigned>(mesh.vertices.size());
    for (int i = 0; i < 8; ++i)
        mesh.vertices.emplace_back(i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z);
    // Two triangles per face, counter-clockwise seen from outside.
    static const unsigned faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                         {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    for (const auto& f : faces) {
        glm::uvec3 a(base + f[0], base + f[1], base + f[2]);
        glm::uvec3 b(base + f[0], base + f[2], base + f[3]);
        if (inward) std::swap(a.y, a.z), std::swap(b.y, b.z);
        mesh.triangles.push_back(a);
        mesh.triangles.push_back(b);
    }
    mesh.polygonsRead += 6;
}

TriangleMesh christenSceneA() {
    TriangleMesh mesh;
    mesh.name = "procedural:christen_a";
    appendBox(mesh, {-3.0f, 0.0f, -1.0f}, {-1.0f, 2.0f, 1.0f});
    appendBox(mesh, {-0.5f, 0.0f, -0.5f}, {0.5f, 1.0f, 0.5f});
    appendBox(mesh, {1.0f, 0.0f, -2.0f}, {3.0f, 4.0f, 0.0f});
    return mesh;
}

TriangleMesh christenSceneB(std::uint32_t seed) {
    TriangleMesh mesh;
    mesh.name = "procedural:christen_b";
    appendBox(mesh, {-10.0f, 0.0f, -10.0f}, {10.0f, 6.0f, 10.0f}, /*inward=*/true);
    // A 32-bit xorshift generator: the same numbers on every platform and standard library.
    std::uint32_t state = seed ? seed : 1u;
    auto next01 = [&state]() {
        state ^= state << 13;
        state ^= state >> 17;
        state ^= state << 5;
        return static_cast<float>(state >> 8) * (1.0f / 16777216.0f);
    };
    for (int i = 0; i < 166; ++i) {
        const float size = 0.2f + 0.8f * next01();
        const glm::vec3 lo(-9.5f + (19.0f - size) * next01(), 0.5f + (5.0f - size) * next01(),
                           -9.5f + (19.0f - size) * next01());
        appendBox(mesh, lo, lo + glm::vec3(size));
    }
    return mesh;
}

std::optional<PinholeCamera> proceduralCamera(const std::string& name, float verticalFovDegrees) {
    if (name != "christen_b") return std::nullopt;
    PinholeCamera camera;
    camera.position = {0.0f, 3.0f, 9.5f};  // by the front wall, looking across the room
    camera.lookAt = {0.0f, 2.5f, 0.0f};
    camera.verticalFovDegrees = verticalFovDegrees;
    return camera;
}

TriangleMesh proceduralScene(const std::string& name) {
    if (name == "christen_a") return christenSceneA();
    if (name == "christen_b") return christenSceneB();
    throw Error("procedural:" + name + ": unknown procedural scene (allowed: christen_a, christen_b)");
}

}  // namespace rtbench
