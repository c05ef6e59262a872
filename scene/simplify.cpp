#include "simplify.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_simplification/Edge_collapse_visitor_base.h>
#include <CGAL/Surface_mesh_simplification/edge_collapse.h>

#include <array>
#include <chrono>
#include <cmath>
#include <vector>

#include "core/error.h"
#include "core/text.h"

namespace rtbench {
namespace {

using Point = CGAL::Simple_cartesian<double>::Point_3;
using Surface = CGAL::Surface_mesh<Point>;
using FloatPoint = CGAL::Exact_predicates_inexact_constructions_kernel::Point_3;  // exact predicates
namespace PMP = CGAL::Polygon_mesh_processing;
namespace SMS = CGAL::Surface_mesh_simplification;

std::string n(std::size_t value) {
    return std::to_string(value);
}

// Removed elements of a Surface_mesh stay in it, marked, until collect_garbage(): the live face
// count is number_of_faces(); the member num_faces(), and CGAL 5.5's BGL num_faces(sm), count the
// removed ones too.
std::size_t liveFaces(const Surface& surface) {
    return surface.number_of_faces();
}

// Stops once the surface has at most `target` faces. CGAL 5.5 has no face-count predicate: its
// Count_stop_predicate compares the edge count.
struct FaceCountStop {
    std::size_t target;
    template <class Cost, class Profile>
    bool operator()(const Cost&, const Profile& profile, std::size_t, std::size_t) const {
        return liveFaces(profile.surface_mesh()) <= target;
    }
};

// The point as the result will hold it: rounded to float. Through a volatile: GCC 12.2's SLP
// vectorizer (-O2, -O3) turns two adjacent double(float(d)) into d, rounding nothing.
double roundedToFloat(double d) {
    volatile float f = float(d);
    return f;
}
FloatPoint inFloat(const Point& p) {
    return FloatPoint(roundedToFloat(p.x()), roundedToFloat(p.y()), roundedToFloat(p.z()));
}

// Refuses a collapse (CGAL drops the edge from its queue, and takes it again when a neighbour
// changes) that would
// - leave a triangle of zero area in float: CGAL's own checks (link condition, no flipped
//   normal) let a triangle through whose moved vertex lands on another one, e.g. where
//   orient_polygon_soup duplicated a point, or whose float rounding makes it flat;
// - with borderOnlyAtLast (exact), one face above the target, remove two faces (an edge inside
//   the surface): only a border edge (one face) can end at the target.
struct CollapseFilter {
    std::size_t target;
    bool borderOnlyAtLast;
    std::size_t* refusedAtLast;  // interior collapses refused one face above the target
    template <class Profile>
    boost::optional<typename Profile::Point> operator()(const Profile& profile,
                                                        boost::optional<typename Profile::Point> placement) const {
        if (!placement) return placement;
        // The triangles around the edge: first those it removes, then the others, the moved
        // vertex second (Edge_profile::triangles()).
        const auto& triangles = profile.triangles();
        const std::size_t removed = std::size_t(profile.left_face_exists()) + std::size_t(profile.right_face_exists());
        const FloatPoint moved = inFloat(*placement);
        for (std::size_t t = removed; t < triangles.size(); ++t)
            if (CGAL::collinear(inFloat(get(profile.vertex_point_map(), triangles[t].v0)), moved,
                                inFloat(get(profile.vertex_point_map(), triangles[t].v2))))
                return boost::none;
        if (borderOnlyAtLast && removed == 2 && liveFaces(profile.surface_mesh()) == target + 1) {
            ++*refusedAtLast;
            return boost::none;
        }
        return placement;
    }
};

// What happened, for the result and the messages. CGAL collapses the zero-length edges while it
// collects the edges, before its loop and without asking the stop predicate.
struct CollapseRecord {
    std::size_t collapses = 0;
    std::size_t facesBeforeLoop = 0;  // when the loop takes its first edge (0: it took none)
};
struct RecordingVisitor : SMS::Edge_collapse_visitor_base<Surface> {
    CollapseRecord* record;
    explicit RecordingVisitor(CollapseRecord* r) : record(r) {}
    void OnSelected(const Profile& profile, const boost::optional<FT>&, size_type, size_type) {
        if (record->facesBeforeLoop == 0) record->facesBeforeLoop = liveFaces(profile.surface_mesh());
    }
    void OnCollapsed(const Profile&, const vertex_descriptor&) { ++record->collapses; }
};

// The mesh as a CGAL surface through the polygon-soup route: orient_polygon_soup orients the
// triangles consistently and duplicates the points where no 2-manifold is possible otherwise
// (edges of more than two triangles, pinched vertices, incompatible orientations). Triangles
// with a repeated vertex index (a point or a segment, no surface) are dropped first: CGAL refuses
// them. Zero-area triangles of three distinct indices are kept.
struct Conversion {
    Surface surface;
    std::size_t droppedRepeated = 0;   // triangles with a repeated vertex index
    std::size_t duplicatedPoints = 0;  // by orient_polygon_soup
};
Conversion toSurface(const TriangleMesh& mesh) {
    Conversion out;
    const std::string name = printable(mesh.name);
    std::vector<Point> points;
    points.reserve(mesh.vertices.size());
    for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
        const glm::vec3 v = mesh.vertices[i];
        if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z))
            throw Error(name + ": cannot simplify: vertex " + n(i) + " has a NaN or infinite coordinate");
        points.emplace_back(v.x, v.y, v.z);
    }
    std::vector<std::array<std::size_t, 3>> triangles;
    triangles.reserve(mesh.triangles.size());
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
        const glm::uvec3 tri = mesh.triangles[t];
        for (int k = 0; k < 3; ++k)
            if (tri[k] >= mesh.vertices.size())
                throw Error(name + ": cannot simplify: triangle " + n(t) + " references vertex " + n(tri[k]) +
                            ", but the mesh has " + n(mesh.vertices.size()) + " vertices");
        if (tri.x == tri.y || tri.y == tri.z || tri.z == tri.x)
            ++out.droppedRepeated;
        else
            triangles.push_back({tri.x, tri.y, tri.z});
    }
    if (triangles.empty())
        throw Error(name + ": cannot simplify: all " + n(mesh.triangles.size()) +
                    " triangles repeat a vertex index (no surface)");
    const std::size_t pointCount = points.size();
    PMP::orient_polygon_soup(points, triangles);
    out.duplicatedPoints = points.size() - pointCount;
    if (!PMP::is_polygon_soup_a_polygon_mesh(triangles))
        throw Error(name + ": cannot simplify: CGAL's orient_polygon_soup did not make a 2-manifold surface of its " +
                    n(triangles.size()) + " triangles (is_polygon_soup_a_polygon_mesh is false)");
    PMP::polygon_soup_to_polygon_mesh(points, triangles, out.surface);
    return out;
}

