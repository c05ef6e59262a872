// What a scene description says of its surfaces and lights ([[material]], [[light]]; see
// scene/scene_description.h): all Whitted ray tracing (rays.type = whitted) reads beside the
// triangles, and nothing more than its rays need. A surface is diffuse (a colour), a mirror (a
// reflectance, the rest of its light diffuse: Christen 2005 eq. 5.1) or glass (an index of
// refraction, reflecting and transmitting by Fresnel's equations).
#pragma once
#include <cstdint>
#include <glm/glm.hpp>
#include <string>
#include <vector>

namespace rtbench {

enum class MaterialKind { Diffuse, Mirror, Glass };

struct DescribedMaterial {
    MaterialKind kind = MaterialKind::Diffuse;
    glm::dvec3 colour{0.8};    // diffuse and mirror: the diffuse colour (images only)
    double reflectance = 1.0;  // mirror: the fraction reflected
    double ior = 1.5;          // glass: the index of refraction against 1 outside
    std::string mesh;          // the mesh it covers, as [[material]] names it
};

// materialOf[t] for a triangle no [[material]] covers: the run's whitted.surface applies.
constexpr std::uint32_t kUndescribedMaterial = 0xFFFFFFFFu;

struct Appearance {
    std::vector<DescribedMaterial> materials;
    std::vector<std::uint32_t> materialOf;  // per triangle, into materials (or kUndescribedMaterial); empty: none given
    std::vector<glm::dvec3> lights;         // point lights, in the description's coordinates
    // True when the triangles were remade (scene.simplify_*) from ones that had materials: which
    // new triangle has which material is not known.
    bool materialsLost = false;
};

}  // namespace rtbench
