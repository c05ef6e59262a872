#include "scene_description.h"

#include <toml++/toml.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <optional>
#include <random>
#include <sstream>

#include "core/error.h"
#include "mesh_io.h"
#include "procedural.h"
#include "scene_limits.h"
#include "core/text.h"

namespace rtbench {

namespace fs = std::filesystem;

namespace {

bool isDescriptionPath(const std::string& source) {
    std::string ext = fs::path(source).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    return ext == ".toml";
}

std::string resolvePath(const std::string& source, const std::string& baseDir) {
    fs::path p(source);
    if (p.is_relative()) p = fs::path(baseDir) / p;
    return p.lexically_normal().string();
}

// A mesh source other than a description: procedural:NAME, cgal:NAME or a file.
TriangleMesh loadMeshSource(const std::string& source, const std::string& baseDir) {
    if (source.rfind("procedural:", 0) == 0) return proceduralScene(source.substr(11));
    if (source.rfind("cgal:", 0) == 0) return readCgalMesh(source.substr(5));
    return readMeshFile(resolvePath(source, baseDir));
}

std::string where(const std::string& file, const toml::source_region& src) {
    if (src.begin.line == 0) return file;
    return file + ":" + std::to_string(src.begin.line);
}

std::string join(const std::vector<std::string>& items) {
    std::string out;
    for (const std::string& s : items) out += (out.empty() ? "" : ", ") + s;
    return out;
}

std::string withCommas(std::uint64_t n) {
    std::string digits = std::to_string(n), out;
    for (std::size_t i = 0; i < digits.size(); ++i) {
        if (i && (digits.size() - i) % 3 == 0) out += ',';
        out += digits[i];
    }
    return out;
}

// ---- deterministic arithmetic ----

// sin(x), cos(x) for |x| <= pi/4 by their Taylor series (Horner, basic operations only): the
// first omitted terms are below 1e-18.
void sinCosReduced(double x, double& s, double& c) {
    const double x2 = x * x;
    // sin x = x (1 - x2/(2*3) (1 - x2/(4*5) (1 - ... (1 - x2/(16*17)))))
    double ps = 1.0;
    for (double k : {16.0 * 17.0, 14.0 * 15.0, 12.0 * 13.0, 10.0 * 11.0, 8.0 * 9.0, 6.0 * 7.0,
                     4.0 * 5.0, 2.0 * 3.0})
        ps = 1.0 - x2 / k * ps;
    s = x * ps;
    // cos x = 1 - x2/(1*2) (1 - x2/(3*4) (1 - ... (1 - x2/(17*18))))
    double pc = 1.0;
    for (double k : {17.0 * 18.0, 15.0 * 16.0, 13.0 * 14.0, 11.0 * 12.0, 9.0 * 10.0, 7.0 * 8.0,
                     5.0 * 6.0, 3.0 * 4.0, 1.0 * 2.0})
        pc = 1.0 - x2 / k * pc;
    c = pc;
}

// A 3x3 rotation in double, row-major.
using Mat3 = std::array<std::array<double, 3>, 3>;

Mat3 identity() {
    return {{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
}

Mat3 multiply(const Mat3& a, const Mat3& b) {
    Mat3 r{};
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            r[i][j] = a[i][0] * b[0][j] + a[i][1] * b[1][j] + a[i][2] * b[2][j];
    return r;
}

// Rotation about one axis (0 x, 1 y, 2 z) by an angle in degrees, right-handed.
Mat3 axisRotation(int axis, double degrees) {
    double s, c;
    sinCosDegrees(degrees, s, c);
    Mat3 r = identity();
    const int i = (axis + 1) % 3, j = (axis + 2) % 3;  // x: (y, z), y: (z, x), z: (x, y)
    r[i][i] = c;
    r[i][j] = -s;
    r[j][i] = s;
    r[j][j] = c;
    return r;
}

// Rz Ry Rx: x first, then y, then z.
Mat3 eulerXyz(const glm::dvec3& degrees) {
    return multiply(axisRotation(2, degrees.z),
                    multiply(axisRotation(1, degrees.y), axisRotation(0, degrees.x)));
}

// A unit quaternion's rotation matrix.
Mat3 quaternionMatrix(double w, double x, double y, double z) {
    return {{{1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)},
             {2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)},
             {2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)}}};
}

// [0, 1) with 53 random bits from two mt19937 outputs (genrand_res53).
double uniform01(std::mt19937& rng) {
    const std::uint32_t a = rng() >> 5, b = rng() >> 6;
    return (double(a) * 67108864.0 + double(b)) * (1.0 / 9007199254740992.0);
}

double between(std::mt19937& rng, double lo, double hi) {
    return lo + (hi - lo) * uniform01(rng);
}

// ---- the description's keys ----

enum class Anchor { Origin, Center, Base };

struct Placement {
    std::string at;  // file:line of the table
    std::uint32_t line = 0;
    std::string meshAt;   // file:line of its mesh key
    std::string mesh;     // as written
    std::string meshKey;  // the cache key (resolved path or cgal:/procedural: source)
    Anchor anchor = Anchor::Origin;
    std::optional<double> size;
    bool scatter = false;
    // object
    glm::dvec3 scale{1.0}, rotateDeg{0.0}, translate{0.0};
    // scatter
    std::uint64_t count = 0;
    std::uint32_t seed = 0;
    glm::dvec3 boxMin{0.0}, boxMax{0.0};
    double scaleMin = 1.0, scaleMax = 1.0;
    int randomRotation = -1;  // -1 none, 0/1/2 about x/y/z, 3 any orientation
};

struct MaterialEntry {
    DescribedMaterial material;
    std::string meshKey;  // as Placement::meshKey
    std::string meshAt;   // file:line of its mesh key
};

class Reader {
  public:
    Reader(std::string file, std::string baseDir)
        : file_(std::move(file)), baseDir_(std::move(baseDir)) {}

