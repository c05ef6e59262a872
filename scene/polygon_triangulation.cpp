#include "polygon_triangulation.h"

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_2.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <queue>
#include <sstream>

namespace rtbench {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point2 = K::Point_2;
using Point3 = K::Point_3;
using Vb = CGAL::Triangulation_vertex_base_with_info_2<std::size_t, K>;
using Fb =
    CGAL::Constrained_triangulation_face_base_2<K,
                                                CGAL::Triangulation_face_base_with_info_2<int, K>>;
using Cdt =
    CGAL::Constrained_Delaunay_triangulation_2<K, CGAL::Triangulation_data_structure_2<Vb, Fb>,
                                               CGAL::Exact_predicates_tag>;

std::string decimal(double value) {
    std::ostringstream text;
    text << value;
    return text.str();
}

// Triangles of a polygon (2D, counter-clockwise, no repeated consecutive point; `ids` its mesh
// indices) whose edges do not cross: the constrained Delaunay triangulation of its edges, faces
// reached from the outside across an odd number of constrained edges kept (CGAL's
// polygon_triangulation example). An edge walked an even number of times (the bridge of a
// keyhole polygon, which joins an outline to a hole and back) constrains nothing. Returns why
// the polygon cannot be triangulated, or "".
std::string triangulateWeaklySimple(const std::vector<Point2>& points,
                                    const std::vector<std::size_t>& ids,
                                    std::vector<glm::uvec3>& out) {
    Cdt cdt;
    std::vector<Cdt::Vertex_handle> handles;
    handles.reserve(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) {
        const std::size_t before = cdt.number_of_vertices();
        handles.push_back(cdt.insert(points[i]));
        if (cdt.number_of_vertices() > before) handles.back()->info() = ids[i];
    }
    std::map<std::pair<Cdt::Vertex_handle, Cdt::Vertex_handle>, int> walked;
    for (std::size_t i = 0; i < handles.size(); ++i)
        ++walked[std::minmax(handles[i], handles[(i + 1) % handles.size()])];
    const std::size_t vertices = cdt.number_of_vertices();
    for (const auto& [edge, times] : walked)
        if (times % 2 == 1) cdt.insert_constraint(edge.first, edge.second);
    if (cdt.number_of_vertices() != vertices)
        return "it is self-intersecting (two of its edges cross)";
    if (cdt.dimension() < 2) return "its corners are collinear in its plane, yet it is not convex";

    for (Cdt::Face_handle f : cdt.all_face_handles()) f->info() = -1;
    std::queue<Cdt::Face_handle> frontier;  // breadth-first over faces, by nesting level
    cdt.infinite_face()->info() = 0;
    frontier.push(cdt.infinite_face());
    while (!frontier.empty()) {
        const Cdt::Face_handle f = frontier.front();
        frontier.pop();
        for (int e = 0; e < 3; ++e) {
            const Cdt::Face_handle g = f->neighbor(e);
            if (g->info() != -1) continue;
            g->info() = f->info() + (cdt.is_constrained({f, e}) ? 1 : 0);
            frontier.push(g);
        }
    }
    // Inside by parity must cover exactly the polygon's signed area, else it overlaps itself.
    double inside = 0.0, area = 0.0;
    for (std::size_t i = 0; i < points.size(); ++i)
        area += CGAL::area(Point2(0, 0), points[i], points[(i + 1) % points.size()]);
    std::vector<glm::uvec3> triangles;
    for (Cdt::Face_handle f : cdt.finite_face_handles())
        if (f->info() % 2 == 1) {
            inside +=
                CGAL::area(f->vertex(0)->point(), f->vertex(1)->point(), f->vertex(2)->point());
            triangles.emplace_back(f->vertex(0)->info(), f->vertex(1)->info(),
                                   f->vertex(2)->info());
        }
    if (triangles.empty() || !(std::abs(inside - area) <= 1e-6 * std::abs(area)))
        return "it overlaps itself (the region it encloses has area " + decimal(inside) +
               " in its plane, its signed area is " + decimal(area) + ")";
    out.insert(out.end(), triangles.begin(), triangles.end());
    return "";
}

}  // namespace

