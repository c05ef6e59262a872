#!/usr/bin/env python3
"""Writes the hostile-mesh corpus and its manifest expected.tsv (run from this folder).

Each case: a file name, its bytes, and its expected outcome for rtbench's reader: `triangles N`
(loads, N triangles) or `error TEXT` (an rtbench::Error whose message contains TEXT; the
message begins with the file's path, so TEXT starts at the ':LINE:' or ': byte N:' after it).
The assimp_* files are copied from Debian's assimp-testmodels (BSD-3-clause, see README.md) and
only listed here. tests/scene/test_mesh_corpus.cpp runs the manifest.
"""
import struct

CASES = []


def case(name, data, outcome, expected, note):
    if isinstance(data, str):
        data = data.encode("utf-8", "surrogateescape")
    CASES.append((name, data, outcome, str(expected), note))


def assimp(name, outcome, expected, note):
    CASES.append((name, None, outcome, str(expected), note))


TRI_OFF = "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"
TET_OFF = "OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n"
CUBE_V = "0 0 0\n1 0 0\n1 1 0\n0 1 0\n0 0 1\n1 0 1\n1 1 1\n0 1 1\n"
CUBE_F = "4 0 3 2 1\n4 4 5 6 7\n4 0 1 5 4\n4 1 2 6 5\n4 2 3 7 6\n4 3 0 4 7\n"

# ---- OFF ----
case("off_no_edge_count.off", "OFF\n8 6\n" + CUBE_V + CUBE_F, "triangles", 12,
     "header without the edge count: vertex 0 keeps its own coordinates")
case("off_extra_face.off", TRI_OFF + "3 0 2 1\n", "error",
     ":7: data after the last of the 1 faces the header declares", "declares 1 face, 2 follow")
case("off_noninteger_index.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 1.7\n", "error",
     ":6: face 0: vertex index '1.7' is not an integer", "CGAL would truncate 1.7 to 1")
case("off_trailing_junk.off", TRI_OFF + "junk\n", "error",
     ":7: data after the last of the 1 faces the header declares: 'junk'", "trailing junk")
case("off_negative_index.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 -1\n", "error",
     ":6: face 0 references vertex -1, but the file has 3 vertices (allowed: 0 to 2)",
     "CGAL's scanner would cast -1.0 to size_t")
case("off_huge_vertex_count.off", "OFF\n4000000000 1 0\n0 0 0\n", "error",
     ":2: the header declares 4000000000 vertices of at least 2 bytes each, more than the 6 bytes",
     "refused before any allocation")
case("off_huge_face_count.off", "OFF\n3 99999999999 0\n0 0 0\n1 0 0\n0 1 0\n", "error",
     ":2: the header declares 99999999999 faces of at least 2 bytes each", "refused before any allocation")
case("off_truncated.off", "OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n", "error",
     "truncated: the header declares 4 vertices and 4 faces, the file holds 6 element lines", "two faces missing")
case("off_nan.off", "OFF\n3 1 0\n0 0 0\nnan 0 0\n0 1 0\n3 0 1 2\n", "error",
     ":4: vertex 1 has a NaN or infinite coordinate ('nan'", "NaN coordinate")
case("off_inf.off", "OFF\n3 1 0\n0 0 0\n0 -inf 0\n0 1 0\n3 0 1 2\n", "error",
     ":4: vertex 1 has a NaN or infinite coordinate ('-inf'", "infinite coordinate")
case("off_float_overflow.off", "OFF\n3 1 0\n0 0 0\n1e39 0 0\n0 1 0\n3 0 1 2\n", "error",
     ":4: vertex 1 overflows single precision ('1e39'", "finite double, infinite float")
case("off_crlf.off", TET_OFF.replace("\n", "\r\n"), "triangles", 4, "CRLF line endings")
case("off_bom.off", "\ufeff" + TET_OFF, "triangles", 4, "UTF-8 byte-order mark")
case("off_header_only.off", "OFF\n", "error", "not an ASCII OFF file", "keyword without counts")
case("off_empty.off", "", "error", "not an ASCII OFF file", "empty file")
case("off_latin1_comment.off", "# caf\udce9 cr\udce8me\n" + TET_OFF, "triangles", 4,
     "non-UTF-8 bytes in a comment")
case("off_latin1_junk.off", TRI_OFF + "caf\udce9\n", "error", "'caf\\xE9'",
     "non-UTF-8 bytes in a message are escaped")