    SceneDescription read(const std::string& text) {
        toml::table root;
        try {
            root = toml::parse(text, file_);
        } catch (const toml::parse_error& e) {
            throw Error(where(file_, e.source()) +
                        ": TOML syntax error: " + std::string(e.description()));
        }
        SceneDescription result;
        std::vector<Placement> placements;
        std::vector<MaterialEntry> materials;
        for (auto&& [key, node] : root) {
            const std::string name(key.str());
            if (name == "name") {
                if (!node.is_string()) throw Error(at(node) + ": key 'name': expected a string");
                result.title = node.as_string()->get();
                refuseControlCharacters(at(node) + ": key 'name': ", result.title);
            } else if (name == "object" || name == "scatter") {
                const toml::array* list = node.as_array();
                if (!list || !list->is_array_of_tables())
                    throw Error(at(key) + ": '" + name + "' must be an array of tables ([[" + name +
                                "]])");
                for (const toml::node& element : *list)
                    placements.push_back(readPlacement(*element.as_table(), name == "scatter"));
            } else if (name == "material" || name == "light") {
                const toml::array* list = node.as_array();
                if (!list || !(list->is_array_of_tables() || list->empty()))
                    throw Error(at(key) + ": '" + name + "' must be an array of tables ([[" + name + "]])");
                if (list->empty())
                    throw Error(at(key) + ": '" + name + "' is an empty list: give at least one [[" + name +
                                "]] table, or leave the key out" +
                                (name == "light" ? " (the run's light.position then lights the scene)" : ""));
                for (const toml::node& element : *list) {
                    if (name == "material") materials.push_back(readMaterial(*element.as_table()));
                    else result.mesh.appearance.lights.push_back(readLight(*element.as_table()));
                }
            } else {
                throw Error(at(key) + ": unknown key '" + name +
                            "' (allowed at the top level: name, object, scatter, material, light)");
            }
        }
        if (placements.empty())
            throw Error(file_ + ": describes nothing (add [[object]] or [[scatter]] tables)");
        // Placements appear in key order of the root table (toml++ keeps tables sorted by key),
        // so put them back in file order: objects and scatters as the lines list them.
        std::stable_sort(placements.begin(), placements.end(),
                         [](const Placement& a, const Placement& b) { return a.line < b.line; });
        place(placements, result);
        assignMaterials(materials, placements, result);
        return result;
    }

  private:
    std::string at(const toml::node& n) const { return where(file_, n.source()); }
    std::string at(const toml::key& k) const { return where(file_, k.source()); }

