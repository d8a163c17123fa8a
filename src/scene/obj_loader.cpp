// Wavefront OBJ loader of our own, with the diffuse colour (Kd) of its .mtl materials.
//
// Format: "Object Files (.obj)" and "Material Library File (.mtl)", appendices B1 and B2 of the Wavefront
// Advanced Visualizer manual (mirrored at paulbourke.net/dataformats/obj and /mtl). Polygons only: free-form
// curves and surfaces, texture coordinates, smoothing groups, lines and points are read past.
//
// Our own rather than tinyobjloader, which read bad input as something else: 'nan', 'abc' or a missing
// coordinate as 0, face indices through atoi (4294967297 wrapped to 1, 1.7 read as 1), "Kd 0.5" as red, and
// polygons of more than 255 vertices not at all. Here every token must parse in full, and a line we cannot
// read is an error that names it. What tinyobjloader decided about grouping is kept, so scenes load as
// before: a new shape at each 'o' or 'g' line, one Mesh per (shape, material) in order of first use.
#include "obscura/error.h"
#include "obscura/scene_io.h"
#include "scene/loader_common.h"

#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <string_view>
#include <unordered_map>
#include <unordered_set>
#include <utility>
#include <vector>

namespace obscura {

namespace {

namespace fs = std::filesystem;

// "No normal" in a Corner; also caps the vertex and normal counts, so every index fits a Mesh's 32 bits.
constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();

// A token as messages quote it, cut short: a corrupt file's megabyte "token" would bury the message.
std::string quoted(std::string_view token) {
    constexpr std::size_t kLongest = 40;
    // Appended piece by piece: GCC 12 warns of a false overlap (-Wrestrict) in "'" + std::string(...).
    std::string out(1, '\'');
    out.append(token.substr(0, kLongest));
    out.append(token.size() > kLongest ? "...'" : "'");
    return out;
}

// "1 vertex", "3 vertices": for the counts in range messages.
std::string counted(std::uint64_t n, const char* one, const char* many) {
    return std::to_string(n) + " " + (n == 1 ? one : many);
}

enum class Number { Ok, NotANumber, TooLarge };

// The whole token as a double. A leading '+' is fine (from_chars rejects it; writers do emit it); a value
// too small for double is 0, as the nearest double to it is, and one too large is reported.
Number parseNumber(std::string_view token, double& v) {
    std::string_view s = token;
    if (s.size() > 1 && s[0] == '+' && s[1] != '+' && s[1] != '-') s.remove_prefix(1);
    auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
    if (end != s.data() + s.size()) return Number::NotANumber;
    if (ec == std::errc::result_out_of_range) {
        // from_chars says the same for a value too large and one too small for double; strtod, given the decimal
        // from_chars accepted, returns +-HUGE_VAL for the first and (nearly) 0 for the second.
        v = std::strtod(std::string(s).c_str(), nullptr);
        if (std::isinf(v)) return Number::TooLarge;
        v = s.front() == '-' ? -0.0 : 0.0;
        return Number::Ok;
    }
    return ec == std::errc{} ? Number::Ok : Number::NotANumber;
}

// The logical lines of an OBJ or MTL text, as tokens. Lines end in LF, CRLF or a lone CR (as tinyobjloader
// read them). A backslash as the last character continues the line on the next one, as the spec allows,
// but not on a comment line: tinyobjloader never joined lines, and a comment ending in a Windows path's
// backslash must not swallow the vertex below it. A token that starts with '#' begins a comment.
class LineReader {
public:
    explicit LineReader(std::string_view text) : text_(text) {}

    // False at the end of the text.
    bool next(std::vector<std::string_view>& tokens) {
        if (pos_ >= text_.size()) return false;
        line_ = next_;
        std::string_view line = physical();
        if (continues(line)) {
            joined_.assign(line.substr(0, line.size() - 1));
            for (bool more = true; more && pos_ < text_.size();) {
                const std::string_view part = physical();
                more = continues(part);
                joined_ += ' ';
                joined_ += part.substr(0, part.size() - (more ? 1 : 0));
            }
            line = joined_;
        }
        tokens.clear();
        for (std::size_t i = 0; i < line.size();) {
            while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
            if (i == line.size() || line[i] == '#') break;
            std::size_t j = i;
            while (j < line.size() && line[j] != ' ' && line[j] != '\t') ++j;
            tokens.push_back(line.substr(i, j - i));
            i = j;
        }
        return true;
    }

