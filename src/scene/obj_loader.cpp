// Wavefront OBJ loader on tinyobjloader, with the index and value checks tinyobjloader does not make.
#include "obscura/error.h"
#include "obscura/scene_io.h"
#include "scene/loader_common.h"

#include <tiny_obj_loader.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <utility>

namespace obscura {

namespace {

// The faces of one (shape, material) pair, already fan-triangulated: 3 corners per triangle.
struct Group {
    int material = -1;
    std::vector<tinyobj::index_t> corners;
};

// Builds a Mesh from a group's corners. With a normal on every corner a vertex is a (position, normal)
// pair, so hard edges survive; otherwise vertices are positions only and normals are computed later.
Mesh buildMesh(const Group& group, const tinyobj::attrib_t& attrib) {
    bool allNormals = true;
    for (const tinyobj::index_t& c : group.corners) allNormals = allNormals && c.normal_index >= 0;
    Mesh m;
    std::map<std::pair<int, int>, std::uint32_t> remap;
    m.indices.reserve(group.corners.size());
    for (const tinyobj::index_t& c : group.corners) {
        auto key = std::make_pair(c.vertex_index, allNormals ? c.normal_index : -1);
        auto [it, inserted] = remap.try_emplace(key, std::uint32_t(m.positions.size()));
        if (inserted) {
            const auto v = std::size_t(c.vertex_index) * 3;
            m.positions.push_back({attrib.vertices[v], attrib.vertices[v + 1], attrib.vertices[v + 2]});
            if (allNormals) {
                const auto n = std::size_t(c.normal_index) * 3;
                m.normals.push_back(normalize(Vec3{attrib.normals[n], attrib.normals[n + 1], attrib.normals[n + 2]}));
            }
        }
        m.indices.push_back(it->second);
    }
    return m;
}

} // namespace

Scene loadObj(const std::string& path, LoadInfo* info) {
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) fail(path, "no such file");

    tinyobj::ObjReaderConfig config;
    // We triangulate ourselves: tinyobjloader's triangulation silently drops faces with bad indices and
    // splits quads by their shorter diagonal, where we promise a fan.
    config.triangulate = false;
    config.vertex_color = false;
    // An empty search path makes tinyobjloader look for the .mtl next to the .obj. A missing .mtl is
    // only a warning there, and LoadInfo has no place for warnings, so it is dropped (default colour).
    tinyobj::ObjReader reader;
    if (!reader.ParseFromFile(path, config))
        fail(path, reader.Error().empty() ? "not a valid OBJ file" : loader::firstLine(reader.Error()));

    const tinyobj::attrib_t& attrib = reader.GetAttrib();
    const std::size_t nv = attrib.vertices.size() / 3, nn = attrib.normals.size() / 3;
    // Numbered from 1, as the file's own 'f' lines count them.
    for (std::size_t i = 0; i < nv; ++i)
        if (!isFinite(Vec3{attrib.vertices[3 * i], attrib.vertices[3 * i + 1], attrib.vertices[3 * i + 2]}))
            fail(path, "vertex " + std::to_string(i + 1) + " has a non-finite position");
    for (std::size_t i = 0; i < nn; ++i)
        if (!isFinite(Vec3{attrib.normals[3 * i], attrib.normals[3 * i + 1], attrib.normals[3 * i + 2]}))
            fail(path, "normal " + std::to_string(i + 1) + " is not finite");

    Scene scene;
    const std::vector<tinyobj::material_t>& materials = reader.GetMaterials();
    std::size_t faceNumber = 0;
    for (std::size_t s = 0; s < reader.GetShapes().size(); ++s) {
        const tinyobj::shape_t& shape = reader.GetShapes()[s];
        const tinyobj::mesh_t& mesh = shape.mesh;
        std::vector<Group> groups;  // in order of first use, so mesh order follows the file
        std::size_t offset = 0;
        for (std::size_t f = 0; f < mesh.num_face_vertices.size(); ++f) {
            ++faceNumber;
            const std::size_t count = mesh.num_face_vertices[f];
            // tinyobjloader drops faces under 3 vertices itself and stores counts in an unsigned char, so a
            // smaller count here (or a mismatch at the end) is a polygon of 256+ vertices, wrapped.
            if (count < 3 || offset + count > mesh.indices.size())
                fail(path, "face " + std::to_string(faceNumber) + ": polygons of more than 255 vertices are not supported");
            for (std::size_t k = 0; k < count; ++k) {
                const tinyobj::index_t& c = mesh.indices[offset + k];
                if (c.vertex_index < 0 || std::size_t(c.vertex_index) >= nv)
                    fail(path, "face " + std::to_string(faceNumber) + ": vertex " + std::to_string(c.vertex_index + 1) +
                                   " out of range (" + std::to_string(nv) + " vertices)");
                if (c.normal_index >= 0 && std::size_t(c.normal_index) >= nn)
                    fail(path, "face " + std::to_string(faceNumber) + ": normal " + std::to_string(c.normal_index + 1) +
                                   " out of range (" + std::to_string(nn) + " normals)");
            }
            int material = f < mesh.material_ids.size() ? mesh.material_ids[f] : -1;
            if (material < 0 || std::size_t(material) >= materials.size()) material = -1;
            Group* group = nullptr;
            for (Group& g : groups)
                if (g.material == material) group = &g;
            if (!group) group = &groups.emplace_back(Group{material, {}});
            for (std::size_t k = 1; k + 1 < count; ++k) {
                group->corners.push_back(mesh.indices[offset]);
                group->corners.push_back(mesh.indices[offset + k]);
                group->corners.push_back(mesh.indices[offset + k + 1]);
            }
            offset += count;
        }
        if (offset != mesh.indices.size())
            fail(path, "polygons of more than 255 vertices are not supported");

        for (const Group& g : groups) {
            Mesh m = buildMesh(g, attrib);
            m.name = shape.name.empty() ? "object" + std::to_string(s) : shape.name;
            if (g.material >= 0) {
                const tinyobj::material_t& mat = materials[std::size_t(g.material)];
                m.name += "/" + mat.name;
                m.baseColor = {float(mat.diffuse[0]), float(mat.diffuse[1]), float(mat.diffuse[2])};
            }
            computeSmoothNormals(m);
            scene.add(std::move(m));
        }
    }
    if (scene.meshes.empty()) fail(path, "no faces");

    loader::InfoSink out(info);
    return loader::finishLoad(std::move(scene), path, out);
}

} // namespace obscura