case("off_face_colors.off", "COFF\n3 1 0\n0 0 0 1 1 1 1\n1 0 0 1 1 1 1\n0 1 0 1 1 1 1\n3 0 1 2 255 0 0\n",
     "triangles", 1, "vertex and face colors")
case("off_color_out_of_range.off", "COFF\n3 1 0\n0 0 0 2550 552 -1\n1 0 0 1 1 1\n0 1 0 1 1 1\n3 0 1 2 1e30\n",
     "triangles", 1, "colors CGAL would cast to unsigned char (undefined behaviour) are not passed on")
case("off_too_many_face_values.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2 1 1 1 1 1\n", "error",
     ":6: face 0 has 5 values after its 3 vertex indices (allowed: a color of at most 4 numbers)",
     "more than a color after the indices")
case("off_binary.off", "OFF BINARY\n", "error", "unsupported OFF variant 'OFF' BINARY", "binary OFF")
case("off_4d.off", "4OFF\n3 1 0\n0 0 0 1\n1 0 0 1\n0 1 0 1\n3 0 1 2\n", "error",
     ":1: unsupported OFF variant '4OFF'", "4D vertices")
case("off_two_vertex_face.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n2 0 1\n", "error",
     ":6: face 0 has 2 vertices (at least 3 needed)", "degenerate face")
case("off_concave_l.off", "OFF\n6 1 0\n0 0 0\n2 0 0\n2 1 0\n1 1 0\n1 2 0\n0 2 0\n6 0 1 2 3 4 5\n",
     "triangles", 4, "concave L-shaped hexagon: 4 triangles of total area 3")
case("off_bowtie.off", "OFF\n4 1 0\n0 0 0\n1 1 0\n1 0 0\n0 1 0\n4 0 1 2 3\n", "error",
     ":7: face 0 (4 vertices) cannot be triangulated: its edges enclose zero net area", "bow-tie quad")
case("off_pentagram.off",
     "OFF\n5 1 0\n0 1 0\n0.5878 -0.809 0\n-0.9511 0.309 0\n0.9511 0.309 0\n-0.5878 -0.809 0\n5 0 1 2 3 4\n",
     "error", ":8: face 0 (5 vertices) cannot be triangulated: it is self-intersecting", "star polygon")
case("off_nonplanar.off", "OFF\n5 1 0\n0 0 0\n2 0 0\n2 2 1\n1 0.5 0\n0 2 0\n5 0 1 2 3 4\n", "error",
     ":8: face 0 (5 vertices) cannot be triangulated: it is not planar", "concave and not planar")
case("off_index_equals_count.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n", "error",
     ":6: face 0 references vertex 3, but the file has 3 vertices (allowed: 0 to 2)",
     "an index equal to the vertex count, one past the last (issue 15)")
case("off_quad_index_equals_count.off", "OFF\n4 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n4 0 1 2 4\n", "error",
     ":8: face 1 references vertex 4, but the file has 4 vertices (allowed: 0 to 3)",
     "the last corner of a quad one past the last vertex")
case("off_inline_header_index_equals_count.off", "OFF 3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 3 1 2\n", "error",
     ":5: face 0 references vertex 3, but the file has 3 vertices (allowed: 0 to 2)",
     "counts on the OFF line, first corner one past the last vertex")
case("off_index_is_last_vertex.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 2 1 0\n", "triangles", 1,
     "the largest allowed index, count - 1")
assimp("assimp_invalid.off", "error", ":6: face 0 has 0 vertices (at least 3 needed)",
       "header '3 4' without edge count, then faces '0', '2\\r20', '4'")
assimp("assimp_OutOfMemory.off", "error", ":2: the header declares 353535235358 vertices",
       "absurd count: refused before any allocation")

# ---- OBJ ----
OBJ_V = "v 0 0 0\nv 1 0 0\nv 0 1 0\n"
case("obj_index_4294967298.obj", OBJ_V + "f 1 2 4294967298\n", "error",
     ":4: face 0: vertex index 4294967298 is out of range (the file has 3 vertices", "index beyond 32 bits")
case("obj_index_zero.obj", OBJ_V + "f 0 1 2\n", "error", ":4: face 0: vertex index 0 is out of range",
     "OBJ indices start at 1")
case("obj_relative_indices.obj", OBJ_V + "f -3 -2 -1\n", "triangles", 1, "negative indices count back")
case("obj_relative_too_far.obj", OBJ_V + "f -4 -2 -1\n", "error", ":4: face 0: vertex index -4 is out of range",
     "relative index before the first vertex")