    // The number of the (first physical) line last returned, from 1.
    std::uint64_t line() const { return line_; }

private:
    // Ends in a backslash outside a comment.
    static bool continues(std::string_view line) {
        if (line.empty() || line.back() != '\\') return false;
        for (std::size_t i = line.find('#'); i != std::string_view::npos; i = line.find('#', i + 1))
            if (i == 0 || line[i - 1] == ' ' || line[i - 1] == '\t') return false;
        return true;
    }

    std::string_view physical() {
        const std::size_t eol = std::min(text_.find_first_of("\r\n", pos_), text_.size());
        const std::string_view line = text_.substr(pos_, eol - pos_);
        pos_ = eol + 1;
        if (eol + 1 < text_.size() && text_[eol] == '\r' && text_[eol + 1] == '\n') ++pos_;
        ++next_;
        return line;
    }

    std::string_view text_;
    std::size_t pos_ = 0;
    std::uint64_t line_ = 0, next_ = 1;
    std::string joined_;
};

// The text from tokens[from] to the end of the last token, inner spacing kept: names may hold spaces.
std::string_view rest(const std::vector<std::string_view>& tokens, std::size_t from) {
    if (from >= tokens.size()) return {};
    const char* begin = tokens[from].data();
    return {begin, std::size_t(tokens.back().data() + tokens.back().size() - begin)};
}

// Messages about the current line of one file: "<path>: line <n>: <problem>".
class LineErrors {
public:
    LineErrors(const std::string& path, const LineReader& lines) : path_(path), lines_(lines) {}

    [[noreturn]] void operator()(const std::string& problem) const {
        fail(path_, "line " + std::to_string(lines_.line()) + ": " + problem);
    }

    // A value we keep as a float: a number, finite, within float's range.
    float real(std::string_view token, const char* what) const {
        double v = 0;
        const Number n = parseNumber(token, v);
        if (n == Number::NotANumber) (*this)("expected a number, got " + quoted(token));
        if (n == Number::TooLarge || (std::isfinite(v) && std::abs(v) > double(std::numeric_limits<float>::max())))
            (*this)(std::string(what) + " " + quoted(token) + " is beyond float range");
        if (!std::isfinite(v)) (*this)(std::string(what) + " " + quoted(token) + " is not a finite number");
        return float(v);
    }