bool hasBorder(const Surface& surface) {
    for (Surface::Halfedge_index h : surface.halfedges())
        if (surface.is_border(h)) return true;
    return false;
}

// The surface back as a TriangleMesh: vertices rounded to float once, in the surface's order
// (isolated ones left out), triangles in its face order, both after collect_garbage().
TriangleMesh toMesh(Surface& surface, const TriangleMesh& source) {
    surface.collect_garbage();
    TriangleMesh mesh;
    mesh.name = source.name;  // the other fields describe how the source was read
    // The lights stay where they were; which new triangle has which material is not kept.
    mesh.appearance.lights = source.appearance.lights;
    mesh.appearance.materialsLost = !source.appearance.materialOf.empty();
    std::vector<unsigned> index(surface.number_of_vertices(), ~0u);
    for (Surface::Vertex_index v : surface.vertices()) {
        if (surface.is_isolated(v)) continue;
        const Point& p = surface.point(v);
        index[v.idx()] = unsigned(mesh.vertices.size());
        mesh.vertices.emplace_back(float(p.x()), float(p.y()), float(p.z()));
    }
    mesh.triangles.reserve(surface.number_of_faces());
    for (Surface::Face_index f : surface.faces()) {
        glm::uvec3 tri;
        int k = 0;
        for (Surface::Vertex_index v : CGAL::vertices_around_face(surface.halfedge(f), surface)) tri[k++] = index[v.idx()];
        mesh.triangles.push_back(tri);
    }
    return mesh;
}

}  // namespace