    double number(const toml::node& n, const std::string& key) const {
        if (!n.is_number()) throw Error(at(n) + ": key '" + key + "': expected a number");
        const double v = n.value<double>().value();
        if (!std::isfinite(v)) throw Error(at(n) + ": key '" + key + "': value must be finite");
        return v;
    }
    double positive(const toml::node& n, const std::string& key) const {
        const double v = number(n, key);
        if (!(v > 0.0))
            throw Error(at(n) + ": key '" + key + "': value " + formatFloat(v) + " must be > 0");
        return v;
    }
    glm::dvec3 vec3(const toml::node& n, const std::string& key) const {
        const toml::array* a = n.as_array();
        if (!a || a->size() != 3)
            throw Error(at(n) + ": key '" + key + "': expected an array of 3 numbers");
        return {number(*a->get(0), key), number(*a->get(1), key), number(*a->get(2), key)};
    }
    std::uint64_t integer(const toml::node& n, const std::string& key, std::int64_t lo,
                          std::int64_t hi) const {
        if (!n.is_integer()) throw Error(at(n) + ": key '" + key + "': expected an integer");
        const std::int64_t v = n.as_integer()->get();
        if (v < lo || v > hi)
            throw Error(at(n) + ": key '" + key + "': value " + std::to_string(v) +
                        " is out of range [" + withCommas(std::uint64_t(lo)) + ", " +
                        withCommas(std::uint64_t(hi)) + "]");
        return std::uint64_t(v);
    }

    Placement readPlacement(const toml::table& table, bool scatter) {
        const std::string section = scatter ? "scatter" : "object";
        const std::vector<std::string> allowed =
            scatter
                ? std::vector<std::string>{"mesh",   "count", "seed",  "box_min",        "box_max",
                                           "anchor", "size",  "scale", "random_rotation"}
                : std::vector<std::string>{"mesh",  "anchor",     "size",
                                           "scale", "rotate_deg", "translate"};
        Placement p;
        p.scatter = scatter;
        p.at = where(file_, table.source());
        p.line = table.source().begin.line;
        p.anchor = scatter ? Anchor::Center : Anchor::Origin;
        const toml::node *boxMin = nullptr, *boxMax = nullptr;
        bool hasMesh = false, hasCount = false, hasSeed = false;
        for (auto&& [key, node] : table) {
            const std::string name(key.str());
            const std::string full = section + "." + name;
            if (std::find(allowed.begin(), allowed.end(), name) == allowed.end())
                throw Error(at(key) + ": unknown key '" + full + "' (allowed in [[" + section +
                            "]]: " + join(allowed) + ")");
            if (name == "mesh") {
                if (!node.is_string())
                    throw Error(at(node) + ": key '" + full + "': expected a string");
                p.mesh = node.as_string()->get();
                refuseControlCharacters(at(node) + ": key '" + full + "': ", p.mesh);
                p.meshAt = at(node);
                if (p.mesh.empty())
                    throw Error(at(node) + ": key '" + full + "': expected a mesh, not \"\"");
                if (isDescriptionPath(p.mesh))
                    throw Error(at(node) + ": key '" + full + "': '" + p.mesh +
                                "' is a scene description; descriptions do not nest (name a mesh "
                                "file, cgal:NAME or "
                                "procedural:NAME)");
                p.meshKey = meshKeyOf(p.mesh);
                hasMesh = true;
            } else if (name == "anchor") {
                const std::optional<std::string> v = node.value<std::string>();
                if (!node.is_string() || (*v != "origin" && *v != "center" && *v != "base"))
                    throw Error(at(node) + ": key '" + full +
                                "': expected \"origin\", \"center\" or \"base\"");
                p.anchor = *v == "origin"   ? Anchor::Origin
                           : *v == "center" ? Anchor::Center
                                            : Anchor::Base;
            } else if (name == "size") {
                p.size = positive(node, full);
            } else if (name == "scale") {
                if (node.is_number()) {
                    const double s = positive(node, full);
                    p.scale = glm::dvec3(s);
                    p.scaleMin = p.scaleMax = s;
                } else if (scatter) {
                    const toml::array* a = node.as_array();
                    if (!a || a->size() != 2)
                        throw Error(at(node) + ": key '" + full +
                                    "': expected a number or a range [min, max]");
                    p.scaleMin = positive(*a->get(0), full);
                    p.scaleMax = positive(*a->get(1), full);
                    if (p.scaleMin > p.scaleMax)
                        throw Error(at(node) + ": key '" + full + "': the range [" +
                                    formatFloat(p.scaleMin) + ", " + formatFloat(p.scaleMax) +
                                    "] has min > max");
                } else {
                    const toml::array* a = node.as_array();
                    if (!a || a->size() != 3)
                        throw Error(at(node) + ": key '" + full +
                                    "': expected a number or an array of 3 numbers");
                    p.scale = {positive(*a->get(0), full), positive(*a->get(1), full),
                               positive(*a->get(2), full)};
                }
            } else if (name == "rotate_deg") {
                p.rotateDeg = vec3(node, full);
            } else if (name == "translate") {
                p.translate = vec3(node, full);
            } else if (name == "count") {
                p.count = integer(node, full, 1, std::int64_t(kMaxDescriptionTriangles));
                hasCount = true;
            } else if (name == "seed") {
                p.seed = std::uint32_t(integer(node, full, 0, 0xffffffffll));
                hasSeed = true;
            } else if (name == "box_min") {
                p.boxMin = vec3(node, full);
                boxMin = &node;
            } else if (name == "box_max") {
                p.boxMax = vec3(node, full);
                boxMax = &node;
            } else if (name == "random_rotation") {
                if (node.is_boolean()) {
                    p.randomRotation = node.as_boolean()->get() ? 3 : -1;
                } else {
                    const std::optional<std::string> v = node.value<std::string>();
                    if (!node.is_string() || (*v != "x" && *v != "y" && *v != "z"))
                        throw Error(at(node) + ": key '" + full +
                                    "': expected true, false, \"x\", \"y\" or \"z\"");
                    p.randomRotation = (*v)[0] - 'x';
                }
            }
        }
        auto need = [&](bool has, const char* key) {
            if (!has) throw Error(p.at + ": [[" + section + "]] needs '" + key + "'");
        };
        need(hasMesh, "mesh");
        if (scatter) {
            need(hasCount, "count");
            need(hasSeed, "seed");
            need(boxMin, "box_min");
            need(boxMax, "box_max");
            for (int a = 0; a < 3; ++a)
                if (p.boxMin[a] > p.boxMax[a])
                    throw Error(at(*boxMax) + ": key 'scatter.box_max': box_max." + "xyz"[a] +
                                " = " + formatFloat(p.boxMax[a]) + " is below box_min." + "xyz"[a] +
                                " = " + formatFloat(p.boxMin[a]));
        }
        return p;
    }

