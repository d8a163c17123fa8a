// Output of a bake: glTF attributes, PLY quality and CSV, with the artist's blend and remap (Sloan et al.
// 2013 §3: "blended long and short AO values, currently 97% using the long radius and 3% using the short
// radius ... remapped to give the artist more control").
#include "obscura/bake_io.h"

#include "obscura/error.h"
#include "obscura/image_io.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>

namespace obscura::bake {

namespace {

float channel(const BakeResult& r, std::size_t vertex, int c) {
    return r.values[vertex * std::size_t(r.channels) + std::size_t(std::min(c, r.channels - 1))];
}

struct Writer {
    std::FILE* f;
    const std::string& path;
    void put(const void* data, std::size_t bytes) {
        if (std::fwrite(data, 1, bytes, f) != bytes) fail(path, "write failed (disk full?)");
    }
};

// Opens the temporary file `temp` of `path`, runs write(f), and checks that everything reached the disk:
// the buffered tail surfaces its errors only at fflush or fclose. Any failure throws naming `path`.
template <typename Write>
void writeFile(const std::string& path, const std::string& temp, Write&& write) {
    std::FILE* f = std::fopen(temp.c_str(), "wb");
    if (!f) fail(path, "cannot open for writing");
    try {
        write(f);
    } catch (...) {
        std::fclose(f);
        throw;
    }
    const bool flushed = std::fflush(f) == 0;
    if (std::fclose(f) != 0 || !flushed) fail(path, "write failed (disk full?)");
}

} // namespace

void ArtistControls::validate() const {
    if (!(blend >= 0.0f && blend <= 1.0f)) fail("--blend", "must be in [0, 1], got " + numberText(blend));
    if (!(gamma > 0.0f && gamma <= 16.0f)) fail("--gamma", "must be in (0, 16], got " + numberText(gamma));
    if (!(low >= 0.0f && low <= 1.0f)) fail("--remap-min", "must be in [0, 1], got " + numberText(low));
    if (!(high >= 0.0f && high <= 1.0f)) fail("--remap-max", "must be in [0, 1], got " + numberText(high));
}

float ArtistControls::shade(float shortAO, float longAO) const {
    const float b = std::clamp(blended(shortAO, longAO), 0.0f, 1.0f);
    return low + (high - low) * std::pow(b, gamma);
}

InstanceAttributes bakedAttributes(const BakeResult& r, const ArtistControls& controls) {
    InstanceAttributes a;
    a.first = r.instanceFirst;
    const std::size_t n = r.instanceFirst.back();
    VertexAttribute color{"COLOR_0", 3, {}}, shortAO{"_AO_SHORT", 1, {}}, longAO{"_AO_LONG", 1, {}};
    color.data.resize(3 * n);
    shortAO.data.resize(n);
    if (r.channels > 1) longAO.data.resize(n);
    for (std::size_t v = 0; v < n; ++v) {
        const float s = channel(r, v, 0), l = channel(r, v, 1);
        const float g = controls.shade(s, l);
        color.data[3 * v] = color.data[3 * v + 1] = color.data[3 * v + 2] = g;
        shortAO.data[v] = s;
        if (r.channels > 1) longAO.data[v] = l;
    }
    a.attributes.push_back(std::move(color));
    a.attributes.push_back(std::move(shortAO));
    if (r.channels > 1) a.attributes.push_back(std::move(longAO));
    return a;
}

void writeBakeOutput(const std::string& inputPath, const Scene& scene, const BakeResult& result,
                     const ArtistControls& controls, const std::string& path) {
    const std::string ext = fileExtension(path);
    if (ext == ".glb" || ext == ".gltf") {
        const std::string in = fileExtension(inputPath);
        const InstanceAttributes a = bakedAttributes(result, controls);
        if (in == ".glb" || in == ".gltf")
            writeGltfWithAttributes(inputPath, scene, path, a);
        else
            writeGltf(scene, path, &a);
    } else if (ext == ".ply") {
        writeBakedPly(scene, result, controls, path);
    } else if (ext == ".csv") {
        writeBakedCsv(scene, result, controls, path);
    } else {
        fail(path, "unsupported output format '" + ext + "' (expected .glb, .gltf, .ply or .csv)");
    }
}

void writeBakedPly(const Scene& scene, const BakeResult& r, const ArtistControls& controls, const std::string& path) {
    std::size_t vertices = r.instanceFirst.back(), faces = 0;
    for (const Instance& inst : scene.instances) faces += scene.meshes[inst.mesh].triangleCount();
    // The header says "int": signed 32-bit indices, which from 2^31 vertices on would read as negative.
    if (vertices > 0x7fffffffu) fail(path, "too many vertices for PLY int indices (2^31 - 1 at most)");
    writeAtomically(path, [&](const std::string& temp) { writeFile(path, temp, [&](std::FILE* f) {
        Writer w{f, path};
        const std::string header =
            "ply\nformat binary_little_endian 1.0\ncomment obscura bake: quality = blended and remapped obscurance\n"
            "element vertex " + std::to_string(vertices) +
            "\nproperty float x\nproperty float y\nproperty float z\nproperty float quality\nproperty float ao_short\n"
            "property float ao_long\nproperty uchar red\nproperty uchar green\nproperty uchar blue\n"
            "element face " + std::to_string(faces) + "\nproperty list uchar int vertex_indices\nend_header\n";
        w.put(header.data(), header.size());
        unsigned char record[27];
        for (std::size_t i = 0; i < scene.instances.size(); ++i) {
            const Instance& inst = scene.instances[i];
            const Mesh& mesh = scene.meshes[inst.mesh];
            for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
                const std::size_t k = r.instanceFirst[i] + v;
                const Vec3 p = transformPoint(inst.worldFromObject, mesh.positions[v]);
                const float s = channel(r, k, 0), l = channel(r, k, 1), q = controls.shade(s, l);
                const float fields[6] = {p.x, p.y, p.z, q, s, l};
                std::memcpy(record, fields, sizeof fields);
                const auto grey = static_cast<unsigned char>(std::lround(std::clamp(q, 0.0f, 1.0f) * 255.0f));
                record[24] = record[25] = record[26] = grey;
                w.put(record, sizeof record);
            }
        }
        unsigned char face[13];
        face[0] = 3;
        for (std::size_t i = 0; i < scene.instances.size(); ++i) {
            const Instance& inst = scene.instances[i];
            const Mesh& mesh = scene.meshes[inst.mesh];
            const bool mirrored = determinant3(inst.worldFromObject) < 0.0f;
            for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
                std::int32_t idx[3];
                for (int k = 0; k < 3; ++k) idx[k] = std::int32_t(r.instanceFirst[i] + mesh.indices[3 * t + std::size_t(k)]);
                if (mirrored) std::swap(idx[1], idx[2]);
                std::memcpy(face + 1, idx, sizeof idx);
                w.put(face, sizeof face);
            }
        }
    }); });
}