SimplifiedMesh simplifyMesh(const TriangleMesh& mesh, std::size_t target, bool exact) {
    const auto start = std::chrono::steady_clock::now();
    const std::string name = printable(mesh.name);
    const std::size_t count = mesh.triangles.size();
    SimplifiedMesh result;
    auto finish = [&] {
        result.ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
        return result;
    };
    if (target == 0) throw Error(name + ": cannot simplify to 0 triangles (the target must be at least 1)");
    // Exactly more triangles than there are: simplification only removes them.
    if (exact && target > count)
        throw Error(name + ": cannot simplify to exactly " + n(target) + " triangles: the scene has only " + n(count) +
                    " triangles, fewer than the " + n(target) + " asked for");
    if (target >= count) {
        result.mesh = mesh;
        result.unchanged = true;
        return finish();
    }

    Conversion conversion = toSurface(mesh);
    Surface& surface = conversion.surface;
    const std::size_t droppedRepeated = conversion.droppedRepeated;
    const std::size_t initial = liveFaces(surface);
    // On a closed surface every collapse removes 2 faces: refusing the last one would not help.
    const bool closed = !hasBorder(surface);
    const std::string at = name + ": simplifying " + n(count) + " triangles to " + n(target) +
                           (droppedRepeated ? " (" + n(droppedRepeated) + " with a repeated vertex index dropped)" : "") +
                           ": ";
    if (initial <= target) {  // the dropped triangles were enough: no collapse
        if (exact && initial < target) throw Error(at + "only " + n(initial) + " triangles are left");
        result.mesh = toMesh(surface, mesh);
        return finish();
    }
    CollapseRecord record;
    std::size_t refused = 0;
    SMS::edge_collapse(surface, FaceCountStop{target},
                       CGAL::parameters::filter(CollapseFilter{target, exact && !closed, &refused})
                           .visitor(RecordingVisitor(&record)));
    const std::size_t faces = liveFaces(surface);
    if (record.facesBeforeLoop == 0) record.facesBeforeLoop = faces;
    result.collapses = record.collapses;

    // Both are reachable where this is said: this run passed target + 1, and its next collapse
    // (taken, or refused by the filter) gave target - 1.
    const std::string askForNeighbours =
        "; ask for " + (target > 1 ? n(target - 1) + " or " : std::string()) + n(target + 1);
    const std::string nonManifold =
        conversion.duplicatedPoints
            ? " (not a 2-manifold: CGAL's orient_polygon_soup duplicated " + n(conversion.duplicatedPoints) +
                  " points, at edges of more than two triangles, pinched vertices or incompatible orientations)"
            : std::string();
    if (faces > target) {
        if (exact && faces == target + 1 && refused > 0)
            throw Error(at + "stopped at " + n(faces) +
                        ": a collapse removes 2 triangles inside the surface, 1 on a border, and no border edge "
                        "could be collapsed there" + askForNeighbours + " (or exact = false)");
        throw Error(at + "stopped at " + n(faces) + " triangles after " + n(record.collapses) +
                    " collapses: no edge left can be collapsed without breaking the surface (CGAL's link "
                    "condition), flipping a triangle or leaving one of zero area, or it has no Lindstrom-Turk "
                    "placement" + nonManifold);
    }
    if (exact && faces < target) {
        if (record.facesBeforeLoop < target)
            throw Error(at + "CGAL collapses every zero-length edge before anything else, whatever the target: " +
                        n(record.collapses) + " collapses of zero-length edges left " + n(faces) + " triangles");
        if (closed)  // faces == target - 1, reached from target + 1
            throw Error(at + "closed surface: each collapse removes 2 triangles, and " + n(initial) + " - " +
                        n(target) + " = " + n(initial - target) + " is odd" + askForNeighbours);
        throw Error(at + "ended at " + n(faces) + " triangles after " + n(record.collapses) + " collapses");
    }
    result.mesh = toMesh(surface, mesh);
    return finish();
}

}  // namespace rtbench