    // A mesh as written, as placements key it: cgal: and procedural: sources as they are, files
    // by their resolved path.
    std::string meshKeyOf(const std::string& mesh) const {
        return mesh.rfind("cgal:", 0) == 0 || mesh.rfind("procedural:", 0) == 0 ? mesh : resolvePath(mesh, baseDir_);
    }

    // [[material]]: mesh, type, and only the keys its type reads (colour; reflectance; ior).
    MaterialEntry readMaterial(const toml::table& table) {
        MaterialEntry e;
        const toml::node* type = table.get("type");
        if (!type) throw Error(where(file_, table.source()) + ": [[material]] needs 'type' (\"diffuse\", \"mirror\" or \"glass\")");
        const std::optional<std::string> kind = type->value<std::string>();
        if (!type->is_string() || (*kind != "diffuse" && *kind != "mirror" && *kind != "glass"))
            throw Error(at(*type) + ": key 'material.type': expected \"diffuse\", \"mirror\" or \"glass\"");
        e.material.kind = *kind == "diffuse" ? MaterialKind::Diffuse : *kind == "mirror" ? MaterialKind::Mirror : MaterialKind::Glass;
        if (e.material.kind == MaterialKind::Glass) e.material.colour = glm::dvec3(0.0);
        const std::vector<std::string> allowed =
            *kind == "diffuse" ? std::vector<std::string>{"mesh", "type", "colour"}
            : *kind == "mirror" ? std::vector<std::string>{"mesh", "type", "colour", "reflectance"}
                                : std::vector<std::string>{"mesh", "type", "ior"};
        bool hasMesh = false;
        for (auto&& [key, node] : table) {
            const std::string name(key.str());
            const std::string full = "material." + name;
            if (std::find(allowed.begin(), allowed.end(), name) == allowed.end())
                throw Error(at(key) + ": key '" + full + "' does not apply to a " + *kind + " material (its keys: " +
                            join(allowed) + ")");
            if (name == "mesh") {
                if (!node.is_string() || node.as_string()->get().empty())
                    throw Error(at(node) + ": key '" + full + "': expected a mesh as an [[object]] or [[scatter]] names it");
                e.material.mesh = node.as_string()->get();
                refuseControlCharacters(at(node) + ": key '" + full + "': ", e.material.mesh);
                e.meshKey = meshKeyOf(e.material.mesh);
                e.meshAt = at(node);
                hasMesh = true;
            } else if (name == "colour") {
                e.material.colour = vec3(node, full);
                for (int a = 0; a < 3; ++a)
                    if (e.material.colour[a] < 0.0 || e.material.colour[a] > 1.0)
                        throw Error(at(node) + ": key '" + full + "': each component must lie in [0, 1]");
            } else if (name == "reflectance") {
                e.material.reflectance = number(node, full);
                if (!(e.material.reflectance > 0.0 && e.material.reflectance <= 1.0))
                    throw Error(at(node) + ": key '" + full + "': value " + formatFloat(e.material.reflectance) +
                                " must lie in (0, 1] (a mirror reflecting nothing is a diffuse material)");
            } else if (name == "ior") {
                e.material.ior = number(node, full);
                if (!(e.material.ior >= 0.01 && e.material.ior <= 100.0))
                    throw Error(at(node) + ": key '" + full + "': value " + formatFloat(e.material.ior) +
                                " must lie in [0.01, 100] (an index of refraction against 1 outside)");
            }
        }
        if (!hasMesh) throw Error(where(file_, table.source()) + ": [[material]] needs 'mesh'");
        return e;
    }