    // A value we read past (a texture coordinate, a w, a vertex colour): it need only be a number.
    void number(std::string_view token) const {
        double v = 0;
        if (parseNumber(token, v) == Number::NotANumber) (*this)("expected a number, got " + quoted(token));
    }

private:
    const std::string& path_;
    const LineReader& lines_;
};

// ---- MTL ------------------------------------------------------------------------------------------------

struct Material {
    std::string name;
    Vec3 diffuse = Mesh{}.baseColor;  // without a Kd line: the colour a mesh without a material gets
};

struct Materials {
    std::vector<Material> list;
    std::unordered_map<std::string, int> byName;
};

// Reads newmtl and Kd; every other statement is read past. A material defined twice keeps its first
// definition, as with tinyobjloader. A missing file is no error (the meshes get the default colour):
// models are often passed around without their .mtl.
void readMtl(const std::string& path, Materials& out) {
    std::error_code ec;
    if (!fs::is_regular_file(path, ec)) return;
    const std::string text = loader::readWholeFile(path);
    LineReader lines(text);
    const LineErrors bad(path, lines);
    std::vector<std::string_view> t;
    int current = -1;  // the material Kd lines set; -1 before any newmtl and in a repeated definition
    while (lines.next(t)) {
        if (t.empty()) continue;
        if (t[0] == "newmtl") {
            const std::string name(rest(t, 1));
            if (name.empty()) bad("'newmtl' without a name");
            current = -1;
            if (out.byName.count(name)) continue;
            current = int(out.list.size());
            out.byName.emplace(name, current);
            out.list.push_back({name});
        } else if (t[0] == "Kd") {
            // The spec's other forms name a spectral curve or CIE XYZ values; neither is an albedo we can use.
            if (t.size() > 1 && (t[1] == "spectral" || t[1] == "xyz"))
                bad("'Kd " + std::string(t[1]) + "' is not supported (expected 'Kd r g b')");
            if (t.size() != 2 && t.size() != 4)
                bad("expected 1 or 3 values after 'Kd', got " + std::to_string(t.size() - 1));
            const float r = bad.real(t[1], "Kd value");
            // One value is grey: "g and b are optional; if only r is specified, g and b are assumed equal to r".
            const Vec3 kd = t.size() == 2 ? Vec3{r, r, r} : Vec3{r, bad.real(t[2], "Kd value"), bad.real(t[3], "Kd value")};
            if (current >= 0) out.list[std::size_t(current)].diffuse = kd;
        }
    }
}

// An mtllib line's file names: space-separated, a backslash escaping the next character (as tinyobjloader
// read them, so "my\ file.mtl" is one name).
std::vector<std::string> mtlNames(std::string_view line) {
    std::vector<std::string> names(1);
    for (std::size_t i = 0; i < line.size(); ++i) {
        if (line[i] == '\\' && i + 1 < line.size()) names.back() += line[++i];
        else if (line[i] == ' ' || line[i] == '\t') {
            if (!names.back().empty()) names.emplace_back();
        } else names.back() += line[i];
    }
    if (names.back().empty()) names.pop_back();
    return names;
}

// ---- OBJ ------------------------------------------------------------------------------------------------

struct Corner {
    std::uint32_t v = 0;      // position, from 0
    std::uint32_t n = kNone;  // normal, from 0, or none
};

struct Face {
    std::size_t firstCorner = 0;
    std::size_t count = 0;  // 3 or more
    int material = -1;      // index into Obj::useNames, -1 for none
};

// tinyobjloader's shape: the faces after an 'o' or 'g' line.
struct Shape {
    std::string name;
    std::size_t index = 0;  // tinyobjloader's number for it, which names it when it has no name
    std::size_t firstFace = 0, endFace = 0;
};

// The largest positive index of one kind, with its line: checked once the whole file is read, because
// tinyobjloader accepted faces that name vertices defined further down.
struct Highest {
    std::int64_t index = 0;
    std::uint64_t line = 0;
};

struct Obj {
    std::vector<Vec3> positions, normals;  // normals unit length (or zero where the file's are)
    std::uint64_t texcoords = 0;
    std::vector<Corner> corners;
    std::vector<Face> faces;
    std::vector<Shape> shapes;  // only those with faces
    std::vector<std::string> useNames, mtllibs;
    std::size_t shortFaces = 0;  // faces of 1 or 2 corners: dropped and counted as degenerate
};

enum class Kind { Vertex, TexCoord, Normal };

class ObjParser {
public:
    ObjParser(const std::string& path, const std::string& text) : path_(path), lines_(text), bad_(path, lines_) {}

