// Reading and writing images: OpenEXR (float data), PNG (8-bit pictures), Radiance .hdr (read).
//
// Errors: every function throws obscura::Error naming the file and the problem (missing, unreadable,
// truncated, corrupt, unsupported). Writers write to a temporary file beside the target and rename it,
// so a failed write leaves no partial file and never replaces an existing file with a broken one.
#pragma once

#include "obscura/image.h"

#include <functional>
#include <string>
#include <vector>

namespace obscura {

// Reads .exr, .png or .hdr by extension (case-insensitive). EXR channels come back with their names, layer by
// layer (a name up to its last '.', in name order), and within a layer R G B A, then X Y Z, then the rest by
// name: not the file's own order, which is alphabetical (B G R). PNG values are the code values / 255 (8-bit) or
// / 65535 (16-bit), no colour-space conversion; HDR gives linear RGB.
Image readImage(const std::string& path);

Image readExr(const std::string& path);
// The EXR as its display window frames it, for images whose pixels mean positions in a frame (an
// equirectangular environment): the data window's pixels at their place, 0 outside it, and what lies outside
// the display window (overscan) left out. readExr gives the data window alone, which for a map a compositor
// cropped to its non-black pixels put the sky's rows where the ground's go.
Image readExrDisplayWindow(const std::string& path);
// The EXR whose data window is its display window, for images whose pixels are a camera's frame (a G-buffer);
// fails naming both windows otherwise. readExr dropped an offset data window's position without a word, so a
// depth and a normal buffer could pair up misaligned.
Image readExrFrame(const std::string& path);
// readImage, but an .exr by readExrDisplayWindow: what an environment map is read with.
Image readEnvironmentImage(const std::string& path);
// Writes every channel as 32-bit float. Channel names come from image.channelNames when it has one per
// channel, otherwise R,G,B,A (up to 4) or Y (1 channel).
void writeExr(const std::string& path, const Image& image);

Image readPng(const std::string& path);
// Writes 1, 2, 3 or 4 channels; values are clamped to [0,1] and quantised to 8 bits as they are, so the
// caller applies the sRGB transfer function first for a picture.
void writePng(const std::string& path, const Image& image);

Image readHdr(const std::string& path);

// Lower-case extension with the dot (".exr"), or "" if none.
std::string fileExtension(const std::string& path);

// Runs write(tempPath), then renames tempPath to path. On any exception the temporary is removed and
// the exception rethrown. Used by every writer in the library.
void writeAtomically(const std::string& path, const std::function<void(const std::string& tempPath)>& write);
// Fails as writeAtomically would, before any work, if `path`'s directory takes no new file; leaves nothing.
void checkWritable(const std::string& path);

// Writes files that belong together (an EXR and its camera JSON) all or none: each writer fills a temporary
// beside its file (writeAtomically's name for it), and only once every writer has succeeded are they
// renamed into place. A failed writer removes every temporary and leaves the files that were there as they were;
// its message names the file, not the temporary. Only the renames, one per file, can leave a mix, if one of
// them fails after another succeeded.
struct FileWriter {
    std::string path;
    std::function<void(const std::string& path)> write;
};
void writeFilesTogether(const std::vector<FileWriter>& files);

} // namespace obscura