    glm::dvec3 readLight(const toml::table& table) {
        const toml::node* position = nullptr;
        for (auto&& [key, node] : table) {
            if (key.str() != "position")
                throw Error(at(key) + ": unknown key 'light." + std::string(key.str()) + "' (allowed in [[light]]: position)");
            position = &node;
        }
        if (!position) throw Error(where(file_, table.source()) + ": [[light]] needs 'position'");
        const glm::dvec3 p = vec3(*position, "light.position");
        for (int a = 0; a < 3; ++a)
            if (!(std::fabs(p[a]) <= double(kMaxVertexCoordinate)))
                throw Error(at(*position) + ": key 'light.position': out of range: " + sceneRangeText());
        return p;
    }

    // Each material covers every copy of its mesh; a mesh no placement places, or one given two
    // materials, is an error.
    void assignMaterials(const std::vector<MaterialEntry>& materials, const std::vector<Placement>& placements,
                         SceneDescription& result) {
        if (materials.empty()) return;
        Appearance& look = result.mesh.appearance;
        std::map<std::string, std::uint32_t> byMesh;
        for (const MaterialEntry& e : materials) {
            const bool placed = std::any_of(placements.begin(), placements.end(),
                                            [&](const Placement& p) { return p.meshKey == e.meshKey; });
            if (!placed) {
                std::vector<std::string> names;
                for (const Placement& p : placements)
                    if (std::find(names.begin(), names.end(), p.mesh) == names.end()) names.push_back(p.mesh);
                throw Error(e.meshAt + ": key 'material.mesh': '" + e.material.mesh +
                            "' is placed by no [[object]] or [[scatter]] (placed: " + join(names) + ")");
            }
            if (byMesh.count(e.meshKey))
                throw Error(e.meshAt + ": key 'material.mesh': '" + e.material.mesh + "' already has a material (" +
                            materials[byMesh[e.meshKey]].meshAt + ")");
            byMesh[e.meshKey] = std::uint32_t(look.materials.size());
            look.materials.push_back(e.material);
        }
        look.materialOf.assign(result.mesh.triangles.size(), kUndescribedMaterial);
        for (std::size_t c = 0; c < result.copies.size(); ++c) {
            const auto m = byMesh.find(copyKeys_[c]);
            if (m == byMesh.end()) continue;
            const PlacedCopy& copy = result.copies[c];
            std::fill_n(look.materialOf.begin() + std::ptrdiff_t(copy.firstTriangle), copy.triangleCount, m->second);
        }
    }

