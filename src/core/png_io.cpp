// PNG reading and writing and Radiance .hdr reading, both through stb_image / stb_image_write.
#include "obscura/error.h"
#include "obscura/image_io.h"

#include <stb_image.h>
#include <stb_image_write.h>

#include <algorithm>
#include <array>
#include <cassert>
#include <cerrno>
#include <climits>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>
#include <new>
#include <system_error>
#include <vector>

namespace obscura {

namespace {

// The whole file is read once, so the format check and the decode see the same bytes and a missing
// file gets our message rather than stb's terse "can't fopen".
std::vector<unsigned char> readFileBytes(const std::string& path) {
    std::error_code ec;
    const auto status = std::filesystem::status(path, ec);
    if (!std::filesystem::exists(status)) fail(path, "no such file");
    if (std::filesystem::is_directory(status)) fail(path, "is a directory, not an image file");
    std::ifstream in(path, std::ios::binary);
    if (!in) fail(path, "cannot open: " + std::generic_category().message(errno));
    std::vector<unsigned char> bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    if (in.bad()) fail(path, "cannot read: " + std::generic_category().message(errno));
    if (bytes.size() > std::size_t(INT_MAX)) fail(path, "file is too large for the image decoder");
    return bytes;
}

std::string stbReason() {
    // stb sets no reason for some truncations, so an empty one gets the likely cause.
    const char* reason = stbi_failure_reason();
    return reason && *reason ? reason : "corrupt or truncated data";
}

struct StbFree {
    void operator()(void* p) const { stbi_image_free(p); }
};

// stbi_write_png itself ignores fwrite/fclose failures (a full disk would pass), so the encoded bytes
// are written here where every step is checked.
void writeFileBytes(const std::string& path, const std::string& tempPath, const std::vector<unsigned char>& bytes) {
    std::FILE* file = std::fopen(tempPath.c_str(), "wb");
    if (!file) fail(path, "cannot write: " + std::generic_category().message(errno));
    const bool written = std::fwrite(bytes.data(), 1, bytes.size(), file) == bytes.size();
    const int writeErr = errno;
    const bool closed = std::fclose(file) == 0;
    if (!written || !closed) fail(path, "cannot write: " + std::generic_category().message(written ? errno : writeErr));
}

} // namespace

Image readPng(const std::string& path) {
    const std::vector<unsigned char> bytes = readFileBytes(path);
    // stb_image would happily decode a JPEG or BMP here; a .png that is not one is worth saying so.
    static constexpr std::array<unsigned char, 8> signature = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    if (bytes.size() < signature.size() || std::memcmp(bytes.data(), signature.data(), signature.size()) != 0)
        fail(path, "not a PNG file (bad signature)");

    int width = 0, height = 0, channels = 0;
    std::unique_ptr<stbi_uc, StbFree> data(
        stbi_load_from_memory(bytes.data(), int(bytes.size()), &width, &height, &channels, 0));
    if (!data) fail(path, "cannot read PNG: " + stbReason());

    Image image(width, height, channels);
    for (std::size_t i = 0; i < image.pixels.size(); ++i) image.pixels[i] = float(data.get()[i]) / 255.0f;
    return image;
}

Image readHdr(const std::string& path) {
    const std::vector<unsigned char> bytes = readFileBytes(path);
    // stbi_loadf would otherwise accept an 8-bit image and invent linear values through a gamma curve.
    if (!stbi_is_hdr_from_memory(bytes.data(), int(bytes.size())))
        fail(path, "not a Radiance HDR file (missing #?RADIANCE header)");

    int width = 0, height = 0, channels = 0;
    std::unique_ptr<float, StbFree> data(
        stbi_loadf_from_memory(bytes.data(), int(bytes.size()), &width, &height, &channels, 0));
    if (!data) fail(path, "cannot read HDR: " + stbReason());

    Image image(width, height, channels);
    std::copy(data.get(), data.get() + image.pixels.size(), image.pixels.begin());
    return image;
}

void writePng(const std::string& path, const Image& image) {
    if (image.empty()) fail(path, "image has zero size");
    if (image.channels > 4) fail(path, "PNG holds 1 to 4 channels, image has " + std::to_string(image.channels));
    if (image.width > INT_MAX / image.channels) fail(path, "image is too wide for PNG");
    assert(image.pixels.size() == image.pixelCount() * std::size_t(image.channels));

    std::vector<unsigned char> codes(image.pixels.size());
    for (std::size_t i = 0; i < codes.size(); ++i) {
        const float v = image.pixels[i];
        // Written so that NaN fails both tests and becomes 0 instead of undefined in the conversion.
        const float clamped = v > 0.0f ? (v < 1.0f ? v : 1.0f) : 0.0f;
        codes[i] = static_cast<unsigned char>(clamped * 255.0f + 0.5f);
    }

    struct Sink {
        std::vector<unsigned char> bytes;
        bool outOfMemory = false;
    } sink;
    // Called from C: an exception must not unwind through stb, so it is turned into a flag.
    auto append = [](void* context, void* data, int size) {
        auto* out = static_cast<Sink*>(context);
        const auto* bytes = static_cast<const unsigned char*>(data);
        try {
            out->bytes.insert(out->bytes.end(), bytes, bytes + size);
        } catch (const std::bad_alloc&) {
            out->outOfMemory = true;
        }
    };
    if (!stbi_write_png_to_func(append, &sink, image.width, image.height, image.channels, codes.data(),
                                image.width * image.channels) ||
        sink.outOfMemory)
        fail(path, "cannot encode PNG (out of memory)");

    writeAtomically(path, [&](const std::string& tempPath) { writeFileBytes(path, tempPath, sink.bytes); });
}

} // namespace obscura