std::string triangulatePolygon(const std::vector<glm::vec3>& vertices,
                               const std::vector<std::size_t>& indices,
                               std::vector<glm::uvec3>& out) {
    const std::size_t n = indices.size();
    auto fan = [&] {
        for (std::size_t k = 1; k + 1 < n; ++k)
            out.emplace_back(indices[0], indices[k], indices[k + 1]);
        return std::string();
    };
    if (n == 3) return fan();

    // Newell's normal: twice the vector area, robust for non-planar polygons. Summed relative to
    // the first corner: on absolute coordinates far from the origin its terms cancel
    // catastrophically and the wrong axis would be dropped below.
    const glm::dvec3 origin(vertices[indices[0]]);
    glm::dvec3 normal(0.0), centroid(0.0), lo(0.0), hi(0.0);  // centroid and box relative too
    for (std::size_t i = 0; i < n; ++i) {
        const glm::dvec3 p = glm::dvec3(vertices[indices[i]]) - origin;
        const glm::dvec3 q = glm::dvec3(vertices[indices[(i + 1) % n]]) - origin;
        normal += glm::dvec3((p.y - q.y) * (p.z + q.z), (p.z - q.z) * (p.x + q.x),
                             (p.x - q.x) * (p.y + q.y));
        centroid += p / double(n);
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    if (normal == glm::dvec3(0.0)) {  // zero area: collinear (degenerate fan) or self-crossing
        auto point = [&](std::size_t i) {
            const glm::vec3& v = vertices[indices[i]];
            return Point3(v.x, v.y, v.z);
        };
        std::size_t second = 1;
        while (second < n && point(second) == point(0)) ++second;
        for (std::size_t i = second + 1; i < n; ++i)
            if (!CGAL::collinear(point(0), point(second), point(i)))
                return "its edges enclose zero net area (self-intersecting)";
        return fan();
    }
    // Project exactly by dropping the normal's dominant axis, ordered so that the polygon turns
    // counter-clockwise; repeated consecutive points are dropped.
    const glm::dvec3 a = glm::abs(normal);
    const int axis = a.x >= a.y && a.x >= a.z ? 0 : (a.y >= a.z ? 1 : 2);
    int u = (axis + 1) % 3, v = (axis + 2) % 3;
    if (normal[axis] < 0) std::swap(u, v);
    std::vector<Point2> points;
    std::vector<std::size_t> ids;
    for (std::size_t i = 0; i < n; ++i) {
        const glm::vec3& p = vertices[indices[i]];
        const Point2 q(p[u], p[v]);
        if (!points.empty() && points.back() == q) continue;
        points.push_back(q);
        ids.push_back(indices[i]);
    }
    while (points.size() > 1 && points.back() == points.front()) points.pop_back(), ids.pop_back();
    if (points.size() < 3) return fan();

    bool convex = CGAL::Polygon_2<K>(points.begin(), points.end()).is_simple();
    for (std::size_t i = 0; i < points.size() && convex; ++i)
        convex = CGAL::orientation(points[i], points[(i + 1) % points.size()],
                                   points[(i + 2) % points.size()]) != CGAL::RIGHT_TURN;
    if (convex) return fan();

    // Concave: triangulated in its projection, which stands for the polygon only if it is planar.
    const glm::dvec3 unit = glm::normalize(normal);
    const double size = glm::length(hi - lo);
    std::size_t farthest = 0;
    double distance = 0.0;
    for (std::size_t i = 0; i < n; ++i)
        if (const double d = std::abs(glm::dot(glm::dvec3(vertices[indices[i]]) - origin - centroid, unit));
            d > distance)
            farthest = i, distance = d;
    if (distance > kPolygonPlanarityTolerance * size)
        return "it is not planar and not convex: its corner " + std::to_string(farthest + 1) +
               " (of " + std::to_string(n) + ") lies " + decimal(distance) +
               " from its mean plane, more than " + decimal(kPolygonPlanarityTolerance * 100) +
               "% of its size " + decimal(size);
    return triangulateWeaklySimple(points, ids, out);
}

}  // namespace rtbench