case("obj_index_one_past_count.obj", OBJ_V + "f 1 2 4\n", "error",
     ":4: face 0: vertex index 4 is out of range (the file has 3 vertices; allowed: 1 to 3, or -1 back to -3 at this line)",
     "1-based: an index of count + 1 is one past the last")
case("obj_index_equals_count.obj", OBJ_V + "f 3 1 2\n", "triangles", 1, "1-based: the count is the last vertex")
case("obj_forward_reference.obj", "v 0 0 0\nv 1 0 0\nf 1 2 3\nv 0 1 0\n", "triangles", 1,
     "a face naming a vertex defined after it (the reader reads all vertices first)")
case("obj_relative_before_later_vertices.obj", "v 0 0 0\nv 1 0 0\nf -3 -2 -1\nv 0 1 0\n", "error",
     ":3: face 0: vertex index -3 is out of range (the file has 3 vertices; allowed: 1 to 3, or -1 back to -2 at this line)",
     "relative indices count back from the vertices read so far, not from the file's count")
case("obj_noninteger.obj", OBJ_V + "f 1 2 2.5\n", "error", ":4: face 0: vertex index '2.5' is not an integer",
     "non-integer index")
case("obj_nan.obj", "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n", "error",
     ":2: vertex 1 has a NaN or infinite coordinate ('nan'", "NaN coordinate")
case("obj_inf.obj", "v 0 0 0\nv 0 0 inf\nv 0 1 0\nf 1 2 3\n", "error",
     ":2: vertex 1 has a NaN or infinite coordinate ('inf'", "infinite coordinate")
case("obj_short_vertex.obj", "v 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "error",
     ":1: vertex 0 has fewer than 3 coordinates", "2D vertex")
case("obj_point_cloud.obj", OBJ_V, "error", "no faces, 3 vertices: a point cloud?", "vertices only")
case("obj_empty.obj", "", "error", "no vertices and no faces (an empty file?)", "empty file")
case("obj_unknown_statement.obj", OBJ_V + "xyz 1 2\nf 1 2 3\n", "error",
     ":4: unrecognized statement 'xyz'", "unknown statement")
case("obj_crlf.obj", (OBJ_V + "f 1 2 3\n").replace("\n", "\r\n"), "triangles", 1, "CRLF line endings")
case("obj_bom.obj", "\ufeff" + OBJ_V + "f 1 2 3\n", "triangles", 1, "UTF-8 byte-order mark")
case("obj_tabs_and_slashes.obj", OBJ_V + "vt 0 0\nvn 0 0 1\nf\t1/1/1\t2//1\t3/1\n", "triangles", 1,
     "tab-separated corners in all slash forms")
case("obj_utf16.obj", "\ufeffv 0 0 0\n".encode("utf-16-be"), "error", "UTF-16 text is not supported",
     "UTF-16 text")
case("obj_latin1_group.obj", "g caf\udce9\n" + OBJ_V + "f 1 2 3\n", "triangles", 1,
     "non-UTF-8 bytes in a group name")
case("obj_lines_only.obj", OBJ_V + "l 1 2 3\n", "error",
     "no faces, 3 vertices: a point cloud? (rtbench needs faces: 'f' lines); skipped 1 line elements",
     "polyline only")
assimp("assimp_testmixed.obj", "triangles", 12, "faces mixed with 'l' and 'p' elements, which are skipped")
assimp("assimp_concave_polygon.obj", "triangles", 64,
       "66-gon: an outline and a hole joined by a bridge (keyhole); fan would cover 13x its area")
assimp("assimp_malformed2.obj", "error", ":23: face 0 has 0 vertices (at least 3 needed)", "bare 'f'")
assimp("assimp_box_longline.obj", "error", ":24: face 0 (936 vertices) cannot be triangulated: it overlaps itself",
       "a quad walked 234 times as one polygon")

# ---- PLY ----
def ply_header(fmt, nv, nf, index_type="int", extra=""):
    return ("ply\nformat %s 1.0\nelement vertex %d\nproperty float x\nproperty float y\nproperty float z\n"
            "%selement face %d\nproperty list uchar %s vertex_indices\nend_header\n"
            % (fmt, nv, extra, nf, index_type))


ASCII_TRI = "0 0 0\n1 0 0\n0 1 0\n"
case("ply_ascii.ply", ply_header("ascii", 3, 1) + ASCII_TRI + "3 0 1 2\n", "triangles", 1, "ASCII triangle")
case("ply_crlf.ply", (ply_header("ascii", 3, 1) + ASCII_TRI + "3 0 1 2\n").replace("\n", "\r\n"),
     "triangles", 1, "CRLF line endings")
