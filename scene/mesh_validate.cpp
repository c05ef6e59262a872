#include "mesh_validate.h"

#include <algorithm>
#include <array>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>

#include "core/error.h"

namespace rtbench {
namespace {

constexpr std::string_view kSpace = " \t\r\v\f";
constexpr double kFloatMax = std::numeric_limits<float>::max();

std::string lowerExtension(const std::string& name) {
    std::string ext = std::filesystem::path(name).extension().string();
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return ext;
}

[[noreturn]] void fail(const std::string& at, const std::string& what) {
    throw Error(printable(at) + ": " + what);
}
std::string atLine(const std::string& name, std::size_t line) {
    return name + ":" + std::to_string(line);
}
std::string atByte(const std::string& name, std::uint64_t byte) {
    return name + ": byte " + std::to_string(byte);
}
// A token from the file, quoted for a message (escaped, at most 40 bytes).
std::string quote(std::string_view token) {
    return "'" + printable(token.substr(0, 40)) + (token.size() > 40 ? "...'" : "'");
}
std::string n(std::uint64_t value) {
    return std::to_string(value);
}

// Text lines with their numbers (from 1); "\r\n" and "\n" both end a line.
struct Line {
    std::string_view text;
    std::size_t number = 0;
    std::size_t end = 0;  // offset just past the line's newline
};
class LineReader {
  public:
    explicit LineReader(std::string_view bytes) : bytes_(bytes) {}
    bool next(Line& line) {
        if (pos_ >= bytes_.size()) return false;
        std::size_t nl = bytes_.find('\n', pos_);
        if (nl == std::string_view::npos) nl = bytes_.size();
        line.text = bytes_.substr(pos_, nl - pos_);
        if (!line.text.empty() && line.text.back() == '\r') line.text.remove_suffix(1);
        line.number = ++number_;
        pos_ = line.end = std::min(nl + 1, bytes_.size());
        return true;
    }

