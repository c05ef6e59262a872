// Every malformed-mesh case produces its error message (asserted), never a crash, a huge
// allocation, output or a partial load; polygons are triangulated inside themselves.
// More cases: tests/corpus/meshes (test_mesh_corpus.cpp).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <sys/resource.h>

#include <cstring>
#include <fstream>
#include <limits>
#include <sstream>

#include "core/error.h"
#include "scene/mesh_io.h"
#include "scene/mesh_validate.h"
#include "tests/temp_dir.h"

namespace rtbench {
namespace {
using ::testing::HasSubstr;

class MeshIo : public ::testing::Test {
protected:
    std::string write(const std::string& name, const std::string& text) { return dir_.write(name, text); }
    // The message of the rtbench::Error that reading `path` throws.
    static std::string errorOf(const std::string& path) {
        try {
            readMeshFile(path);
        } catch (const Error& e) {
            return e.what();
        }
        return "(no error)";
    }
    TempDir dir_;
};

const char* kTetrahedronOff =
    "OFF\n# a tetrahedron\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";

TEST_F(MeshIo, ReadsOffObjPlyStlAndTriangulatesPolygons) {
    const TriangleMesh off = readMeshFile(write("tet.off", kTetrahedronOff));
    EXPECT_EQ(off.vertices.size(), 4u);
    EXPECT_EQ(off.triangles.size(), 4u);
    EXPECT_EQ(off.triangles[0], glm::uvec3(0, 2, 1));

    const TriangleMesh quad = readMeshFile(write("quad.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n"));
    EXPECT_EQ(quad.polygonsRead, 1u);
    ASSERT_EQ(quad.triangles.size(), 2u);  // fan: (0,1,2), (0,2,3)
    EXPECT_EQ(quad.triangles[1], glm::uvec3(0, 2, 3));

    const TriangleMesh ply = readMeshFile(write("tri.ply",
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
        "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"));
    EXPECT_EQ(ply.triangles.size(), 1u);

    const TriangleMesh stl = readMeshFile(write("tri.stl",
        "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid t\n"));
    EXPECT_EQ(stl.triangles.size(), 1u);
}

TEST_F(MeshIo, MissingFile) {
    EXPECT_EQ(errorOf(dir_.file("nope.off")), dir_.file("nope.off") + ": mesh file not found");
}

TEST_F(MeshIo, UnknownExtension) {
    EXPECT_THAT(errorOf(write("mesh.xyz", "1 2 3\n")), HasSubstr("unknown mesh extension '.xyz' (allowed: .off, .obj, .ply, .stl)"));
}

TEST_F(MeshIo, TruncatedOffWithHeaderDeclaringMoreElements) {
    const std::string path = write("trunc.off", "OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n");
    const std::string error = errorOf(path);
    EXPECT_EQ(error, path + ": truncated: the header declares 4 vertices and 4 faces, the file holds 6 element lines");
}

TEST_F(MeshIo, TruncatedPly) {
    const std::string path = write("trunc.ply",
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
        "element face 2\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
    const std::string error = errorOf(path);
    EXPECT_EQ(error, path + ": truncated: element 'face' declares 2 items, the file ends before item 1");
}

TEST_F(MeshIo, IndexOutOfRangeNamesTheLine) {
    const std::string path = write("range.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n");
    const std::string error = errorOf(path);
    EXPECT_EQ(error, path + ":6: face 0 references vertex 7, but the file has 3 vertices (allowed: 0 to 2)");
    const std::string negative = write("negative.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 -1\n");
    EXPECT_EQ(errorOf(negative), negative + ":6: face 0 references vertex -1, but the file has 3 vertices (allowed: 0 to 2)");
    const std::string obj = write("range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n");
    EXPECT_EQ(errorOf(obj), obj + ":4: face 0: vertex index 9 is out of range (the file has 3 vertices; allowed: 1 to 3, or -1 back to -3 at this line)");
    // CGAL's read_OBJ would read 4294967298 as a failed int and report "face 0 has 2 vertices".
    const std::string huge = write("huge.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4294967298\n");
    EXPECT_THAT(errorOf(huge), HasSubstr(huge + ":4: face 0: vertex index 4294967298 is out of range"));
    // PLY: CGAL would read -5 as vertex 18446744073709551611.
    const std::string ply = write("negative.ply",
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
        "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 -5\n");
    EXPECT_EQ(errorOf(ply), ply + ":13: face 0 references vertex -5, but the file has 3 vertices (allowed: 0 to 2)");
}

TEST_F(MeshIo, NanOrInfiniteCoordinate) {
    const std::string path = write("nan.obj", "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n");
    EXPECT_EQ(errorOf(path), path + ":2: vertex 1 has a NaN or infinite coordinate ('nan'; allowed: finite numbers)");
    const std::string off = write("nan.off", "OFF\n3 1 0\n0 0 0\nnan 0 0\n0 1 0\n3 0 1 2\n");
    EXPECT_EQ(errorOf(off), off + ":4: vertex 1 has a NaN or infinite coordinate ('nan'; allowed: finite numbers)");
    const std::string inf = write("inf.off", "OFF\n3 1 0\n0 0 0\n1e39 0 0\n0 1 0\n3 0 1 2\n");
    EXPECT_THAT(errorOf(inf), HasSubstr(inf + ":4: vertex 1 overflows single precision"));
    const std::string ply = write("inf.ply",
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
        "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n0 inf 0\n0 1 0\n3 0 1 2\n");
    EXPECT_EQ(errorOf(ply), ply + ":11: vertex 1 has a NaN or infinite coordinate ('inf'; allowed: finite numbers)");
}

TEST_F(MeshIo, EmptyMesh) {
    const std::string path = write("empty.off", "OFF\n0 0 0\n");
    EXPECT_EQ(errorOf(path), path + ": no vertices and no faces (an empty mesh)");
    const std::string obj = write("empty.obj", "# nothing\n");
    EXPECT_EQ(errorOf(obj), obj + ": no vertices and no faces (an empty file?)");
    // CGAL says "empty file?" for a point cloud too.
    const std::string cloud = write("cloud.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n");
    EXPECT_EQ(errorOf(cloud), cloud + ": no faces, 3 vertices: a point cloud? (rtbench needs faces: 'f' lines)");
}

TEST_F(MeshIo, FaceWithTooFewVertices) {
    const std::string path = write("two.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n2 0 1\n");
    EXPECT_EQ(errorOf(path), path + ":6: face 0 has 2 vertices (at least 3 needed)");
}

TEST_F(MeshIo, GarbageIsAnErrorNotACrash) {
    const std::string off = write("garbage.off", "this is not a mesh\n\x01\x02\x03");
    EXPECT_EQ(errorOf(off), off + ": not an ASCII OFF file (no 'OFF' header with vertex and face counts)");
    const std::string stl = write("garbage.stl", std::string("\0\0\0", 3));
    EXPECT_THAT(errorOf(stl), HasSubstr(stl + ": too short for a binary STL (3 bytes) and does not begin with 'solid'"));
}

TEST_F(MeshIo, HeaderDeclaringMoreElementsThanTheFileCanHoldIsRefusedBeforeReading) {
    // A reader would reserve memory for 10^11 vertices; the size check refuses first.
    const std::string ply = write("huge.ply", "ply\nformat ascii 1.0\nelement vertex 99999999999\nproperty float x\nend_header\n");
    EXPECT_EQ(errorOf(ply), ply + ":3: the header declares 99999999999 'vertex' elements of at least 2 bytes each, more than the 0 bytes that follow the header can hold");
    const std::string off = write("huge.off", "OFF\n2000000000 1 0\n0 0 0\n");
    EXPECT_EQ(errorOf(off), off + ":2: the header declares 2000000000 vertices of at least 2 bytes each, more than the 6 bytes that follow the header can hold");
    const std::string noEnd = write("noend.ply", "ply\nformat ascii 1.0\nelement vertex 99999999999\n");
    EXPECT_EQ(errorOf(noEnd), noEnd + ": the PLY header has no 'end_header' line");
}

TEST_F(MeshIo, DegenerateTrianglesAreKeptAndCounted) {
    const TriangleMesh mesh = readMeshFile(write("degenerate.off",
        "OFF\n5 3 0\n0 0 0\n1 0 0\n0 1 0\n2 0 0\n0 0 1\n3 0 1 2\n3 0 1 3\n3 4 4 4\n"));
    EXPECT_EQ(mesh.triangles.size(), 3u);
    EXPECT_EQ(mesh.degenerateCount(), 2u);  // collinear (0,1,3) and a point (4,4,4)
}

// Binary PLY of issue 7: a 4e9 face count made CGAL's reader reserve 8.7 GB before failing.
TEST_F(MeshIo, HugeDeclaredCountIsRefusedFromTheFileSizeInLittleMemory) {
    std::string ply =
        "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
        "property float z\nelement face 4000000000\nproperty list uchar int vertex_indices\nend_header\n";
    const float xyz[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    ply.append(reinterpret_cast<const char*>(xyz), sizeof xyz);
    const std::int32_t face[3] = {0, 1, 2};
    ply += '\3';
    ply.append(reinterpret_cast<const char*>(face), sizeof face);
    rusage before{}, after{};
    getrusage(RUSAGE_SELF, &before);
    const std::string path = write("huge.ply", ply);
    EXPECT_EQ(errorOf(path), path + ":7: the header declares 4000000000 'face' elements of at least 1 bytes each, more than the 13 bytes that follow the header can hold");
    const std::string off = write("huge.off", "OFF\n3 4000000000 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
    EXPECT_THAT(errorOf(off), HasSubstr(off + ":2: the header declares 4000000000 faces of at least 2 bytes each"));
    getrusage(RUSAGE_SELF, &after);
    EXPECT_LT(after.ru_maxrss - before.ru_maxrss, 64L << 10) << "peak memory grew by more than 64 MiB";
}

TEST_F(MeshIo, BinaryStlSizeMustMatchItsTriangleCount) {
    auto stl = [](std::uint32_t count, int records) {
        std::string bytes(80, '\0');
        bytes.append(reinterpret_cast<const char*>(&count), 4);
        for (int r = 0; r < records; ++r) {
            const float v[12] = {0, 0, 1, 0, 0, float(r), 1, 0, float(r), 0, 1, float(r)};
            bytes.append(reinterpret_cast<const char*>(v), sizeof v);
            bytes.append(2, '\0');
        }
        return bytes;
    };
    EXPECT_EQ(readMeshFile(write("ok.stl", stl(2, 2))).triangles.size(), 2u);
    const std::string low = write("low.stl", stl(1, 2));
    EXPECT_EQ(errorOf(low), low + ": byte 80: binary STL: the header declares 1 triangles, which take 84 + 50 x 1 = 134 bytes, but the file has 184 (50 bytes more; the size must match exactly)");
    const std::string high = write("high.stl", stl(3, 2));
    EXPECT_THAT(errorOf(high), HasSubstr("but the file has 184 (50 bytes fewer"));
    std::string nan = stl(2, 2);
    const float notANumber = std::numeric_limits<float>::quiet_NaN();
    std::memcpy(&nan[84 + 50 + 12 + 4], &notANumber, 4);  // triangle 1, vertex 0, y
    const std::string nanPath = write("nan.stl", nan);
    EXPECT_EQ(errorOf(nanPath), nanPath + ": byte 150: triangle 1 has a NaN or infinite coordinate (allowed: finite numbers)");
}

// CGAL's read_STL takes "solid<TAB>name" for binary (assimp's sphereWithHole.stl: 1,036 garbage
// facets, then the 285 real ones); a binary file whose header begins with "solid " is binary.
TEST_F(MeshIo, StlModeIsDecidedByTheFileNotItsFirstWord) {
    const std::string facet =
        "facet normal 0 0 1\nouter loop\nvertex 0 0 5\nvertex 1 0 5\nvertex 0 1 5\nendloop\nendfacet\n";
    const TriangleMesh ascii = readMeshFile(write("tab.stl",
        "solid\ta name long enough to fill the eighty bytes of a binary header, and more\n" + facet + "endsolid\n"));
    ASSERT_EQ(ascii.triangles.size(), 1u);
    ASSERT_EQ(ascii.vertices.size(), 3u);
    EXPECT_EQ(ascii.vertices[ascii.triangles[0][1]], glm::vec3(1, 0, 5));

    std::string binary = "solid but binary";
    binary.resize(80, ' ');
    const std::uint32_t one = 1;
    binary.append(reinterpret_cast<const char*>(&one), 4);
    const float v[12] = {0, 0, 1, 0, 0, 5, 1, 0, 5, 0, 1, 5};
    binary.append(reinterpret_cast<const char*>(v), sizeof v);
    binary.append(2, '\0');
    EXPECT_EQ(readMeshFile(write("solidbinary.stl", binary)).triangles.size(), 1u);
}

TEST_F(MeshIo, NothingFromTheReaderReachesStdoutOrStderr) {
    std::string stl(80, '\0');  // CGAL's verbose binary STL reader prints the header, NULs and all
    const std::uint32_t one = 1;
    stl.append(reinterpret_cast<const char*>(&one), 4);
    const float v[12] = {0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0};
    stl.append(reinterpret_cast<const char*>(v), sizeof v);
    stl.append(2, '\0');
    ::testing::internal::CaptureStdout();
    ::testing::internal::CaptureStderr();
    const TriangleMesh mesh = readMeshFile(write("nul.stl", stl));
    readMeshFile(write("normals.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nvt 0 0\nf 1/1/1 2/1/1 3/1/1\n"));
    errorOf(write("bad.obj", "v 0 0 0\nf 1 2 3\n"));
    EXPECT_EQ(::testing::internal::GetCapturedStdout(), "");
    EXPECT_EQ(::testing::internal::GetCapturedStderr(), "");
    EXPECT_EQ(mesh.triangles.size(), 1u);
}

TEST_F(MeshIo, OffHeaderWithoutEdgeCountKeepsEveryVertex) {
    const TriangleMesh mesh = readMeshFile(write("noedges.off",
        "OFF\n4 2\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n"));
    ASSERT_EQ(mesh.vertices.size(), 4u);
    EXPECT_EQ(mesh.vertices[0], glm::vec3(0, 0, 0));  // CGAL alone read (0, 0, 1) here
    EXPECT_EQ(mesh.vertices[1], glm::vec3(1, 0, 0));
    EXPECT_EQ(mesh.triangles.size(), 2u);
}

TEST_F(MeshIo, ExtraFacesNonIntegerIndicesAndTrailingJunkAreErrors) {
    const std::string tri = "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n";
    const std::string extra = write("extra.off", tri + "3 0 1 2\n3 0 2 1\n");
    EXPECT_EQ(errorOf(extra), extra + ":7: data after the last of the 1 faces the header declares: '3 0 2 1' (is the face count too low?)");
    const std::string fraction = write("fraction.off", tri + "3 0 1 1.7\n");
    EXPECT_EQ(errorOf(fraction), fraction + ":6: face 0: vertex index '1.7' is not an integer");
}

// Signed area of a polygon in 3D (half the length of Newell's normal) and of triangles.
double polygonArea(const std::vector<glm::dvec3>& p) {
    glm::dvec3 normal(0.0);
    for (std::size_t i = 0; i < p.size(); ++i) normal += glm::cross(p[i], p[(i + 1) % p.size()]);
    return glm::length(normal) / 2;
}
double triangulatedArea(const TriangleMesh& mesh, glm::dvec3 normal) {
    double area = 0.0;
    for (const glm::uvec3& t : mesh.triangles) {
        const glm::dvec3 a(mesh.vertices[t[0]]), b(mesh.vertices[t[1]]), c(mesh.vertices[t[2]]);
        const glm::dvec3 n = glm::cross(b - a, c - a);
        EXPECT_GT(glm::dot(n, normal), 0.0) << "a triangle is degenerate or wound against the polygon";
        area += glm::length(n) / 2;
    }
    return area;
}

TEST_F(MeshIo, ConcaveLShapeIsTriangulatedInsideItself) {
    // The L: a 2x2 square without its top-right unit square. Its fan from vertex 0 would cover
    // the missing square with triangle (0, 2, 3).
    const TriangleMesh mesh = readMeshFile(write("l.obj",
        "v 0 0 0\nv 2 0 0\nv 2 1 0\nv 1 1 0\nv 1 2 0\nv 0 2 0\nf 1 2 3 4 5 6\n"));
    ASSERT_EQ(mesh.triangles.size(), 4u);
    EXPECT_DOUBLE_EQ(triangulatedArea(mesh, {0, 0, 1}), 3.0);
    for (const glm::uvec3& t : mesh.triangles) {
        const glm::vec3 centroid = (mesh.vertices[t[0]] + mesh.vertices[t[1]] + mesh.vertices[t[2]]) / 3.0f;
        EXPECT_FALSE(centroid.x > 1 && centroid.y > 1) << "a triangle lies in the missing square";
    }
    EXPECT_EQ(mesh.degenerateCount(), 0u);
}

TEST_F(MeshIo, ConcavePolygonTriangulationHasThePolygonsArea) {
    // assimp's concave_polygon.obj: a 66-gon, an outline and a hole joined by a bridge walked
    // both ways. Fanned, its 64 triangles covered 13 times its area.
    const std::string path = RTBENCH_SOURCE_DIR "/tests/corpus/meshes/assimp_concave_polygon.obj";
    const TriangleMesh mesh = readMeshFile(path);
    std::ifstream in(path);
    std::string line;
    std::vector<glm::dvec3> polygon;
    while (std::getline(in, line))
        if (line.rfind("f ", 0) == 0) {
            std::istringstream corners(line.substr(2));
            std::size_t index;
            std::string rest;
            while (corners >> index) {
                polygon.emplace_back(mesh.vertices[index - 1]);
                corners >> rest;  // "//1"
            }
        }
    ASSERT_EQ(polygon.size(), 66u);
    ASSERT_EQ(mesh.triangles.size(), 64u);
    EXPECT_NEAR(triangulatedArea(mesh, {1, 0, 0}), polygonArea(polygon), 1e-6 * polygonArea(polygon));
}

TEST_F(MeshIo, ConvexPolygonsKeepTheirFan) {
    const TriangleMesh mesh = readMeshFile(write("pentagon.off",
        "OFF\n5 1 0\n0 0 0\n2 0 0\n3 1 0\n1 2 0\n-1 1 0\n5 0 1 2 3 4\n"));
    const std::vector<glm::uvec3> fan = {{0, 1, 2}, {0, 2, 3}, {0, 3, 4}};
    EXPECT_EQ(mesh.triangles, fan);
    const TriangleMesh warped = readMeshFile(write("warped.off",
        "OFF\n4 1 0\n0 0 0\n1 0 0\n1 1 0.5\n0 1 0\n4 0 1 2 3\n"));  // convex seen from above
    EXPECT_EQ(warped.triangles, std::vector<glm::uvec3>({{0, 1, 2}, {0, 2, 3}}));
    const std::string nonPlanar = write("nonplanar.off",
        "OFF\n5 1 0\n0 0 0\n2 0 0\n2 2 1\n1 0.5 0\n0 2 0\n5 0 1 2 3 4\n");
    EXPECT_THAT(errorOf(nonPlanar), HasSubstr(nonPlanar + ":8: face 0 (5 vertices) cannot be triangulated: it is not planar and not convex: its corner 3 (of 5) lies"));
}

// Found by fuzz_mesh (tests/corpus/fuzz/fuzz_mesh/obj_degenerate_quad_cdt_null_face.obj): a
// planar face with a repeated corner and one coordinate of 3e17. Newell's normal on absolute
// coordinates cancelled, the wrong axis was dropped, the projection was a line and the
// triangulation of a line was walked as if it had faces (a null dereference).
TEST_F(MeshIo, APolygonFarFromTheOriginIsProjectedAlongItsRealNormal) {
    const std::string path = write("far.obj",
        "v 0 0 5\nv -.5 5 -.5\nv 0 .5 -.5\nv 5 5 0\nv 0 0 5\nv 0 333333333333333333 -.5\nv -.5 5 -.5\nf 3 7 6 2\n");
    EXPECT_THAT(errorOf(path), HasSubstr(path + ":8: face 0 (4 vertices) cannot be triangulated: it overlaps itself"));
    // The same L-shape far along y triangulates as it does at the origin.
    const TriangleMesh far = readMeshFile(write("farL.obj",
        "v 0 1e15 0\nv 2 1e15 0\nv 2 1e15 1\nv 1 1e15 1\nv 1 1e15 2\nv 0 1e15 2\nf 1 2 3 4 5 6\n"));
    EXPECT_EQ(far.triangles.size(), 4u);
}

TEST_F(MeshIo, LineAndPointElementsAreSkippedAndCounted) {
    const TriangleMesh mesh = readMeshFile(write("mixed.obj",
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nl 1 2\np 3\nl 2 3\nf 1 2 3\n"));
    EXPECT_EQ(mesh.triangles.size(), 1u);
    EXPECT_EQ(mesh.elementsSkipped, 3u);
    EXPECT_EQ(mesh.elementsSkippedWhat, "2 line elements ('l') and 1 point elements ('p')");
}

TEST_F(MeshIo, NonUtf8BytesAreEscapedInMessages) {
    const std::string path = write("latin1.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 caf\xe9\n");
    EXPECT_EQ(errorOf(path), path + ":4: face 0: vertex index 'caf\\xE9' is not an integer");
    EXPECT_EQ(printable("ok \xc3\xa9 \xff\x01\xc3"), "ok \xc3\xa9 \\xFF\\x01\\xC3");
}

TEST(MeshBytes, ReadsFromMemoryWithTheNamesExtension) {
    EXPECT_EQ(readMeshBytes("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "memory.obj").triangles.size(), 1u);
    try {
        readMeshBytes("v 0 0 0\n", "memory.obj");
        FAIL();
    } catch (const Error& e) {
        EXPECT_STREQ(e.what(), "memory.obj: no faces, 1 vertices: a point cloud? (rtbench needs faces: 'f' lines)");
    }
}

TEST(CgalMeshes, ResolvesBunnyAndRejectsUnknownNames) {
    const std::string path = resolveCgalMesh("bunny00");
    const TriangleMesh bunny = readMeshFile(path);
    EXPECT_EQ(bunny.triangles.size(), 75408u);
    try {
        resolveCgalMesh("no_such_mesh");
        FAIL();
    } catch (const Error& e) {
        EXPECT_THAT(e.what(), HasSubstr("cgal:no_such_mesh: no such mesh in libcgal-demo"));
    }
}

}  // namespace
}  // namespace rtbench