case("ply_negative_index.ply", ply_header("ascii", 3, 1) + ASCII_TRI + "3 0 1 -5\n", "error",
     ":13: face 0 references vertex -5, but the file has 3 vertices", "CGAL would read 18446744073709551611")
case("ply_inf.ply", ply_header("ascii", 3, 1) + "0 0 0\ninf 0 0\n0 1 0\n3 0 1 2\n", "error",
     ":11: vertex 1 has a NaN or infinite coordinate ('inf'", "infinite coordinate")
case("ply_point_cloud.ply",
     "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
     "end_header\n" + ASCII_TRI, "error", "no faces, 3 vertices: a point cloud?", "no face element")
case("ply_ushort_indices.ply", ply_header("ascii", 3, 1, "ushort") + ASCII_TRI + "3 0 1 2\n", "error",
     ":7: the face element needs a list property 'vertex_indices' or 'vertex_index' of int or uint items "
     "(the reader takes no other), found items of type ushort", "list type CGAL cannot take")
case("ply_truncated.ply", ply_header("ascii", 3, 2) + ASCII_TRI + "3 0 1 2\n", "error",
     "truncated: element 'face' declares 2 items, the file ends before item 1", "one face missing")
case("ply_uchar_overflow.ply", ply_header("ascii", 3, 1) + ASCII_TRI + "300 0 1 2\n", "error",
     ":13: face 0: '300' is not an integer of type uchar", "a list count beyond its type")
case("ply_extra_values.ply", ply_header("ascii", 3, 1) + ASCII_TRI + "3 0 1 2 7\n", "error",
     ":13: face 0 has 5 values, its properties declare 4", "a value too many")
case("ply_trailing.ply", ply_header("ascii", 3, 1) + ASCII_TRI + "3 0 1 2\n3 0 2 1\n", "error",
     ":14: data after the last element the header declares", "more faces than declared")
PLY_V3 = "element vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
PLY_F1 = "element face 1\nproperty list uchar int vertex_indices\n"
case("ply_index_equals_count.ply", ply_header("ascii", 3, 1) + ASCII_TRI + "3 0 1 3\n", "error",
     ":13: face 0 references vertex 3, but the file has 3 vertices (allowed: 0 to 2)",
     "an index equal to the vertex count, one past the last")
case("ply_blank_header_line.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n\nproperty float y\n"
     "property float z\n" + PLY_F1 + "end_header\n" + ASCII_TRI + "3 0 1 2\n", "error",
     ":5: empty line in the PLY header", "CGAL's header parser stops at a blank line and reads nothing")
case("ply_comment_before_format.ply", "ply\ncomment made by hand\nformat ascii 1.0\n" + PLY_V3 + PLY_F1 +
     "end_header\n" + ASCII_TRI + "3 0 1 2\n", "error",
     ":2: expected the 'format' line right after 'ply', found 'comment made by hand'",
     "CGAL takes the second line for the format line")
case("ply_second_format.ply", "ply\nformat binary_little_endian 1.0\n" + PLY_V3 + PLY_F1 + "format ascii 1.0\n"
     "end_header\n" + ASCII_TRI + "3 0 1 2\n", "error", ":9: a second 'format' line",
     "validation took the last format, the reader the first")
case("ply_two_index_lists.ply", "ply\nformat ascii 1.0\n" + PLY_V3 + PLY_F1 +
     "property list uchar int vertex_indices\nend_header\n" + ASCII_TRI + "0 3 0 1 2\n", "error",
     ":9: element 'face' has a second property 'vertex_indices' (allowed: each property name once)",
     "validation checked the second list, CGAL built an empty polygon from the first: a crash")
case("ply_vertex_index_and_indices.ply", "ply\nformat ascii 1.0\n" + PLY_V3 +
     "element face 1\nproperty list uchar int vertex_index\nproperty list uchar int vertex_indices\nend_header\n" +
     ASCII_TRI + "3 0 1 7 3 0 1 2\n", "error",
     ":7: the face element has two index lists, 'vertex_indices' and 'vertex_index' (allowed: one)",
     "two index lists: which one the reader takes is not validation's choice")