  private:
    std::string_view bytes_;
    std::size_t pos_ = 0, number_ = 0;
};

std::vector<std::string_view> split(std::string_view text) {
    std::vector<std::string_view> tokens;
    std::size_t pos = text.find_first_not_of(kSpace);
    while (pos != std::string_view::npos) {
        const std::size_t end = std::min(text.find_first_of(kSpace, pos), text.size());
        tokens.push_back(text.substr(pos, end - pos));
        pos = text.find_first_not_of(kSpace, end);
    }
    return tokens;
}
std::string_view uncommented(std::string_view text) {
    return text.substr(0, text.find('#'));
}

template <class T>
bool parse(std::string_view token, T& value) {
    if (token.size() > 1 && token[0] == '+' && token[1] != '-') token.remove_prefix(1);
    const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
    return ec == std::errc() && end == token.data() + token.size();
}

// A coordinate must be a finite number that single precision can hold.
void checkCoordinate(double value, std::string_view token, const std::string& at,
                     const std::string& what) {
    if (!std::isfinite(value))
        fail(at, what + " has a NaN or infinite coordinate (" + quote(token) +
                     "; allowed: finite numbers)");
    if (std::abs(value) > kFloatMax)
        fail(at, what + " overflows single precision (" + quote(token) +
                     "; allowed: |x| <= " + "3.4028235e38)");
}

// Refuses `count` elements of at least `minBytes` each when fewer than that many bytes remain,
// before any reader reserves memory for them.
void checkDeclared(std::uint64_t count, std::uint64_t minBytes, std::uint64_t available,
                   const std::string& at, const std::string& what) {
    if (count > available / minBytes)
        fail(at, "the header declares " + n(count) + " " + what + " of at least " + n(minBytes) +
                     " bytes each, more than the " + n(available) +
                     " bytes that follow the header can hold");
}

// Text without its UTF-8 byte-order mark; UTF-16 (marked) is refused.
std::string_view withoutBom(std::string_view bytes, const std::string& name) {
    if (bytes.starts_with("\xEF\xBB\xBF")) bytes.remove_prefix(3);
    if (bytes.starts_with("\xFE\xFF") || bytes.starts_with("\xFF\xFE"))
        fail(name, "UTF-16 text is not supported (allowed: ASCII or UTF-8)");
    return bytes;
}

// The element lines of an OFF file: each line with something before any '#'.
struct OffElements {
    LineReader lines;
    Line line;
    std::vector<std::string_view> tokens;
    bool next() {
        while (lines.next(line))
            if (tokens = split(uncommented(line.text)); !tokens.empty()) return true;
        return false;
    }
};

// The keyword (a variant with 3D vertices) and the counts "vertices faces [edges]".
std::array<std::uint64_t, 2> readOffHeader(OffElements& e, std::uint64_t size, const std::string& name) {
    const std::string notOff = "not an ASCII OFF file (no 'OFF' header with vertex and face counts)";
    if (!e.next()) fail(name, notOff);
    const std::string_view keyword = e.tokens[0];
    if (!keyword.ends_with("OFF")) fail(name, notOff);
    std::string_view prefix = keyword.substr(0, keyword.size() - 3);
    if (prefix.starts_with("ST")) prefix.remove_prefix(2);
    if (prefix.starts_with("C")) prefix.remove_prefix(1);
    if (prefix.starts_with("N")) prefix.remove_prefix(1);
    const bool binary = e.tokens.size() > 1 && e.tokens[1] == "BINARY";
    if (!prefix.empty() || binary)
        fail(atLine(name, e.line.number), "unsupported OFF variant " + quote(keyword) + (binary ? " BINARY" : "") +
                                              " (allowed: ASCII OFF, COFF, NOFF, CNOFF, STOFF with 3D vertices)");
    e.tokens.erase(e.tokens.begin());
    if (e.tokens.empty() && !e.next()) fail(name, notOff);
    std::uint64_t counts[3] = {0, 0, 0};
    for (std::size_t k = 0; k < e.tokens.size(); ++k)
        if (e.tokens.size() > 3 || !parse(e.tokens[k], counts[k]))
            fail(atLine(name, e.line.number),
                 "the OFF header's counts must be 'vertices faces [edges]', non-negative integers; found " + quote(e.line.text));
    if (e.tokens.size() < 2) fail(atLine(name, e.line.number), notOff);
    const std::uint64_t nv = counts[0], nf = counts[1];
    const std::uint64_t available = size - e.line.end;
    const std::string at = atLine(name, e.line.number);
    checkDeclared(nv, 2, available, at, "vertices");
    checkDeclared(nf, 2, available, at, "faces");
    checkDeclared(nv + nf, 2, available, at, "vertices and faces");
    if (nf == 0)
        fail(name, nv ? "no faces, " + n(nv) + " vertices: a point cloud? (rtbench needs faces)"
                      : std::string("no vertices and no faces (an empty mesh)"));
    return {nv, nf};
}

// Face f's line: a vertex count of at least 3, that many indices below nv, at most a color after.
// Returns the count.
std::size_t checkOffFace(const std::vector<std::string_view>& tokens, std::uint64_t f, std::uint64_t nv, const std::string& at) {
    const std::string what = "face " + n(f);
    std::int64_t count = 0;
    if (!parse(tokens[0], count) || count < 0) fail(at, what + ": " + quote(tokens[0]) + " is not a vertex count");
    if (count < 3) fail(at, what + " has " + n(count) + " vertices (at least 3 needed)");
    if (tokens.size() < std::size_t(count) + 1) fail(at, what + " lists fewer than " + n(count) + " vertices");
    for (std::size_t k = 1; k <= std::size_t(count); ++k) {
        std::int64_t index = 0;
        if (!parse(tokens[k], index)) fail(at, what + ": vertex index " + quote(tokens[k]) + " is not an integer");
        if (index < 0 || std::uint64_t(index) >= nv)
            fail(at, what + " references vertex " + std::to_string(index) + ", but the file has " + n(nv) +
                         " vertices (allowed: 0 to " + std::to_string(std::int64_t(nv) - 1) + ")");
    }
    const std::size_t extra = tokens.size() - 1 - std::size_t(count);
    double value = 0.0;
    for (std::size_t k = std::size_t(count) + 1; k < tokens.size(); ++k)
        if (extra > 4 || !parse(tokens[k], value))
            fail(at, what + " has " + n(extra) + " values after its " + n(count) +
                         " vertex indices (allowed: a color of at most 4 numbers)");
    return std::size_t(count);
}

// ---- OFF (Geomview): [ST][C][N]OFF, "nv nf [ne]", nv vertex lines, nf face lines ----------
// One element per line, as assimp reads it; the edge count, which some writers omit, is not
// used. CGAL gets a plain OFF copy: the header with all three counts (its scanner reads three
// numbers), each vertex's x y z and each face's indices. Colors, normals and texture
// coordinates are left out: rtbench does not use them, and CGAL 5.5's scanner casts colors out
// of [0, 255] to unsigned char (undefined behaviour, File_scanner_OFF.h).
ValidatedMesh validateOff(std::string_view file, const std::string& name) {
    const std::string_view bytes = withoutBom(file, name);
    OffElements e{LineReader(bytes)};
    const auto [nv, nf] = readOffHeader(e, bytes.size(), name);
    ValidatedMesh mesh;
    mesh.format = MeshFormat::Off;
    mesh.vertices = nv;
    mesh.faces = nf;
    mesh.normalized = "OFF\n" + n(nv) + " " + n(nf) + " 0\n";
    auto copy = [&](std::size_t count) {
        for (std::size_t k = 0; k < count; ++k) (mesh.normalized += e.tokens[k]) += k + 1 < count ? ' ' : '\n';
    };
    auto truncated = [&](std::uint64_t held) {
        fail(name, "truncated: the header declares " + n(nv) + " vertices and " + n(nf) + " faces, the file holds " + n(held) +
                       " element lines");
    };
    for (std::uint64_t i = 0; i < nv; ++i) {
        if (!e.next()) truncated(i);
        const std::string at = atLine(name, e.line.number), what = "vertex " + n(i);
        if (e.tokens.size() < 3) fail(at, what + " has fewer than 3 coordinates");
        for (std::size_t k = 0; k < e.tokens.size(); ++k) {
            double value = 0.0;
            if (!parse(e.tokens[k], value)) fail(at, what + ": " + quote(e.tokens[k]) + " is not a number");
            if (k < 3) checkCoordinate(value, e.tokens[k], at, what);
        }
        copy(3);
    }
    mesh.faceAt.reserve(nf);
    for (std::uint64_t f = 0; f < nf; ++f) {
        if (!e.next()) truncated(nv + f);
        copy(checkOffFace(e.tokens, f, nv, atLine(name, e.line.number)) + 1);
        mesh.faceAt.push_back(e.line.number);
    }
    if (e.next())
        fail(atLine(name, e.line.number), "data after the last of the " + n(nf) + " faces the header declares: " +
                                              quote(e.line.text) + " (is the face count too low?)");
    return mesh;
}

// A 'v' line: at least 3 numbers, the first 3 coordinates in range. Returns CGAL's copy.
std::string objVertex(const std::vector<std::string_view>& tokens, const std::string& at, ValidatedMesh& mesh) {
    const std::string what = "vertex " + n(mesh.vertices);
    if (tokens.size() < 4) fail(at, what + " has fewer than 3 coordinates");
    for (std::size_t k = 1; k < tokens.size(); ++k) {
        double value = 0.0;
        if (!parse(tokens[k], value)) fail(at, what + ": " + quote(tokens[k]) + " is not a number");
        if (k < 4) checkCoordinate(value, tokens[k], at, what);
    }
    ++mesh.vertices;
    return "v " + std::string(tokens[1]) + " " + std::string(tokens[2]) + " " + std::string(tokens[3]);
}

// An 'f' line: at least 3 corners, each v, v/vt, v/vt/vn or v//vn; v counts from 1, or back from
// the last vertex read when negative. Returns CGAL's copy, with absolute indices.
std::string objFace(const std::vector<std::string_view>& tokens, const std::string& at, std::uint64_t totalVertices,
                    ValidatedMesh& mesh) {
    const std::string what = "face " + n(mesh.faces);
    if (tokens.size() < 4) fail(at, what + " has " + n(tokens.size() - 1) + " vertices (at least 3 needed)");
    std::string copy = "f";
    for (std::size_t k = 1; k < tokens.size(); ++k) {
        const std::string_view corner = tokens[k].substr(0, tokens[k].find('/'));
        std::int64_t index = 0;
        if (!parse(corner, index)) fail(at, what + ": vertex index " + quote(corner) + " is not an integer");
        const std::int64_t absolute = index < 0 ? std::int64_t(mesh.vertices) + index + 1 : index;
        if (index == 0 || absolute < 1 || std::uint64_t(absolute) > totalVertices)
            fail(at, what + ": vertex index " + std::to_string(index) + " is out of range (the file has " + n(totalVertices) +
                         " vertices; allowed: 1 to " + n(totalVertices) + ", or -1 back to -" + n(mesh.vertices) + " at this line)");
        copy += " " + std::to_string(absolute);
    }
    ++mesh.faces;
    return copy;
}

// ---- OBJ (Wavefront): v, f and other statements, one per line ------------------------------
ValidatedMesh validateObj(std::string_view file, const std::string& name) {
    const std::string_view bytes = withoutBom(file, name);
    // Statements of the OBJ specification that CGAL 5.5's read_OBJ accepts and ignores (OBJ.h),
    // besides vt and vn. CGAL gets a copy of only the v and f lines, normalized: three
    // coordinates, absolute 1-based indices, space-separated.
    static const std::vector<std::string_view> kIgnored = {
        "vp",    "bevel",    "lod",    "ctech",      "c_interp",  "usemap", "usemtl",
        "stech", "d_interp", "mtllib", "shadow_obj", "trace_obj", "o",      "g",
        "s",     "cstype",   "deg",    "step",       "bmat",      "con",    "curv",
        "curv2", "surf",     "parm",   "trim",       "hole",      "scrv",   "sp",
        "end",   "surf_1",   "q0_1",   "q1_1",       "curv2d_1",  "surf_2", "q0_2",
        "q1_2",  "curv2d_2", "bsp",    "bzp",        "cdc",       "cdp",    "res"};
    ValidatedMesh mesh;
    mesh.format = MeshFormat::Obj;
    LineReader counter(bytes);
    Line line;
    std::uint64_t totalVertices = 0;
    while (counter.next(line)) {
        const auto tokens = split(line.text);
        if (!tokens.empty() && tokens[0] == "v") ++totalVertices;
    }
    std::uint64_t lineElements = 0, pointElements = 0;
    LineReader lines(bytes);
    while (lines.next(line)) {
        const auto tokens = split(uncommented(line.text));
        const std::string at = atLine(name, line.number);
        std::string copy;  // CGAL's copy of a v or f line
        if (tokens.empty()) {
        } else if (tokens[0] == "v") {
            copy = objVertex(tokens, at, mesh);
        } else if (tokens[0] == "f") {
            copy = objFace(tokens, at, totalVertices, mesh);
            mesh.faceAt.push_back(line.number);
        } else if (tokens[0] == "l" || tokens[0] == "p") {
            ++(tokens[0] == "l" ? lineElements : pointElements);
        } else if (tokens[0] != "vt" && tokens[0] != "vn" &&
                   std::find(kIgnored.begin(), kIgnored.end(), tokens[0]) == kIgnored.end()) {
            fail(at, "unrecognized statement " + quote(tokens[0]) +
                         " (allowed: v, vt, vn, f, l, p, g, o, s, usemtl, mtllib and the other "
                         "statements of the OBJ specification)");
        }
        if (!copy.empty()) (mesh.normalized += copy) += '\n';
    }
    mesh.elementsSkipped = lineElements + pointElements;
    if (lineElements) mesh.skippedWhat = n(lineElements) + " line elements ('l')";
    if (pointElements)
        mesh.skippedWhat +=
            (lineElements ? " and " : "") + n(pointElements) + " point elements ('p')";
    if (mesh.faces == 0)
        fail(name, mesh.vertices
                       ? "no faces, " + n(mesh.vertices) +
                             " vertices: a point cloud? (rtbench needs faces: 'f' lines)" +
                             (mesh.elementsSkipped ? "; skipped " + mesh.skippedWhat : "")
                       : std::string("no vertices and no faces (an empty file?)"));
    return mesh;
}

// ---- PLY (Turk 1994): header, then elements in ascii or binary little/big endian -----------
struct PlyType {
    std::string_view names[2];
    std::uint8_t size;
    bool integer, isSigned;
};
constexpr PlyType kPlyTypes[] = {
    {{"char", "int8"}, 1, true, true},      {{"uchar", "uint8"}, 1, true, false},
    {{"short", "int16"}, 2, true, true},    {{"ushort", "uint16"}, 2, true, false},
    {{"int", "int32"}, 4, true, true},      {{"uint", "uint32"}, 4, true, false},
    {{"float", "float32"}, 4, false, true}, {{"double", "float64"}, 8, false, true}};
constexpr std::string_view kPlyTypeList =
    "char, uchar, short, ushort, int, uint, float, double, int8, uint8, int16, uint16, int32, "
    "uint32, float32, float64";

struct PlyProperty {
    std::string name;
    const PlyType* type = nullptr;
    const PlyType* countType = nullptr;  // list properties only
};
struct PlyElement {
    std::string name;
    std::uint64_t count = 0;
    std::size_t line = 0;
    std::vector<PlyProperty> properties;
};

const PlyType* plyType(std::string_view word, const std::string& at) {
    for (const PlyType& t : kPlyTypes)
        if (word == t.names[0] || word == t.names[1]) return &t;
    fail(at, "unknown PLY type " + quote(word) + " (allowed: " + std::string(kPlyTypeList) + ")");
}

// One value of a binary body, as double (coordinates) and as integer (counts, indices).
struct PlyValue {
    double real = 0.0;
    std::int64_t integer = 0;
};
PlyValue readBinary(const unsigned char* p, const PlyType& type, bool bigEndian) {
    unsigned char raw[8];
    std::memcpy(raw, p, type.size);
    if (bigEndian != (std::endian::native == std::endian::big)) std::reverse(raw, raw + type.size);
    PlyValue v;
    auto get = [&]<class T>(T) {
        T x;
        std::memcpy(&x, raw, sizeof x);
        v.real = double(x);
        if constexpr (std::is_integral_v<T>) v.integer = std::int64_t(x);
    };
    switch (type.size * 4 + type.integer * 2 + type.isSigned) {
        case 1 * 4 + 2 + 1:
            get(std::int8_t());
            break;
        case 1 * 4 + 2:
            get(std::uint8_t());
            break;
        case 2 * 4 + 2 + 1:
            get(std::int16_t());
            break;
        case 2 * 4 + 2:
            get(std::uint16_t());
            break;
        case 4 * 4 + 2 + 1:
            get(std::int32_t());
            break;
        case 4 * 4 + 2:
            get(std::uint32_t());
            break;
        case 4 * 4 + 1:
            get(float());
            break;
        default:
            get(double());
            break;
    }
    return v;
}

// Two properties of one name: the reader takes one of them, validation would check the other
// (two vertex_indices lists: CGAL's polygon from the first, unchecked, list).
void refuseRepeatedProperty(const PlyElement& element, std::string_view property, const std::string& at) {
    for (const PlyProperty& p : element.properties)
        if (p.name == property)
            fail(at, "element " + quote(element.name) + " has a second property " + quote(property) +
                         " (allowed: each property name once)");
}

// The PLY header: its elements and format, up to 'end_header' (the line after it starts the body).
struct PlyHeader {
    std::vector<PlyElement> elements;
    bool binary = false, bigEndian = false;
    std::size_t bodyStart = 0;
};

// One header line into the header (the 'format' line checked by the caller).
void readPlyHeaderLine(const std::vector<std::string_view>& t, const Line& line, const std::string& at, PlyHeader& h) {
    if (t[0] == "format" && t.size() == 3 && t[2] == "1.0" &&
        (t[1] == "ascii" || t[1] == "binary_little_endian" || t[1] == "binary_big_endian")) {
        h.binary = t[1] != "ascii";
        h.bigEndian = t[1] == "binary_big_endian";
    } else if (t[0] == "element" && t.size() == 3) {
        h.elements.push_back({std::string(t[1]), 0, line.number, {}});
        if (!parse(t[2], h.elements.back().count))
            fail(at, "element " + quote(t[1]) + ": count " + quote(t[2]) + " is not a non-negative integer");
    } else if (t[0] == "property" && !h.elements.empty() && t.size() == 3 && t[1] != "list") {
        refuseRepeatedProperty(h.elements.back(), t[2], at);
        h.elements.back().properties.push_back({std::string(t[2]), plyType(t[1], at), nullptr});
    } else if (t[0] == "property" && !h.elements.empty() && t.size() == 5 && t[1] == "list") {
        const PlyType* count = plyType(t[2], at);
        if (!count->integer) fail(at, "list " + quote(t[4]) + " has a non-integer count type");
        refuseRepeatedProperty(h.elements.back(), t[4], at);
        h.elements.back().properties.push_back({std::string(t[4]), plyType(t[3], at), count});
    } else if (t[0] == "format" || t[0] == "element" || t[0] == "property") {
        fail(at, "malformed PLY header line " + quote(line.text) +
                     " (allowed: format ascii|binary_little_endian|binary_big_endian 1.0, "
                     "element NAME COUNT, property TYPE NAME, property list TYPE TYPE NAME, "
                     "after an element line)");
    }  // other lines (e.g. Blender 2.47's comment without 'comment') carry no data: ignored
}

PlyHeader readPlyHeader(LineReader& lines, Line& line, const std::string& name) {
    if (!lines.next(line) || split(line.text) != std::vector<std::string_view>{"ply"})
        fail(name, "not a PLY file (its first line is not 'ply')");
    PlyHeader h;
    bool sawFormat = false, sawEnd = false;
    while (!sawEnd && lines.next(line)) {
        const auto t = split(line.text);
        const std::string at = atLine(name, line.number);
        // CGAL's header parser stops at an empty line and reads nothing.
        if (t.empty()) fail(at, "empty line in the PLY header (allowed: header lines up to 'end_header', no blank one)");
        // CGAL's reader takes the line after 'ply' for the format line, whatever it is.
        if (!sawFormat && t[0] != "format")
            fail(at, "expected the 'format' line right after 'ply', found " + quote(line.text) +
                         " (allowed: format ascii|binary_little_endian|binary_big_endian 1.0)");
        if (sawFormat && t[0] == "format") fail(at, "a second 'format' line (allowed: one, right after 'ply')");
        if (t[0] == "comment" || t[0] == "obj_info") continue;
        if (t[0] == "end_header") {
            sawEnd = true;
            continue;
        }
        readPlyHeaderLine(t, line, at, h);
        sawFormat = sawFormat || t[0] == "format";
    }
    if (!sawEnd) fail(name, "the PLY header has no 'end_header' line");
    if (!sawFormat) fail(name, "the PLY header has no 'format' line");
    h.bodyStart = line.end;
    return h;
}

// The elements the reader takes: the vertices (x, y, z as float or double) and the faces' index
// list (int or uint items).
struct PlyLayout {
    const PlyElement* vertex = nullptr;
    const PlyElement* face = nullptr;
    const PlyProperty* indices = nullptr;
};

// Declared counts against the body's size (a binary item takes at least its fixed-size
// properties, a list at least its count; an ASCII value at least a digit and a separator), one
// vertex element with float or double x, y, z, and one face element.
PlyLayout plyElements(const PlyHeader& h, std::uint64_t bodyBytes, const std::string& name) {
    PlyLayout layout;
    std::uint64_t available = bodyBytes;
    std::string skipped;
    for (const PlyElement& e : h.elements) {
        std::uint64_t minBytes = 0;
        for (const PlyProperty& p : e.properties) minBytes += h.binary ? (p.countType ? p.countType->size : p.type->size) : 2;
        if (minBytes == 0) fail(atLine(name, e.line), "element " + quote(e.name) + " has no properties");
        checkDeclared(e.count, minBytes, available, atLine(name, e.line), "'" + printable(e.name) + "' elements");
        available -= e.count * minBytes;
        // CGAL's reader takes the items of every element of these names; validation checks one.
        const bool isVertex = e.name == "vertex" || e.name == "vertices", isFace = e.name == "face" || e.name == "faces";
        const PlyElement* first = isVertex ? layout.vertex : layout.face;
        if ((isVertex || isFace) && first)
            fail(atLine(name, e.line), "a second " + std::string(isVertex ? "vertex" : "face") + " element " + quote(e.name) +
                                           " (the first, " + quote(first->name) + ", is at line " + n(first->line) +
                                           "; allowed: one of each)");
        if (isVertex)
            layout.vertex = &e;
        else if (isFace)
            layout.face = &e;
        else if (e.count)
            skipped += (skipped.empty() ? "" : ", ") + n(e.count) + " '" + printable(e.name) + "'";
    }
    if (!layout.vertex) fail(name, "no 'vertex' element in the PLY header");
    for (const char* axis : {"x", "y", "z"}) {
        const std::vector<PlyProperty>& properties = layout.vertex->properties;
        auto p = std::find_if(properties.begin(), properties.end(), [&](const PlyProperty& q) { return q.name == axis; });
        if (p == properties.end() || p->countType || p->type->integer)
            fail(atLine(name, layout.vertex->line),
                 std::string("vertex property '") + axis + "' must be a float or double scalar (the reader takes no other)");
    }
    if (!layout.face || layout.face->count == 0)
        fail(name, "no faces, " + n(layout.vertex->count) + " vertices: a point cloud? (rtbench needs a " + "'face' element" +
                       (skipped.empty() ? ")" : "; the file has " + skipped + ")"));
    return layout;
}

// The face index list the reader takes.
void plyIndices(PlyLayout& layout, const std::string& name) {
    for (const PlyProperty& p : layout.face->properties)
        if ((p.name == "vertex_indices" || p.name == "vertex_index") && p.countType) {
            if (layout.indices)
                fail(atLine(name, layout.face->line),
                     "the face element has two index lists, 'vertex_indices' and 'vertex_index' (allowed: one)");
            layout.indices = &p;
        }
    const PlyProperty* indices = layout.indices;
    if (!indices || !indices->type->integer || indices->type->size != 4)
        fail(atLine(name, layout.face->line),
             "the face element needs a list property 'vertex_indices' or 'vertex_index' of int or "
             "uint items (the reader takes no other)" +
                 (indices ? ", found items of type " + std::string(indices->type->names[0]) : std::string()));
}

// Reads the values of a PLY body one by one, each checked as the reader will take it: a binary
// body from its bytes, an ASCII one from the tokens of the item's line.
struct PlyCursor {
    std::string_view bytes, body;
    bool binary = false, bigEndian = false;
    std::size_t pos = 0;  // binary: offset in body
    std::vector<std::string_view> tokens;
    std::size_t token = 0;
    std::string at, what;  // the item's place and name, for errors

