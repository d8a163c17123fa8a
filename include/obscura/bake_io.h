// Writing a bake's per-vertex results: glTF/GLB (COLOR_0 grey plus _AO_SHORT and _AO_LONG), PLY (a
// `quality` property, as MeshLab reads it) and CSV. Artist controls from Sloan et al. 2013 §3: the blend
// of the two distances and a remap of the blended value.
//
// Errors: writers throw obscura::Error("<path>: <problem>"); every file is written to a temporary and
// renamed, so a failure leaves no partial output and an input file is never touched.
#pragma once

#include "obscura/bake.h"
#include "obscura/gltf_writer.h"

#include <string>

namespace obscura::bake {

struct ArtistControls {
    float blend = 0.03f;   // weight of the short distance in the blend: [0, 1]; the seed ships 3% short, 97% long
    float gamma = 1.0f;    // remap exponent applied to the blend: (0, 16]; 1 keeps it linear
    float low = 0.0f;      // remapped value of a fully obscured vertex: [0, 1]
    float high = 1.0f;     // remapped value of an open vertex: [0, 1]

    void validate() const;  // throws obscura::Error naming the flag
    // (1 - blend) long + blend short; with one channel, that channel.
    float blended(float shortAO, float longAO) const { return (1.0f - blend) * longAO + blend * shortAO; }
    // low + (high - low) * blended^gamma: what COLOR_0 and PLY quality carry.
    float shade(float shortAO, float longAO) const;
};

// COLOR_0 (VEC3 grey, the shade), _AO_SHORT and, with two channels, _AO_LONG, per instance.
InstanceAttributes bakedAttributes(const BakeResult& result, const ArtistControls& controls);

// Dispatches on the extension of `path`: .glb/.gltf (keeping a glTF input's nodes, meshes and materials
// when `inputPath` is one, else a new file from the scene), .ply or .csv.
void writeBakeOutput(const std::string& inputPath, const Scene& scene, const BakeResult& result,
                     const ArtistControls& controls, const std::string& path);

// PLY (binary little-endian): every instance's vertices in world space with float quality (the shade),
// ao_short, ao_long and uchar grey red/green/blue; faces with the file's winding (mirrored instances flipped).
void writeBakedPly(const Scene& scene, const BakeResult& result, const ArtistControls& controls, const std::string& path);

// CSV with a header: index,x,y,z,short,long,blended per instance vertex (world space; blended before the remap).
void writeBakedCsv(const Scene& scene, const BakeResult& result, const ArtistControls& controls, const std::string& path);

} // namespace obscura::bake