case("ply_duplicate_coordinate.ply", "ply\nformat ascii 1.0\n" + PLY_V3 + "property float x\n" + PLY_F1 +
     "end_header\n0 0 0 9\n1 0 0 9\n0 1 0 9\n3 0 1 2\n", "error",
     ":7: element 'vertex' has a second property 'x' (allowed: each property name once)", "x given twice")
case("ply_two_vertex_elements.ply", "ply\nformat ascii 1.0\n" + PLY_V3.replace(" 3\n", " 1\n") + PLY_V3 + PLY_F1 +
     "end_header\n9 9 9\n" + ASCII_TRI + "3 0 1 2\n", "error",
     ":7: a second vertex element 'vertex' (the first, 'vertex', is at line 3; allowed: one of each)",
     "CGAL reads the vertices of both, validation counted one")
case("ply_vertex_and_vertices.ply", "ply\nformat ascii 1.0\n" + PLY_V3.replace(" 3\n", " 1\n") +
     PLY_V3.replace("vertex", "vertices") + PLY_F1 + "end_header\n9 9 9\n" + ASCII_TRI + "3 0 1 2\n", "error",
     ":7: a second vertex element 'vertices' (the first, 'vertex', is at line 3; allowed: one of each)",
     "'vertex' and 'vertices' are both vertex elements")
case("ply_two_face_elements.ply", "ply\nformat ascii 1.0\n" + PLY_V3 + PLY_F1 + PLY_F1 + "end_header\n" +
     ASCII_TRI + "3 0 1 3\n3 0 1 2\n", "error",
     ":9: a second face element 'face' (the first, 'face', is at line 7; allowed: one of each)",
     "the first face element's indices went unchecked, CGAL read both")
case("ply_no_end_header.ply", "ply\nformat ascii 1.0\nelement vertex 3\n", "error",
     "the PLY header has no 'end_header' line", "header only")
case("ply_int_coordinates.ply", ply_header("ascii", 3, 1).replace("float", "int") + ASCII_TRI + "3 0 1 2\n",
     "error", ":3: vertex property 'x' must be a float or double scalar", "integer coordinates")
case("ply_empty.ply", "", "error", "not a PLY file", "empty file")

VERTS = [(0, 0, 0), (1, 0, 0), (0, 1, 0)]


def ply_binary(nf_declared, faces, verts=VERTS, endian="<", fmt="binary_little_endian", trailing=b"", index="int"):
    body = b"".join(struct.pack(endian + "3f", *v) for v in verts)
    for f in faces:
        body += struct.pack(endian + "B%d%s" % (len(f), "i" if index == "int" else "I"), len(f), *f)
    return ply_header(fmt, len(verts), nf_declared, index).encode() + body + trailing


case("ply_binary.ply", ply_binary(1, [(0, 1, 2)]), "triangles", 1, "binary little endian")
case("ply_binary_big_endian.ply", ply_binary(1, [(0, 1, 2)], endian=">", fmt="binary_big_endian"),
     "triangles", 1, "binary big endian")
case("ply_binary_huge_face_count.ply", ply_binary(4000000000, [(0, 1, 2)]), "error",
     ":7: the header declares 4000000000 'face' elements of at least 1 bytes each",
     "the 8.7 GB allocation of issue 7: refused from the size")
case("ply_binary_truncated.ply", ply_binary(2, [(0, 1, 2)]) + b"\x03", "error",
     "truncated: face 1's list 'vertex_indices' declares 3 items, more than the rest of the file holds",
     "last face cut")
case("ply_binary_trailing.ply", ply_binary(1, [(0, 1, 2)], trailing=b"\0\0\0\0"), "error",
     ": byte 218: 4 bytes of data after the last element", "trailing bytes")
case("ply_binary_nan.ply", ply_binary(1, [(0, 1, 2)], verts=[(0, 0, 0), (float("nan"), 0, 0), (0, 1, 0)]),
     "error", ": byte 181: vertex 1 has a NaN or infinite coordinate", "NaN coordinate")
case("ply_binary_negative_index.ply", ply_binary(1, [(0, 1, -5)]), "error",
     ": byte 205: face 0 references vertex -5", "negative index")
case("ply_binary_index_equals_count.ply", ply_binary(1, [(0, 1, 3)]), "error",
     ": byte 205: face 0 references vertex 3, but the file has 3 vertices (allowed: 0 to 2)",
     "binary: an index equal to the vertex count")
case("ply_binary_uint_index_max.ply", ply_binary(1, [(0, 4294967295, 2)], index="uint"), "error",
     ": byte 206: face 0 references vertex 4294967295, but the file has 3 vertices (allowed: 0 to 2)",
     "uint index 2^32 - 1 (-1 as int)")