void writeBakedCsv(const Scene& scene, const BakeResult& r, const ArtistControls& controls, const std::string& path) {
    writeAtomically(path, [&](const std::string& temp) { writeFile(path, temp, [&](std::FILE* f) {
        Writer w{f, path};
        const std::string header = "index,x,y,z,short,long,blended\n";
        w.put(header.data(), header.size());
        // std::to_chars: the shortest text that reads back as the same float, and no locale (printf wrote
        // "0,66464" with decimal commas in a host program that had set a German locale).
        char line[160];
        for (std::size_t i = 0; i < scene.instances.size(); ++i) {
            const Instance& inst = scene.instances[i];
            const Mesh& mesh = scene.meshes[inst.mesh];
            for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
                const std::size_t k = r.instanceFirst[i] + v;
                const Vec3 p = transformPoint(inst.worldFromObject, mesh.positions[v]);
                const float s = channel(r, k, 0), l = channel(r, k, 1);
                char* end = std::to_chars(line, line + sizeof line, k).ptr;
                for (float x : {p.x, p.y, p.z, s, l, controls.blended(s, l)}) {
                    *end++ = ',';
                    end = std::to_chars(end, line + sizeof line, x).ptr;
                }
                *end++ = '\n';
                w.put(line, std::size_t(end - line));
            }
        }
    }); });
}

} // namespace obscura::bake
