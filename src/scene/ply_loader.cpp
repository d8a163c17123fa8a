// PLY loader of our own: ASCII and binary (both byte orders), unknown elements skipped, every read checked.
//
// Our own rather than a library: the format is small, and what matters here is that a truncated or lying
// file gives a message naming the line or element, which is easier to promise in code we control.
#include "obscura/error.h"
#include "obscura/scene_io.h"
#include "scene/loader_common.h"

#include <algorithm>
#include <bit>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <string_view>
#include <type_traits>

namespace obscura {

namespace {

enum class Type { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };
enum class Format { Ascii, BinaryLittle, BinaryBig };

std::size_t sizeOf(Type t) {
    switch (t) {
    case Type::Int8: case Type::UInt8: return 1;
    case Type::Int16: case Type::UInt16: return 2;
    case Type::Int32: case Type::UInt32: case Type::Float32: return 4;
    case Type::Float64: return 8;
    }
    return 0;
}

bool isInteger(Type t) { return t != Type::Float32 && t != Type::Float64; }

// The largest value of an integer type, which is what a full-intensity colour channel holds in it (127 for a
// char: a signed type's negative half is not light).
double fullScale(Type t) {
    switch (t) {
    case Type::Int8: return 127.0;
    case Type::UInt8: return 255.0;
    case Type::Int16: return 32767.0;
    case Type::UInt16: return 65535.0;
    case Type::Int32: return 2147483647.0;
    case Type::UInt32: return 4294967295.0;
    default: return 1.0;
    }
}

// The smallest value of an integer type.
double lowest(Type t) {
    switch (t) {
    case Type::Int8: return -128.0;
    case Type::Int16: return -32768.0;
    case Type::Int32: return -2147483648.0;
    default: return 0.0;
    }
}

const char* typeName(Type t) {
    switch (t) {
    case Type::Int8: return "char";
    case Type::UInt8: return "uchar";
    case Type::Int16: return "short";
    case Type::UInt16: return "ushort";
    case Type::Int32: return "int";
    case Type::UInt32: return "uint";
    case Type::Float32: return "float";
    case Type::Float64: return "double";
    }
    return "?";
}

bool parseType(std::string_view s, Type& t) {
    struct Name {
        std::string_view name;
        Type type;
    };
    static constexpr Name kNames[] = {
        {"char", Type::Int8},    {"int8", Type::Int8},       {"uchar", Type::UInt8},   {"uint8", Type::UInt8},
        {"short", Type::Int16},  {"int16", Type::Int16},     {"ushort", Type::UInt16}, {"uint16", Type::UInt16},
        {"int", Type::Int32},    {"int32", Type::Int32},     {"uint", Type::UInt32},   {"uint32", Type::UInt32},
        {"float", Type::Float32}, {"float32", Type::Float32}, {"double", Type::Float64}, {"float64", Type::Float64}};
    for (const Name& n : kNames)
        if (n.name == s) return t = n.type, true;
    return false;
}

struct Property {
    std::string name;
    Type type = Type::Float32;  // of the items, for a list
    bool list = false;
    Type countType = Type::UInt8;
};

struct Element {
    std::string name;
    std::uint64_t count = 0;
    std::vector<Property> properties;
    int line = 0;  // where it was declared, for messages about its layout
};

struct Header {
    Format format = Format::Ascii;
    std::vector<Element> elements;
    std::size_t dataStart = 0;  // byte offset of the first byte after "end_header\n"
    int lines = 0;
};

std::vector<std::string_view> split(std::string_view line) {
    std::vector<std::string_view> tokens;
    std::size_t i = 0;
    while (i < line.size()) {
        while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
        std::size_t j = i;
        while (j < line.size() && line[j] != ' ' && line[j] != '\t') ++j;
        if (j > i) tokens.push_back(line.substr(i, j - i));
        i = j;
    }
    return tokens;
}

Header parseHeader(std::string_view data, const std::string& path) {
    Header h;
    bool haveFormat = false;
    std::size_t pos = 0;
    for (int lineNo = 1;; ++lineNo) {
        auto bad = [&](const std::string& problem) { fail(path, "line " + std::to_string(lineNo) + ": " + problem); };
        std::size_t eol = data.find('\n', pos);
        if (eol == std::string_view::npos) {
            if (lineNo == 1) bad("not a PLY file (no 'ply' line)");
            bad("the header has no end_header");
        }
        std::string_view line = data.substr(pos, eol - pos);
        if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
        pos = eol + 1;
        std::vector<std::string_view> t = split(line);
        if (lineNo == 1) {
            if (t.size() != 1 || t[0] != "ply") bad("not a PLY file (the first line is not 'ply')");
            continue;
        }
        if (t.empty() || t[0] == "comment" || t[0] == "obj_info") continue;
        const std::string key(t[0]);
        if (key == "format") {
            if (haveFormat) bad("a second format line");
            if (t.size() != 3) bad("expected 'format <ascii|binary_little_endian|binary_big_endian> 1.0'");
            if (t[1] == "ascii") h.format = Format::Ascii;
            else if (t[1] == "binary_little_endian") h.format = Format::BinaryLittle;
            else if (t[1] == "binary_big_endian") h.format = Format::BinaryBig;
            else bad("unknown format '" + std::string(t[1]) + "'");
            if (t[2] != "1.0" && t[2] != "1") bad("unsupported format version '" + std::string(t[2]) + "'");
            haveFormat = true;
        } else if (key == "element") {
            Element e;
            if (t.size() != 3) bad("expected 'element <name> <count>'");
            auto [end, ec] = std::from_chars(t[2].data(), t[2].data() + t[2].size(), e.count);
            if (ec != std::errc{} || end != t[2].data() + t[2].size())
                bad("element count '" + std::string(t[2]) + "' is not a non-negative integer");
            e.name = std::string(t[1]);
            e.line = lineNo;
            h.elements.push_back(std::move(e));
        } else if (key == "property") {
            if (h.elements.empty()) bad("property before any element");
            Property p;
            if (t.size() >= 2 && t[1] == "list") {
                if (t.size() != 5) bad("expected 'property list <count type> <item type> <name>'");
                if (!parseType(t[2], p.countType)) bad("unknown property type '" + std::string(t[2]) + "'");
                if (!isInteger(p.countType)) bad("list count type '" + std::string(t[2]) + "' is not an integer type");
                if (!parseType(t[3], p.type)) bad("unknown property type '" + std::string(t[3]) + "'");
                p.list = true;
                p.name = std::string(t[4]);
            } else {
                if (t.size() != 3) bad("expected 'property <type> <name>'");
                if (!parseType(t[1], p.type)) bad("unknown property type '" + std::string(t[1]) + "'");
                p.name = std::string(t[2]);
            }
            h.elements.back().properties.push_back(std::move(p));
        } else if (key == "end_header") {
            if (!haveFormat) bad("end_header before any format line");
            h.dataStart = pos;
            h.lines = lineNo;
            return h;
        } else {
            bad("unknown header keyword '" + key + "'");
        }
    }
}

// Whitespace-separated numbers; knows its line for messages.
class AsciiSource {
public:
    AsciiSource(std::string_view data, int line, const std::string& path) : data_(data), line_(line), path_(path) {}