    // Reads each distinct mesh once, checks the totals, then writes every copy.
    void place(const std::vector<Placement>& placements, SceneDescription& result) {
        std::map<std::string, std::shared_ptr<const TriangleMesh>> meshes;
        std::uint64_t triangles = 0, vertices = 0;
        for (const Placement& p : placements) {
            auto& mesh = meshes[p.meshKey];
            if (!mesh) {
                try {
                    mesh = std::make_shared<const TriangleMesh>(loadMeshSource(p.mesh, baseDir_));
                } catch (const Error& e) {
                    throw Error(p.meshAt + ": key '" +
                                std::string(p.scatter ? "scatter" : "object") +
                                ".mesh': " + e.what());
                }
                if (mesh->triangles.empty())
                    throw Error(p.meshAt + ": mesh '" + p.mesh + "' has no triangles");
                result.mesh.inputs.insert(result.mesh.inputs.end(), mesh->inputs.begin(), mesh->inputs.end());
            }
            const std::uint64_t copies = p.scatter ? p.count : 1;
            triangles +=
                copies * mesh->triangles.size();  // <= 2^24 * 2^32 per placement: no overflow
            vertices += copies * mesh->vertices.size();
            if (triangles > kMaxDescriptionTriangles || vertices > 3 * kMaxDescriptionTriangles)
                throw Error(p.at + ": this placement brings the scene to " + withCommas(triangles) +
                            " triangles and " + withCommas(vertices) +
                            " vertices: a description may produce at most " +
                            withCommas(kMaxDescriptionTriangles) + " triangles and " +
                            withCommas(3 * kMaxDescriptionTriangles) + " vertices");
        }
        result.meshesRead = meshes.size();
        TriangleMesh& out = result.mesh;
        out.vertices.reserve(vertices);
        out.triangles.reserve(triangles);
        std::map<std::string, std::uint64_t> skipped;  // mesh -> copies that skipped elements
        for (const Placement& p : placements) {
            const TriangleMesh& mesh = *meshes[p.meshKey];
            const Bounds3 box = mesh.bounds();
            const glm::dvec3 lo(box.min), hi(box.max);
            glm::dvec3 anchor(0.0);
            if (p.anchor != Anchor::Origin) anchor = (lo + hi) * 0.5;
            if (p.anchor == Anchor::Base) anchor.y = lo.y;
            double sizeFactor = 1.0;
            if (p.size) {
                const double largest = std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z});
                if (!(largest > 0.0))
                    throw Error(p.at + ": 'size' cannot apply: mesh '" + p.mesh +
                                "' has an empty box");
                sizeFactor = *p.size / largest;
            }
            if (!p.scatter) {
                emit(p, mesh, anchor, sizeFactor, p.scale, eulerXyz(p.rotateDeg), p.translate,
                     result);
            } else {
                std::mt19937 rng(p.seed);
                for (std::uint64_t i = 0; i < p.count; ++i) {
                    glm::dvec3 position;
                    for (int a = 0; a < 3; ++a)
                        position[a] = between(rng, p.boxMin[a], p.boxMax[a]);
                    const double s = p.scaleMin == p.scaleMax
                                         ? p.scaleMin
                                         : between(rng, p.scaleMin, p.scaleMax);
                    Mat3 rotation = identity();
                    if (p.randomRotation >= 0 && p.randomRotation < 3) {
                        rotation = axisRotation(p.randomRotation, between(rng, 0.0, 360.0));
                    } else if (p.randomRotation == 3) {
                        // Uniform in the unit 4-ball, projected to the sphere: a uniformly random
                        // rotation (the tiny inner ball is refused: its direction is ill-rounded).
                        double q[4], n2;
                        do {
                            n2 = 0.0;
                            for (double& c : q) {
                                c = between(rng, -1.0, 1.0);
                                n2 += c * c;
                            }
                        } while (n2 > 1.0 || n2 < 1e-6);
                        const double n = std::sqrt(n2);
                        rotation = quaternionMatrix(q[0] / n, q[1] / n, q[2] / n, q[3] / n);
                    }
                    emit(p, mesh, anchor, sizeFactor, glm::dvec3(s), rotation, position, result);
                }
            }
            if (mesh.elementsSkipped)
                skipped[mesh.name + ": " + mesh.elementsSkippedWhat] += p.scatter ? p.count : 1;
        }
        out.name = file_;
        for (const auto& [what, copies] : skipped)
            out.elementsSkippedWhat += (out.elementsSkippedWhat.empty() ? "" : "; ") + what +
                                       " (placed " + std::to_string(copies) + "x)";
    }

    void emit(const Placement& p, const TriangleMesh& mesh, const glm::dvec3& anchor,
              double sizeFactor, const glm::dvec3& scale, const Mat3& r,
              const glm::dvec3& translate, SceneDescription& result) {
        TriangleMesh& out = result.mesh;
        PlacedCopy copy;
        copy.mesh = p.mesh;
        copy.firstVertex = out.vertices.size();
        copy.vertexCount = mesh.vertices.size();
        copy.firstTriangle = out.triangles.size();
        copy.triangleCount = mesh.triangles.size();
        copy.anchorAt = translate;
        copy.scale = scale;
        const glm::dvec3 factor = scale * sizeFactor;
        for (const glm::vec3& v : mesh.vertices) {
            const glm::dvec3 s = (glm::dvec3(v) - anchor) * factor;
            glm::dvec3 w;
            for (int i = 0; i < 3; ++i)
                w[i] = translate[i] + (r[i][0] * s.x + r[i][1] * s.y + r[i][2] * s.z);
            for (int i = 0; i < 3; ++i)
                if (!(std::fabs(w[i]) <=
                      double(kMaxVertexCoordinate)))  // also NaN; before the float cast
                    throw Error(p.at + ": mesh '" + p.mesh + "' places a vertex at (" +
                                formatFloat(w.x) + ", " + formatFloat(w.y) + ", " +
                                formatFloat(w.z) + "), out of range: " + sceneRangeText());
            out.vertices.emplace_back(float(w.x), float(w.y), float(w.z));
        }
        const unsigned base = unsigned(copy.firstVertex);
        for (const glm::uvec3& t : mesh.triangles) out.triangles.push_back(t + base);
        out.polygonsRead += mesh.polygonsRead;
        out.elementsSkipped += mesh.elementsSkipped;
        result.copies.push_back(copy);
        copyKeys_.push_back(p.meshKey);
    }

    std::string file_, baseDir_;
    std::vector<std::string> copyKeys_;  // each copy's Placement::meshKey
};

}  // namespace

