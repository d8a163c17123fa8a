// The glTF 2.0 properties the loader reads (Khronos glTF 2.0 specification, section 5, "Properties
// Reference"), held to their types in the file's JSON: tinygltf reads an index, count or offset only when it is
// a JSON integer and a transform only when it is an array of numbers, and silently keeps the default otherwise,
// so a corrupt or hand-edited file ("byteOffset": 1e10, "translation": "abc") loaded as different geometry.
#pragma once

#include <string>

namespace obscura::loader {

// Throws obscura::Error naming `path` and the first property whose value has the wrong type, e.g.
// "bufferViews[0].byteOffset must be a non-negative integer, got 10000000000.0". The document is the whole
// .gltf, or with `binary` the JSON chunk of a .glb (glTF 2.0, section 4.4 "Binary glTF Layout"), read without
// its binary chunk. Properties the loader never reads are not checked.
void checkGltfJson(const std::string& path, bool binary);

// The JSON text of `path`: the whole .gltf, or with `binary` the JSON chunk of a .glb. Throws obscura::Error
// naming `path` for a file that cannot be read or a .glb header that does not hold its JSON chunk.
std::string readGltfJsonText(const std::string& path, bool binary);

// `text` with the contents of every JSON string that starts with "data:" (a base64 data URI) left out, the quotes
// kept: "uri": "data:...;base64,AAAA" becomes "uri": "". The scan follows the JSON's strings, escapes included,
// so a "data:" inside another string is not taken for one. An unterminated string is copied as it is, with what follows it.
std::string withoutDataUris(const std::string& text);

} // namespace obscura::loader