    // False at the end of the data; throws for a token that is not a number that fits `type`.
    bool read(Type type, double& v) {
        while (pos_ < data_.size() && std::isspace(static_cast<unsigned char>(data_[pos_])))
            if (data_[pos_++] == '\n') ++line_;
        if (pos_ >= data_.size()) return false;
        std::size_t end = pos_;
        while (end < data_.size() && !std::isspace(static_cast<unsigned char>(data_[end]))) ++end;
        std::string_view tok = data_.substr(pos_, end - pos_);
        pos_ = end;
        std::string_view digits = tok.front() == '+' ? tok.substr(1) : tok;  // from_chars rejects '+'
        auto [stop, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), v);
        if (ec != std::errc{} || stop != digits.data() + digits.size())
            fail(path_, "line " + std::to_string(line_) + ": expected a number, got '" + std::string(tok) + "'");
        if (isInteger(type) && !(std::floor(v) == v))
            fail(path_, "line " + std::to_string(line_) + ": expected an integer, got '" + std::string(tok) + "'");
        // What a binary file could hold in the declared type, and no more: 'inf' and 1e30 passed the integer
        // test above and then met an integer cast, undefined for them.
        if (isInteger(type) && !(v >= lowest(type) && v <= fullScale(type)))
            fail(path_, "line " + std::to_string(line_) + ": '" + std::string(tok) + "' does not fit the declared type " +
                            typeName(type));
        return true;
    }

