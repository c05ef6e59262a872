// Every malformed-mesh case produces its error message (asserted), never a crash or a partial load.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "structures/error.h"
#include "structures/mesh_io.h"
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
    EXPECT_EQ(error, path + ": the CGAL reader failed");  // CGAL's PLY reader says no more
}

TEST_F(MeshIo, IndexOutOfRangeNamesTheLine) {
    const std::string path = write("range.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n");
    const std::string error = errorOf(path);
    EXPECT_EQ(error, path + ":6: face 0 references vertex 7, but the file has 3 vertices");
    const std::string negative = write("negative.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 -1\n");
    EXPECT_EQ(errorOf(negative), negative + ":6: face 0 references vertex -1, but the file has 3 vertices");
    const std::string obj = write("range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n");
    EXPECT_EQ(errorOf(obj), obj + ": the CGAL reader failed (error: invalid face index)");
}

TEST_F(MeshIo, NanOrInfiniteCoordinate) {
    const std::string path = write("nan.obj", "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n");
    EXPECT_EQ(errorOf(path), path + ": the CGAL reader failed (error while reading OBJ vertex.)");
    const std::string off = write("nan.off", "OFF\n3 1 0\n0 0 0\nnan 0 0\n0 1 0\n3 0 1 2\n");
    EXPECT_EQ(errorOf(off), off + ":4: vertex 1 has a NaN or infinite coordinate");
    const std::string inf = write("inf.off", "OFF\n3 1 0\n0 0 0\n1e39 0 0\n0 1 0\n3 0 1 2\n");
    EXPECT_THAT(errorOf(inf), HasSubstr(inf + ":4: vertex 1 overflows single precision"));
}

TEST_F(MeshIo, EmptyMesh) {
    const std::string path = write("empty.off", "OFF\n0 0 0\n");
    EXPECT_EQ(errorOf(path), path + ": the mesh has no faces");
    const std::string obj = write("empty.obj", "# nothing\n");
    EXPECT_EQ(errorOf(obj), obj + ": the CGAL reader failed (warning: empty file?)");
}

TEST_F(MeshIo, FaceWithTooFewVertices) {
    const std::string path = write("two.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n2 0 1\n");
    EXPECT_EQ(errorOf(path), path + ":6: face 0 has 2 vertices (at least 3 needed)");
}

TEST_F(MeshIo, GarbageIsAnErrorNotACrash) {
    const std::string off = write("garbage.off", "this is not a mesh\n\x01\x02\x03");
    EXPECT_EQ(errorOf(off), off + ": not an ASCII OFF file (no 'OFF' header with vertex and face counts)");
    const std::string stl = write("garbage.stl", std::string("\0\0\0", 3));
    EXPECT_EQ(errorOf(stl), stl + ": the mesh has no faces");
}

TEST_F(MeshIo, HeaderDeclaringMoreElementsThanTheFileCanHoldIsRefusedBeforeReading) {
    // A reader would reserve memory for 10^11 vertices; the size check refuses first.
    const std::string ply = write("huge.ply", "ply\nformat ascii 1.0\nelement vertex 99999999999\n");
    EXPECT_EQ(errorOf(ply), ply + ": truncated: the header declares 99999999999 vertices and 0 faces, but the file has only 48 bytes");
    const std::string off = write("huge.off", "OFF\n2000000000 1 0\n0 0 0\n");
    EXPECT_EQ(errorOf(off), off + ": truncated: the header declares 2000000000 vertices and 1 faces, but the file has only 25 bytes");
}

TEST_F(MeshIo, DegenerateTrianglesAreKeptAndCounted) {
    const TriangleMesh mesh = readMeshFile(write("degenerate.off",
        "OFF\n5 3 0\n0 0 0\n1 0 0\n0 1 0\n2 0 0\n0 0 1\n3 0 1 2\n3 0 1 3\n3 4 4 4\n"));
    EXPECT_EQ(mesh.triangles.size(), 3u);
    EXPECT_EQ(mesh.degenerateCount(), 2u);  // collinear (0,1,3) and a point (4,4,4)
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