    Obj parse() {
        std::vector<std::string_view> t;
        std::unordered_map<std::string, int> useIndex;
        std::unordered_set<std::string> libs;
        int material = -1;  // carried across 'o' and 'g' lines, as tinyobjloader carried it
        while (lines_.next(t)) {
            if (t.empty()) continue;
            const std::string_view key = t[0];
            if (key == "v") vertex(t);
            else if (key == "vn") normal(t);
            else if (key == "vt") texcoord(t);
            else if (key == "f") face(t, material);
            else if (key == "l" || key == "p") {
                // Not drawn, but their indices are held to the same rules as a face's.
                Corner c;
                for (std::size_t i = 1; i < t.size(); ++i) reference(t[i], c);
                hasLinesOrPoints_ = hasLinesOrPoints_ || t.size() > 1;
            } else if (key == "o") {
                startShape(std::string(rest(t, 1)), true);
            } else if (key == "g") {
                // Several group names join with a space: tinyobjloader keeps one name per shape.
                std::string name;
                for (std::size_t i = 1; i < t.size(); ++i) {
                    if (i > 1) name += ' ';
                    name.append(t[i]);
                }
                startShape(std::move(name), false);
            } else if (key == "usemtl") {
                const std::string name(rest(t, 1));
                if (name.empty()) {
                    material = -1;
                    continue;
                }
                auto [it, added] = useIndex.try_emplace(name, int(obj_.useNames.size()));
                if (added) obj_.useNames.push_back(name);
                material = it->second;
            } else if (key == "mtllib") {
                for (std::string& name : mtlNames(rest(t, 1)))
                    if (libs.insert(name).second) obj_.mtllibs.push_back(std::move(name));
            }
            // Anything else ('s', 'vp', free-form geometry, unknown statements): read past.
        }
        endShape();
        checkHighest(Kind::Vertex, obj_.positions.size());
        checkHighest(Kind::TexCoord, obj_.texcoords);
        checkHighest(Kind::Normal, obj_.normals.size());
        return std::move(obj_);
    }

private:
    void vertex(const std::vector<std::string_view>& t) {
        // x y z, x y z w (a weight for rational curves), or x y z r g b (a common vertex-colour extension).
        if (t.size() != 4 && t.size() != 5 && t.size() != 7)
            bad_("expected 3, 4 or 6 values after 'v' (x y z [w] or x y z r g b), got " + std::to_string(t.size() - 1));
        if (obj_.positions.size() >= kNone) bad_("more than " + std::to_string(kNone) + " vertices");
        const Vec3 p{bad_.real(t[1], "vertex coordinate"), bad_.real(t[2], "vertex coordinate"),
                     bad_.real(t[3], "vertex coordinate")};
        for (std::size_t i = 4; i < t.size(); ++i) bad_.number(t[i]);
        obj_.positions.push_back(p);
    }

    void normal(const std::vector<std::string_view>& t) {
        if (t.size() != 4) bad_("expected 3 values after 'vn', got " + std::to_string(t.size() - 1));
        if (obj_.normals.size() >= kNone) bad_("more than " + std::to_string(kNone) + " normals");
        const double x = bad_.real(t[1], "normal component"), y = bad_.real(t[2], "normal component"),
                     z = bad_.real(t[3], "normal component");
        // In double: float squares of components beyond 1e19 overflow, and a valid normal would become zero.
        // A zero normal stays zero here; sanitizeScene refuses it on a triangle it keeps.
        const double length = std::sqrt(x * x + y * y + z * z);
        obj_.normals.push_back(length > 0 ? Vec3{float(x / length), float(y / length), float(z / length)} : Vec3{});
    }

    void texcoord(const std::vector<std::string_view>& t) {
        if (t.size() < 2 || t.size() > 4) bad_("expected 1 to 3 values after 'vt', got " + std::to_string(t.size() - 1));
        for (std::size_t i = 1; i < t.size(); ++i) bad_.number(t[i]);
        ++obj_.texcoords;
    }

    void face(const std::vector<std::string_view>& t, int material) {
        const std::size_t count = t.size() - 1;
        if (count < 3) {
            // No area (a point or an edge): dropped, as tinyobjloader dropped them, but counted with the
            // degenerate triangles rather than silently.
            for (std::size_t i = 1; i < t.size(); ++i) reference(t[i], scratch_);
            ++obj_.shortFaces;
            return;
        }
        Face f{obj_.corners.size(), count, material};
        for (std::size_t i = 1; i < t.size(); ++i) {
            Corner c;
            reference(t[i], c);
            obj_.corners.push_back(c);
        }
        obj_.faces.push_back(f);
    }