    bool skip(Type type, std::uint64_t n) {
        double v;
        for (std::uint64_t i = 0; i < n; ++i)
            if (!read(type, v)) return false;
        return true;
    }

    std::size_t remaining() const { return data_.size() - pos_; }

    // Throws if anything but white space follows the last element's rows.
    void expectEnd() {
        while (pos_ < data_.size() && std::isspace(static_cast<unsigned char>(data_[pos_])))
            if (data_[pos_++] == '\n') ++line_;
        if (pos_ < data_.size())
            fail(path_, "line " + std::to_string(line_) + ": data after the last element (the header declares fewer rows "
                                                          "than the file holds)");
    }

private:
    std::string_view data_;
    std::size_t pos_ = 0;
    int line_;
    const std::string& path_;
};

class BinarySource {
public:
    BinarySource(std::string_view data, bool bigEndian, const std::string& path)
        : data_(data), swap_(bigEndian != (std::endian::native == std::endian::big)), path_(path) {}

    bool read(Type type, double& v) {
        const std::size_t n = sizeOf(type);
        if (remaining() < n) return false;
        unsigned char b[8];
        std::memcpy(b, data_.data() + pos_, n);
        pos_ += n;
        if (swap_)
            for (std::size_t i = 0; i < n / 2; ++i) std::swap(b[i], b[n - 1 - i]);
        v = decode(type, b);
        return true;
    }

    bool skip(Type type, std::uint64_t n) {
        if (n > remaining() / sizeOf(type)) return false;
        pos_ += std::size_t(n) * sizeOf(type);
        return true;
    }

    std::size_t remaining() const { return data_.size() - pos_; }

    // Throws if bytes follow the last element's rows.
    void expectEnd() const {
        if (remaining() > 0)
            fail(path_, std::to_string(remaining()) + " bytes after the last element (the header declares fewer rows "
                                                      "than the file holds)");
    }

private:
    template <class T> static double as(const unsigned char* b) {
        T x;
        std::memcpy(&x, b, sizeof x);
        return double(x);
    }
    static double decode(Type type, const unsigned char* b) {
        switch (type) {
        case Type::Int8: return as<std::int8_t>(b);
        case Type::UInt8: return as<std::uint8_t>(b);
        case Type::Int16: return as<std::int16_t>(b);
        case Type::UInt16: return as<std::uint16_t>(b);
        case Type::Int32: return as<std::int32_t>(b);
        case Type::UInt32: return as<std::uint32_t>(b);
        case Type::Float32: return as<float>(b);
        case Type::Float64: return as<double>(b);
        }
        return 0;
    }