    // The next value of type t, checked for presence, number and (integer) type.
    PlyValue next(const PlyType& t, bool coordinate) {
        PlyValue v;
        if (binary) {
            if (body.size() - pos < t.size) fail(at, "truncated: " + what + " ends at byte " + n(bytes.size()) + ", inside its values");
            v = readBinary(reinterpret_cast<const unsigned char*>(body.data()) + pos, t, bigEndian);
            pos += t.size;
            if (coordinate) checkCoordinate(v.real, std::to_string(v.real), at, what);
            return v;
        }
        if (token >= tokens.size()) fail(at, what + " has fewer values than its properties declare");
        // Each value must fit its type: CGAL's stream extraction fails otherwise.
        const std::string_view word = tokens[token++];
        if (coordinate) {
            if (!parse(word, v.real)) fail(at, what + ": " + quote(word) + " is not a number");
            checkCoordinate(v.real, word, at, what);
            return v;
        }
        const int bits = 8 * t.size - (t.isSigned ? 1 : 0);
        const bool fits = t.integer ? parse(word, v.integer) && v.integer < (std::int64_t(1) << bits) &&
                                          v.integer >= (t.isSigned ? -(std::int64_t(1) << bits) : 0)
                                    : parse(word, v.real) && std::isfinite(v.real) && (t.size == 8 || std::abs(v.real) <= kFloatMax);
        if (!fits)
            fail(at, what + ": " + quote(word) + " is not " + (t.integer ? "an integer" : "a finite number") + " of type " +
                         std::string(t.names[0]));
        if (t.integer) v.real = double(v.integer);
        return v;
    }
};

// One item's properties: coordinates checked, list lengths against the file, face indices
// against the vertex count.
void readPlyItem(PlyCursor& cursor, const PlyElement& e, std::uint64_t item, const PlyLayout& layout) {
    const bool isVertex = &e == layout.vertex;
    for (const PlyProperty& p : e.properties) {
        if (!p.countType) {
            cursor.next(*p.type, isVertex && (p.name == "x" || p.name == "y" || p.name == "z"));
            continue;
        }
        const std::int64_t count = cursor.next(*p.countType, false).integer;
        const std::string& at = cursor.at;
        if (count < 0) fail(at, cursor.what + ": list '" + printable(p.name) + "' has a negative length " + std::to_string(count));
        if (cursor.binary && std::uint64_t(count) > (cursor.body.size() - cursor.pos) / p.type->size)
            fail(at, "truncated: " + cursor.what + "'s list '" + printable(p.name) + "' declares " + std::to_string(count) +
                         " items, more than the rest of the file holds");
        if (&p == layout.indices && count < 3)
            fail(at, "face " + n(item) + " has " + std::to_string(count) + " vertices (at least 3 needed)");
        for (std::int64_t k = 0; k < count; ++k) {
            const std::int64_t index = cursor.next(*p.type, false).integer;
            const std::uint64_t vertices = layout.vertex->count;
            if (&p == layout.indices && (index < 0 || std::uint64_t(index) >= vertices))
                fail(at, "face " + n(item) + " references vertex " + std::to_string(index) + ", but the file has " + n(vertices) +
                             " vertices (allowed: 0 to " + std::to_string(std::int64_t(vertices) - 1) + ")");
        }
    }
}

// Every value of every element, and nothing after the last.
void readPlyBody(const PlyHeader& h, const PlyLayout& layout, std::string_view bytes, LineReader& lines, Line& line,
                 const std::string& name, ValidatedMesh& mesh) {
    PlyCursor cursor{bytes, bytes.substr(h.bodyStart), h.binary, h.bigEndian};
    for (const PlyElement& e : h.elements)
        for (std::uint64_t item = 0; item < e.count; ++item) {
            cursor.what = printable(e.name) + " " + n(item);
            const std::size_t itemStart = cursor.pos;
            if (h.binary) {
                cursor.at = atByte(name, h.bodyStart + cursor.pos);
            } else {
                do {
                    if (!lines.next(line))
                        fail(name, "truncated: element '" + printable(e.name) + "' declares " + n(e.count) +
                                       " items, the file ends before item " + n(item));
                    cursor.tokens = split(line.text);
                } while (cursor.tokens.empty());
                cursor.at = atLine(name, line.number);
                cursor.token = 0;
            }
            readPlyItem(cursor, e, item, layout);
            if (!h.binary && cursor.token != cursor.tokens.size())
                fail(cursor.at, cursor.what + " has " + n(cursor.tokens.size()) + " values, its properties declare " + n(cursor.token));
            if (&e == layout.face) mesh.faceAt.push_back(h.binary ? h.bodyStart + itemStart : line.number);
        }
    if (h.binary && cursor.pos != cursor.body.size())
        fail(atByte(name, h.bodyStart + cursor.pos), n(cursor.body.size() - cursor.pos) + " bytes of data after the last element the header declares");
    if (!h.binary)
        while (lines.next(line))
            if (!split(line.text).empty())
                fail(atLine(name, line.number), "data after the last element the header declares: " + quote(line.text));
}

ValidatedMesh validatePly(std::string_view bytes, const std::string& name) {
    LineReader lines(bytes);
    Line line;
    const PlyHeader header = readPlyHeader(lines, line, name);
    PlyLayout layout = plyElements(header, bytes.size() - header.bodyStart, name);
    plyIndices(layout, name);
    ValidatedMesh mesh;
    mesh.format = header.binary ? MeshFormat::PlyBinary : MeshFormat::PlyAscii;
    mesh.vertices = layout.vertex->count;
    mesh.faces = layout.face->count;
    mesh.faceAt.reserve(layout.face->count);
    readPlyBody(header, layout, bytes, lines, line, name, mesh);
    return mesh;
}

// ---- STL: ASCII ("solid", facets, "endsolid") or binary (80-byte header, uint32 count, 50
// bytes per triangle). Binary iff the size is exactly 84 + 50 * count: text can match only by
// accident (bytes 80-83 of an ASCII file would have to encode that count). -------------------
// A binary STL of `count` triangles (the size matched): every coordinate finite.
ValidatedMesh validateBinaryStl(std::string_view bytes, std::uint32_t count, const std::string& name) {
    ValidatedMesh mesh;
    mesh.format = MeshFormat::StlBinary;
    if (count == 0) fail(name, "no triangles (the binary STL header's count is 0)");
    mesh.faces = count;
    mesh.faceAt.reserve(count);
    for (std::uint64_t i = 0; i < count; ++i) {
        const std::uint64_t record = 84 + 50 * i;
        for (int k = 0; k < 9; ++k) {  // after the 12-byte normal, 3 vertices of 3 floats
            float value;
            std::memcpy(&value, bytes.data() + record + 12 + 4 * k, 4);
            if (!std::isfinite(value))
                fail(atByte(name, record + 12 + 4 * k), "triangle " + n(i) + " has a NaN or infinite coordinate (allowed: finite numbers)");
        }
        mesh.faceAt.push_back(record);
    }
    return mesh;
}

// The words of an ASCII STL, line by line.
struct StlWords {
    LineReader lines;
    const std::string& name;
    Line line;
    std::vector<std::string_view> tokens;
    std::size_t token = 0;