assimp("assimp_cube_binary.ply", "triangles", 12, "binary PLY with normals")


# ---- STL ----
def stl_binary(count, tris, header=b"binary stl"):
    data = header.ljust(80, b"\0")[:80] + struct.pack("<I", count)
    for t in tris:
        data += struct.pack("<12fH", 0, 0, 1, *[c for v in t for c in v], 0)
    return data


T1 = [(0, 0, 0), (1, 0, 0), (0, 1, 0)]
T2 = [(0, 0, 1), (1, 0, 1), (0, 1, 1)]
case("stl_binary.stl", stl_binary(2, [T1, T2]), "triangles", 2, "binary STL, NUL-padded header")
case("stl_binary_solid_header.stl", stl_binary(1, [T1], b"solid exported as binary"), "triangles", 1,
     "binary STL whose header begins with 'solid '")
case("stl_binary_count_low.stl", stl_binary(1, [T1, T2]), "error",
     ": byte 80: binary STL: the header declares 1 triangles, which take 84 + 50 x 1 = 134 bytes, "
     "but the file has 184 (50 bytes more", "count lower than the data")
case("stl_binary_count_high.stl", stl_binary(3, [T1, T2]), "error",
     "but the file has 184 (50 bytes fewer", "count higher than the data")
case("stl_binary_nan.stl", stl_binary(2, [T1, [(0, 0, 1), (float("nan"), 0, 1), (0, 1, 1)]]), "error",
     ": byte 158: triangle 1 has a NaN or infinite coordinate", "NaN vertex (CGAL keeps it)")
case("stl_binary_zero.stl", stl_binary(0, []), "error", "no triangles (the binary STL header's count is 0)",
     "84-byte file, count 0")
case("stl_short.stl", "abc", "error", "too short for a binary STL (3 bytes)", "3 bytes")
case("stl_empty.stl", "", "error", "empty file", "empty file")

FACET = ("facet normal 0 0 1\n outer loop\n  vertex %s\n  vertex 1 0 0\n  vertex 0 1 0\n endloop\nendfacet\n")
ASCII_STL = "solid t\n" + FACET % "0 0 0" + "endsolid t\n"
case("stl_ascii.stl", ASCII_STL, "triangles", 1, "ASCII STL")
case("stl_ascii_crlf.stl", ASCII_STL.replace("\n", "\r\n"), "triangles", 1, "CRLF line endings")
case("stl_ascii_tab_solid.stl",
     "solid\tsphere with a hole, the name is long enough to fill the first eighty bytes of the file\n"
     + FACET % "0 0 0" + FACET % "0 0 2" + "endsolid\n", "triangles", 2,
     "'solid<TAB>name' (assimp's sphereWithHole.stl): CGAL's read_STL would take it for binary")
case("stl_ascii_keyword_name.stl", "solid facet solid\n" + FACET % "0 0 0" + "endsolid facet\n", "triangles", 1,
     "a solid named with keywords, which CGAL's word parser would take for facets")
case("stl_ascii_nan.stl", "solid t\n" + FACET % "0 nan 0" + "endsolid t\n", "error",
     ":4: facet 0 vertex 0 has a NaN or infinite coordinate ('nan'", "NaN coordinate")
case("stl_ascii_truncated.stl", "solid t\n" + FACET % "0 0 0", "error",
     "truncated: the file ends inside a solid (expected 'endsolid')", "no endsolid")
case("stl_ascii_four_vertices.stl", ASCII_STL.replace("  vertex 0 1 0\n", "  vertex 0 1 0\n  vertex 1 1 0\n"),
     "error", ":7: expected 'endloop', found 'vertex'", "a quad facet")
case("stl_ascii_trailing_junk.stl", ASCII_STL + "junk\n", "error", ":10: expected 'solid', found 'junk'",
     "junk after endsolid")
case("stl_ascii_no_facets.stl", "solid t\nendsolid t\n", "error", "no facets in the ASCII STL file",
     "empty solid")
assimp("assimp_triangle_with_two_solids.stl", "triangles", 2, "two solids in one file")

with open("expected.tsv", "w") as manifest:
    manifest.write("# file\toutcome\texpected (error: message substring; triangles: count)\tcase\n")
    for name, data, outcome, expected, note in CASES:
        if data is not None:
            with open(name, "wb") as f:
                f.write(data)
        manifest.write("%s\t%s\t%s\t%s\n" % (name, outcome, expected, note))