    // One corner: v, v/vt, v//vn or v/vt/vn.
    void reference(std::string_view token, Corner& c) {
        auto malformed = [&] { bad_("bad vertex reference " + quoted(token) + " (expected v, v/vt, v//vn or v/vt/vn)"); };
        std::string_view parts[3];
        std::size_t n = 0;
        for (std::size_t start = 0;;) {
            const std::size_t slash = token.find('/', start);
            if (n == 3) malformed();
            parts[n++] = token.substr(start, slash - start);  // to the end for npos
            if (slash == std::string_view::npos) break;
            start = slash + 1;
        }
        // The texture coordinate may only be left out between two slashes (v//vn).
        if (parts[0].empty() || (n == 2 && parts[1].empty()) || (n == 3 && parts[2].empty())) malformed();
        c.v = resolve(parts[0], token, Kind::Vertex);
        if (n >= 2 && !parts[1].empty()) resolve(parts[1], token, Kind::TexCoord);
        c.n = n == 3 ? resolve(parts[2], token, Kind::Normal) : kNone;
    }

    // An index as written, 1-based or negative (relative: -1 is the last one defined so far), made 0-based.
    std::uint32_t resolve(std::string_view part, std::string_view token, Kind kind) {
        static constexpr const char* kOne[] = {"vertex", "texture coordinate", "normal"};
        static constexpr const char* kMany[] = {"vertices", "texture coordinates", "normals"};
        const std::size_t k = std::size_t(kind);
        const std::uint64_t count = kind == Kind::Vertex   ? obj_.positions.size()
                                    : kind == Kind::Normal ? obj_.normals.size()
                                                           : obj_.texcoords;
        auto outOfRange = [&] {
            bad_(std::string(kOne[k]) + " " + std::string(part) + " out of range (" + counted(count, kOne[k], kMany[k]) + ")");
        };
        std::string_view digits = part;
        if (digits.size() > 1 && digits[0] == '+' && digits[1] != '+' && digits[1] != '-') digits.remove_prefix(1);
        std::int64_t i = 0;
        auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), i);
        if (end != digits.data() + digits.size() || (ec != std::errc{} && ec != std::errc::result_out_of_range))
            bad_("bad vertex reference " + quoted(token) + " (indices are integers)");
        if (ec == std::errc::result_out_of_range) outOfRange();
        if (i == 0) bad_(std::string(kOne[k]) + " index 0 in " + quoted(token) + " (indices start at 1; -1 is the last one)");
        if (i < 0) {
            if (i < -std::int64_t(count)) outOfRange();
            return std::uint32_t(std::int64_t(count) + i);
        }
        // Beyond the count so far is a forward reference, checked at the end. One beyond any count we take
        // fails there, so what is stored for it does not matter.
        if (i > highest_[k].index) highest_[k] = {i, lines_.line()};
        return i <= std::int64_t(kNone) ? std::uint32_t(i - 1) : 0;
    }

    void checkHighest(Kind kind, std::uint64_t count) const {
        static constexpr const char* kOne[] = {"vertex", "texture coordinate", "normal"};
        static constexpr const char* kMany[] = {"vertices", "texture coordinates", "normals"};
        const Highest& h = highest_[std::size_t(kind)];
        const std::size_t k = std::size_t(kind);
        if (std::uint64_t(h.index) > count)
            fail(path_, "line " + std::to_string(h.line) + ": " + kOne[k] + " " + std::to_string(h.index) +
                            " out of range (" + counted(count, kOne[k], kMany[k]) + ")");
    }

    // tinyobjloader's shape list, whose positions name unnamed shapes ("object2"): an 'o' line ends the
    // current shape and lists it if it has faces, lines or points; a 'g' line only if it has faces.
    void startShape(std::string name, bool isObject) {
        const bool listed = obj_.faces.size() > current_.firstFace || (isObject && hasLinesOrPoints_);
        endShape();
        if (listed) ++listedShapes_;
        current_ = Shape{std::move(name), listedShapes_, obj_.faces.size(), 0};
        hasLinesOrPoints_ = false;
    }

    void endShape() {
        current_.endFace = obj_.faces.size();
        if (current_.endFace > current_.firstFace) obj_.shapes.push_back(current_);
    }

    const std::string& path_;
    LineReader lines_;
    LineErrors bad_;
    Obj obj_;
    Shape current_;
    std::size_t listedShapes_ = 0;
    bool hasLinesOrPoints_ = false;
    Highest highest_[3];
    Corner scratch_;
};