    bool atEnd() {  // no word left in the file
        while (token >= tokens.size()) {
            if (!lines.next(line)) return true;
            tokens = split(line.text);
            token = 0;
        }
        return false;
    }
    std::string_view next() {
        if (atEnd()) fail(name, "truncated: the file ends inside a solid (expected 'endsolid')");
        return tokens[token++];
    }
    void expect(std::string_view word) {
        if (const std::string_view got = next(); got != word)
            fail(atLine(name, line.number), "expected '" + std::string(word) + "', found " + quote(got));
    }
    std::string_view number(const std::string& what, bool coordinate) {
        const std::string_view word = next();
        double value = 0.0;
        if (!parse(word, value)) fail(atLine(name, line.number), what + ": " + quote(word) + " is not a number");
        if (coordinate) checkCoordinate(value, word, atLine(name, line.number), what);
        return word;
    }
    void skipLine() { token = tokens.size(); }
};

// One facet (after its 'facet'), written to the normalized text CGAL reads.
void readStlFacet(StlWords& words, ValidatedMesh& mesh) {
    const std::string what = "facet " + n(mesh.faces);
    mesh.faceAt.push_back(words.line.number);
    words.expect("normal");
    for (int k = 0; k < 3; ++k) words.number(what + "'s normal", false);
    words.expect("outer");
    words.expect("loop");
    mesh.normalized += "facet normal 0 0 0\nouter loop\n";
    for (int v = 0; v < 3; ++v) {
        words.expect("vertex");
        mesh.normalized += "vertex";
        for (int k = 0; k < 3; ++k) (mesh.normalized += ' ') += words.number(what + " vertex " + std::to_string(v), true);
        mesh.normalized += '\n';
    }
    words.expect("endloop");
    words.expect("endfacet");
    mesh.normalized += "endloop\nendfacet\n";
    ++mesh.faces;
}

// ASCII: solid NAME { facet normal n n n outer loop (vertex x y z)x3 endloop endfacet }
// endsolid [NAME], possibly several solids. CGAL gets one solid of the facets' vertices:
// its parser reads words, and would take a name's words ("solid", "facet") for keywords.
ValidatedMesh validateAsciiStl(std::string_view bytes, const std::string& name) {
    ValidatedMesh mesh;
    mesh.format = MeshFormat::StlAscii;
    mesh.normalized = "solid\n";
    StlWords words{LineReader(bytes), name};
    while (!words.atEnd()) {
        words.expect("solid");
        words.skipLine();  // the rest of the line is the solid's name
        for (std::string_view word = words.next(); word != "endsolid"; word = words.next()) {
            if (word != "facet") fail(atLine(name, words.line.number), "expected 'facet' or 'endsolid', found " + quote(word));
            readStlFacet(words, mesh);
        }
        words.skipLine();  // the rest of the line repeats the name
    }
    if (mesh.faces == 0) fail(name, "no facets in the ASCII STL file");
    mesh.normalized += "endsolid\n";
    return mesh;
}

ValidatedMesh validateStl(std::string_view bytes, const std::string& name) {
    const std::string allowed =
        "allowed: ASCII STL beginning with 'solid', or binary STL: an 80-byte header, a "
        "little-endian uint32 triangle count, 50 bytes per triangle";
    if (bytes.empty()) fail(name, "empty file (" + allowed + ")");
    std::uint32_t count = 0;
    if (bytes.size() >= 84) std::memcpy(&count, bytes.data() + 80, 4);  // little-endian hosts
    static_assert(std::endian::native == std::endian::little);
    const std::uint64_t binarySize = 84 + 50 * std::uint64_t(count);
    const std::string_view text = bytes.substr(std::min(bytes.find_first_not_of(std::string(kSpace) + "\n"), bytes.size()));
    const bool looksAscii = text.starts_with("solid") &&
                            (text.size() == 5 || kSpace.find(text[5]) != std::string_view::npos || text[5] == '\n') &&
                            bytes.find('\0') == std::string_view::npos;
    if (bytes.size() >= 84 && bytes.size() == binarySize) return validateBinaryStl(bytes, count, name);
    if (looksAscii) return validateAsciiStl(bytes, name);
    if (bytes.size() < 84)
        fail(name, "too short for a binary STL (" + n(bytes.size()) + " bytes) and does not begin with 'solid' (" + allowed + ")");
    const std::int64_t difference = std::int64_t(bytes.size()) - std::int64_t(binarySize);
    fail(atByte(name, 80), "binary STL: the header declares " + n(count) + " triangles, which take 84 + 50 x " + n(count) +
                               " = " + n(binarySize) + " bytes, but the file has " + n(bytes.size()) + " (" +
                               n(std::uint64_t(std::abs(difference))) + (difference > 0 ? " bytes more" : " bytes fewer") +
                               "; the size must match exactly)");
}

}  // namespace

std::string ValidatedMesh::faceLocation(const std::string& name, std::size_t f) const {
    const bool binary = format == MeshFormat::PlyBinary || format == MeshFormat::StlBinary;
    return binary ? atByte(name, faceAt[f]) : atLine(name, faceAt[f]);
}

ValidatedMesh validateMesh(std::string_view bytes, const std::string& name) {
    const std::string ext = lowerExtension(name);
    if (ext == ".off") return validateOff(bytes, name);
    if (ext == ".obj") return validateObj(bytes, name);
    if (ext == ".ply") return validatePly(bytes, name);
    if (ext == ".stl") return validateStl(bytes, name);
    throw Error(printable(name) + ": unknown mesh extension '" + printable(ext) +
                "' (allowed: .off, .obj, .ply, .stl)");
}

}  // namespace rtbench