    std::string_view data_;
    std::size_t pos_ = 0;
    bool swap_;
    const std::string& path_;
};

// Non-finite normals are kept as they are, for sanitizeScene to report (normalize would zero them).
Vec3 unitIfFinite(Vec3 n) { return isFinite(n) ? normalize(n) : n; }

// "4 vertices", "1 face", "2 'edge' elements": what a count of e's rows is called in messages.
std::string counted(const Element& e) {
    const bool one = e.count == 1;
    if (e.name == "vertex") return one ? "1 vertex" : std::to_string(e.count) + " vertices";
    if (e.name == "face") return one ? "1 face" : std::to_string(e.count) + " faces";
    return std::to_string(e.count) + " '" + e.name + (one ? "' element" : "' elements");
}

int find(const Element& e, std::string_view name) {
    for (std::size_t i = 0; i < e.properties.size(); ++i)
        if (e.properties[i].name == name) return int(i);
    return -1;
}

template <class Source> class BodyReader {
public:
    BodyReader(Source& src, const std::string& path) : src_(src), path_(path) {}

    Mesh read(const Header& h) {
        const Element* vertex = nullptr;
        for (const Element& e : h.elements)
            if (e.name == "vertex") vertex = &e;
        if (!vertex) fail(path_, "no vertex element");
        nv_ = vertex->count;
        bool haveFaces = false;
        for (const Element& e : h.elements) {
            if (e.name == "vertex") readVertices(e);
            else if (e.name == "face") {
                readFaces(e);
                haveFaces = true;
            } else skipElement(e);
        }
        if (!haveFaces) fail(path_, "no face element (point clouds are not supported)");
        src_.expectEnd();
        if (colorCount_ > 0) mesh_.baseColor = colorSum_ / float(colorCount_);
        return std::move(mesh_);
    }

private:
    [[noreturn]] void truncated(const Element& e, std::uint64_t got) {
        fail(path_, "truncated: expected " + counted(e) + ", got " + std::to_string(got));
    }

    // Reads one row's scalars into row[] (lists are read past); false at the end of the data.
    bool readRow(const Element& e, std::vector<double>& row, int listIndex, std::vector<std::uint32_t>* list) {
        for (std::size_t i = 0; i < e.properties.size(); ++i) {
            const Property& p = e.properties[i];
            if (!p.list) {
                if (!src_.read(p.type, row[i])) return false;
                continue;
            }
            double count;
            if (!src_.read(p.countType, count)) return false;
            if (count < 0) fail(path_, "element '" + e.name + "': negative list length");
            if (int(i) != listIndex) {
                if (!src_.skip(p.type, std::uint64_t(count))) return false;
                continue;
            }
            list->clear();
            for (std::uint64_t k = 0; k < std::uint64_t(count); ++k) {
                double v;
                if (!src_.read(p.type, v)) return false;
                if (!(v >= 0 && v < double(nv_)))
                    fail(path_, "face " + std::to_string(faces_) + ": index " + std::to_string(std::int64_t(v)) +
                                    " out of range (" + std::to_string(nv_) + " vertices)");
                list->push_back(std::uint32_t(v));
            }
        }
        return true;
    }

    void readVertices(const Element& e) {
        if (!mesh_.positions.empty()) fail(path_, "line " + std::to_string(e.line) + ": a second vertex element");
        const int x = find(e, "x"), y = find(e, "y"), z = find(e, "z");
        if (x < 0 || y < 0 || z < 0) fail(path_, "line " + std::to_string(e.line) + ": the vertex element has no x, y, z");
        const int nx = find(e, "nx"), ny = find(e, "ny"), nz = find(e, "nz");
        const int r = find(e, "red"), g = find(e, "green"), b = find(e, "blue");
        for (int i : {x, y, z, nx, ny, nz, r, g, b})
            if (i >= 0 && e.properties[std::size_t(i)].list)
                fail(path_, "line " + std::to_string(e.line) + ": vertex property '" + e.properties[std::size_t(i)].name +
                                "' is a list");
        const bool normals = nx >= 0 && ny >= 0 && nz >= 0, colors = r >= 0 && g >= 0 && b >= 0;
        if (std::uint64_t(e.count) > std::numeric_limits<std::uint32_t>::max())
            fail(path_, "line " + std::to_string(e.line) + ": more than 2^32 vertices");
        // Reserve no more than the data could hold, so a lying count cannot exhaust memory.
        mesh_.positions.reserve(std::size_t(std::min<std::uint64_t>(e.count, src_.remaining() / 3)));
        std::vector<double> row(e.properties.size());
        auto at = [&](int i) { return row[std::size_t(i)]; };
        for (std::uint64_t i = 0; i < e.count; ++i) {
            if (!readRow(e, row, -1, nullptr)) truncated(e, i);
            mesh_.positions.push_back({float(at(x)), float(at(y)), float(at(z))});
            if (normals) mesh_.normals.push_back(unitIfFinite(Vec3{float(at(nx)), float(at(ny)), float(at(nz))}));
            if (colors) {
                auto channel = [&](int c) { return float(at(c) / fullScale(e.properties[std::size_t(c)].type)); };
                const Vec3 color{channel(r), channel(g), channel(b)};
                // Each vertex's, before the mesh's mean: (2, 2, 2), (-1, -1, -1) and (0.5, 0.5, 0.5) averaged to a
                // valid grey.
                if (!(color.x >= 0 && color.x <= 1 && color.y >= 0 && color.y <= 1 && color.z >= 0 && color.z <= 1))
                    fail(path_, "vertex " + std::to_string(i) + " has colour (" + numberText(color.x) + ", " +
                                    numberText(color.y) + ", " + numberText(color.z) + "), outside [0, 1]");
                colorSum_ += color;
                ++colorCount_;
            }
        }
    }

    void readFaces(const Element& e) {
        int list = find(e, "vertex_indices");
        if (list < 0) list = find(e, "vertex_index");
        if (list < 0) fail(path_, "line " + std::to_string(e.line) + ": the face element has no vertex_indices");
        const Property& p = e.properties[std::size_t(list)];
        if (!p.list) fail(path_, "line " + std::to_string(e.line) + ": face property '" + p.name + "' is not a list");
        if (!isInteger(p.type)) fail(path_, "line " + std::to_string(e.line) + ": face indices are not integers");
        std::vector<double> row(e.properties.size());
        std::vector<std::uint32_t> corners;
        for (faces_ = 0; faces_ < e.count; ++faces_) {
            if (!readRow(e, row, list, &corners)) truncated(e, faces_);
            // Fewer than 3 corners is a point or an edge: nothing to shade.
            for (std::size_t k = 1; k + 1 < corners.size(); ++k)
                mesh_.indices.insert(mesh_.indices.end(), {corners[0], corners[k], corners[k + 1]});
        }
    }

    void skipElement(const Element& e) {
        // Rows of no properties hold nothing, however many the header declares (1e18 once took centuries).
        if (e.properties.empty()) return;
        bool fixed = true;
        std::size_t rowBytes = 0;
        for (const Property& p : e.properties) {
            fixed = fixed && !p.list;
            rowBytes += sizeOf(p.type);
        }
        // Binary rows of scalars only have one size: skip them all in one checked step.
        if constexpr (std::is_same_v<Source, BinarySource>) {
            if (fixed && rowBytes > 0) {
                if (e.count > src_.remaining() / rowBytes) truncated(e, src_.remaining() / rowBytes);
                src_.skip(Type::UInt8, e.count * rowBytes);
                return;
            }
        }
        std::vector<double> row(e.properties.size());
        for (std::uint64_t i = 0; i < e.count; ++i)
            if (!readRow(e, row, -1, nullptr)) truncated(e, i);
    }

    Source& src_;
    const std::string& path_;
    Mesh mesh_;
    std::uint64_t nv_ = 0;
    std::uint64_t faces_ = 0;
    Vec3 colorSum_{};
    std::size_t colorCount_ = 0;
};

} // namespace

Scene loadPly(const std::string& path, LoadInfo* info) {
    loader::checkSceneFile(path);
    const std::string bytes = loader::readWholeFile(path);

    std::string_view data(bytes);
    Header h = parseHeader(data, path);
    std::string_view body = data.substr(h.dataStart);
    Mesh mesh;
    if (h.format == Format::Ascii) {
        AsciiSource src(body, h.lines + 1, path);
        mesh = BodyReader<AsciiSource>(src, path).read(h);
    } else {
        BinarySource src(body, h.format == Format::BinaryBig, path);
        mesh = BodyReader<BinarySource>(src, path).read(h);
    }
    mesh.name = std::filesystem::path(path).stem().string();
    computeSmoothNormals(mesh);

    Scene scene;
    scene.add(std::move(mesh));
    loader::InfoSink out(info);
    return loader::finishLoad(std::move(scene), path, out);
}

} // namespace obscura