void sinCosDegrees(double degrees, double& sine, double& cosine) {
    double r = std::fmod(degrees, 360.0);  // exact
    if (r < 0.0) r += 360.0;
    const double q = std::floor(r / 90.0 + 0.5);  // the nearest multiple of 90: 0..4
    const double x = (r - 90.0 * q) * (3.14159265358979323846 / 180.0);  // within +-pi/4
    double s, c;
    sinCosReduced(x, s, c);
    switch (int(q) % 4) {
        case 0:
            sine = s, cosine = c;
            break;
        case 1:
            sine = c, cosine = -s;
            break;
        case 2:
            sine = -s, cosine = -c;
            break;
        default:
            sine = -c, cosine = s;
            break;
    }
}

SceneDescription readSceneDescription(const std::string& path) {
    const std::string text = readInputFile(path, kMaxConfigBytes, "scene description");
    SceneDescription description = Reader(path, fs::path(path).parent_path().string()).read(text);
    // The description first, then each mesh as first read.
    description.mesh.inputs.insert(description.mesh.inputs.begin(), fingerprint(path, text));
    return description;
}

void checkSceneSource(const std::string& source, const std::string& baseDir) {
    if (source.rfind("procedural:", 0) == 0) {
        const std::string name = source.substr(11);
        const std::vector<std::string>& known = proceduralSceneNames();
        if (std::find(known.begin(), known.end(), name) == known.end()) proceduralScene(name);  // throws, naming them
        return;
    }
    if (source.rfind("cgal:", 0) == 0) {
        resolveCgalMesh(source.substr(5));
        return;
    }
    // Nothing at all at the path; anything else (a link, a folder, a FIFO) the run's reader names.
    const std::string path = resolvePath(source, baseDir);
    std::error_code ec;
    if (!fs::exists(fs::symlink_status(path, ec))) {
        // The nearest names of the folder it would be in, for a typo.
        std::vector<std::string> names;
        const fs::path folder = fs::path(path).parent_path();
        for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec))
            if (it->is_regular_file(ec)) names.push_back(it->path().filename().string());
        const std::vector<std::string> nearest = nearestNames(fs::path(path).filename().string(), names, 3);
        std::string suggestion;
        for (const std::string& n : nearest) suggestion += (suggestion.empty() ? "" : ", ") + printable(n);
        throw Error(printable(path) + ": no such file" +
                    (suggestion.empty() ? std::string() : " (nearest in " + printable(folder.string()) + ": " + suggestion + ")"));
    }
}

TriangleMesh loadSceneSource(const std::string& source, const std::string& baseDir) {
    if (source.rfind("procedural:", 0) != 0 && source.rfind("cgal:", 0) != 0 &&
        isDescriptionPath(source))
        return readSceneDescription(resolvePath(source, baseDir)).mesh;
    return loadMeshSource(source, baseDir);
}

}  // namespace rtbench