// One shape's faces of one material as a Mesh, fan-triangulated from each face's first corner. With a normal
// on every corner a vertex is a (position, normal) pair, so hard edges survive; otherwise vertices are
// positions only, numbered in order of first use, and normals are computed later.
Mesh buildMesh(const Obj& obj, const std::vector<std::size_t>& faces, const std::string& path) {
    bool allNormals = true;
    std::size_t triangles = 0;
    for (std::size_t f : faces) {
        const Face& face = obj.faces[f];
        for (std::size_t k = 0; k < face.count; ++k) allNormals = allNormals && obj.corners[face.firstCorner + k].n != kNone;
        triangles += face.count - 2;
    }
    Mesh m;
    m.indices.reserve(3 * triangles);
    std::unordered_map<std::uint64_t, std::uint32_t> remap;
    auto add = [&](const Corner& c) {
        const std::uint32_t n = allNormals ? c.n : kNone;
        auto [it, added] = remap.try_emplace(std::uint64_t(c.v) << 32 | n, std::uint32_t(m.positions.size()));
        if (added) {
            if (m.positions.size() >= kNone) fail(path, "more than " + std::to_string(kNone) + " vertices in one mesh");
            m.positions.push_back(obj.positions[c.v]);
            if (allNormals) m.normals.push_back(obj.normals[n]);
        }
        m.indices.push_back(it->second);
    };
    for (std::size_t f : faces) {
        const Corner* c = &obj.corners[obj.faces[f].firstCorner];
        for (std::size_t k = 1; k + 1 < obj.faces[f].count; ++k) {
            add(c[0]);
            add(c[k]);
            add(c[k + 1]);
        }
    }
    return m;
}

} // namespace

Scene loadObj(const std::string& path, LoadInfo* info) {
    loader::checkSceneFile(path);
    Obj obj;
    {
        const std::string text = loader::readWholeFile(path);
        obj = ObjParser(path, text).parse();
    }

    // mtllib names are relative to the .obj's directory. All the files named are read (tinyobjloader stopped
    // at the first it found); a material in two of them keeps its first definition.
    Materials materials;
    const fs::path dir = fs::path(path).parent_path();
    for (const std::string& name : obj.mtllibs) readMtl((dir / name).string(), materials);
    // Names resolved once the whole file is read, so a usemtl above its mtllib still finds its material. An
    // unknown name is no material (the default colour), as before.
    std::vector<int> materialOf(obj.useNames.size(), -1);
    for (std::size_t i = 0; i < obj.useNames.size(); ++i) {
        auto it = materials.byName.find(obj.useNames[i]);
        if (it != materials.byName.end()) materialOf[i] = it->second;
    }

    Scene scene;
    for (const Shape& shape : obj.shapes) {
        // The shape's faces per material, materials in order of first use, faces in file order.
        std::vector<std::pair<int, std::vector<std::size_t>>> groups;
        std::unordered_map<int, std::size_t> groupOf;
        for (std::size_t f = shape.firstFace; f < shape.endFace; ++f) {
            const int use = obj.faces[f].material;
            const int material = use < 0 ? -1 : materialOf[std::size_t(use)];
            auto [it, added] = groupOf.try_emplace(material, groups.size());
            if (added) groups.emplace_back(material, std::vector<std::size_t>{});
            groups[it->second].second.push_back(f);
        }
        for (const auto& [material, faces] : groups) {
            Mesh m = buildMesh(obj, faces, path);
            m.name = shape.name.empty() ? "object" + std::to_string(shape.index) : shape.name;
            if (material >= 0) {
                const Material& mat = materials.list[std::size_t(material)];
                m.name += "/" + mat.name;
                m.baseColor = mat.diffuse;
            }
            computeSmoothNormals(m);
            scene.add(std::move(m));
        }
    }
    if (scene.meshes.empty()) fail(path, "no faces");

    loader::InfoSink out(info);
    Scene result = loader::finishLoad(std::move(scene), path, out);
    out->droppedTriangles += obj.shortFaces;
    return result;
}

} // namespace obscura
