// PNG reading and writing through stb_image / stb_image_write, and Radiance .hdr reading (own RGBE
// decoder, see HdrReader).
#include "obscura/camera.h"
#include "obscura/error.h"
#include "obscura/image_io.h"

#include <stb_image.h>
#include <stb_image_write.h>

#include <algorithm>
#include <array>
#include <cassert>
#include <cerrno>
#include <charconv>
#include <climits>
#include <cmath>
#include <cstdint>
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

// CRC-32 as PNG defines it (ISO 3309, polynomial 0xedb88320), of the running value `crc`.
std::uint32_t crc32(const unsigned char* data, std::size_t n, std::uint32_t crc) {
    static const std::array<std::uint32_t, 256> table = [] {
        std::array<std::uint32_t, 256> t{};
        for (std::uint32_t i = 0; i < 256; ++i) {
            std::uint32_t c = i;
            for (int k = 0; k < 8; ++k) c = (c & 1u) ? 0xedb88320u ^ (c >> 1) : c >> 1;
            t[i] = c;
        }
        return t;
    }();
    for (std::size_t i = 0; i < n; ++i) crc = table[(crc ^ data[i]) & 0xffu] ^ (crc >> 8);
    return crc;
}

std::uint32_t bigEndian32(const unsigned char* p) {
    return std::uint32_t(p[0]) << 24 | std::uint32_t(p[1]) << 16 | std::uint32_t(p[2]) << 8 | std::uint32_t(p[3]);
}

// Every chunk's CRC, from the signature to IEND. stb_image checks none (nor zlib's Adler-32): a flipped bit in
// IDAT decoded to other pixels without an error.
void checkPngChunks(const std::string& path, const std::vector<unsigned char>& bytes) {
    for (std::size_t at = 8;;) {
        if (bytes.size() - at < 12)
            fail(path, "cannot read PNG: truncated (a chunk header at byte " + std::to_string(at) + " runs past the end)");
        const std::uint32_t length = bigEndian32(&bytes[at]);
        const std::string type(reinterpret_cast<const char*>(&bytes[at + 4]), 4);
        if (length > bytes.size() - at - 12)
            fail(path, "cannot read PNG: truncated (chunk '" + type + "' at byte " + std::to_string(at) +
                           " runs past the end)");
        const std::uint32_t crc = crc32(&bytes[at + 4], 4 + std::size_t(length), 0xffffffffu) ^ 0xffffffffu;
        if (crc != bigEndian32(&bytes[at + 8 + length]))
            fail(path, "cannot read PNG: chunk '" + type + "' at byte " + std::to_string(at) + " fails its CRC (corrupt file)");
        at += 12 + std::size_t(length);
        if (type == "IEND") return;
    }
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
    checkPngChunks(path, bytes);

    int width = 0, height = 0, channels = 0;
    // The size from the header first: Obscura reads no image larger than kMaxImageSide (camera.h) on a side.
    if (stbi_info_from_memory(bytes.data(), int(bytes.size()), &width, &height, &channels) &&
        (width > kMaxImageSide || height > kMaxImageSide))
        fail(path, "PNG size " + std::to_string(width) + "x" + std::to_string(height) + " is too large (at most " +
                       std::to_string(kMaxImageSide) + " on a side)");
    // A 16-bit PNG is read as 16 bits: stbi_load would cut it to its high byte (0x00FF became 0, not 1/255).
    const auto decode = [&](auto* pixels, float maxValue) {
        std::unique_ptr<std::remove_pointer_t<decltype(pixels)>, StbFree> data(pixels);
        if (!data) fail(path, "cannot read PNG: " + stbReason());
        Image image(width, height, channels);
        for (std::size_t i = 0; i < image.pixels.size(); ++i) image.pixels[i] = float(data.get()[i]) / maxValue;
        return image;
    };
    const int size = int(bytes.size());
    if (stbi_is_16_bit_from_memory(bytes.data(), size))
        return decode(stbi_load_16_from_memory(bytes.data(), size, &width, &height, &channels, 0), 65535.0f);
    Image image = decode(stbi_load_from_memory(bytes.data(), size, &width, &height, &channels, 0), 255.0f);
    return image;
}

namespace {

// Radiance RGBE decoding, written out here because stb_image pads a truncated file with zeros and
// reports success: a cut-off environment map would light a frame black without a word.
class HdrReader {
public:
    HdrReader(const std::string& path, const std::vector<unsigned char>& bytes) : path_(path), bytes_(bytes) {}

    Image read() {
        const std::string magic = line();
        if (magic != "#?RADIANCE" && magic != "#?RGBE") fail(path_, "not a Radiance HDR file (missing #?RADIANCE header)");
        // EXPOSURE and COLORCORR give what the file's values were multiplied by, one line per adjustment
        // (they multiply up); the radiance an environment lights with is the values divided by the product.
        std::array<double, 3> factor{1.0, 1.0, 1.0};
        for (std::string header = line(); !header.empty(); header = line()) {
            if (header.rfind("FORMAT=", 0) == 0 && header != "FORMAT=32-bit_rle_rgbe")
                fail(path_, "unsupported Radiance HDR pixel format '" + header.substr(7) + "' (only 32-bit_rle_rgbe)");
            if (header.rfind("EXPOSURE=", 0) == 0) {
                const double e = headerFactors(header, 1)[0];
                for (double& f : factor) f *= e;
            } else if (header.rfind("COLORCORR=", 0) == 0) {
                const std::array<double, 3> c = headerFactors(header, 3);
                for (std::size_t i = 0; i < 3; ++i) factor[i] *= c[i];
            }
        }
        std::array<float, 3> unscale{};
        for (std::size_t i = 0; i < 3; ++i) {
            unscale[i] = float(1.0 / factor[i]);
            if (!(unscale[i] > 0.0f) || !std::isfinite(unscale[i])) {
                char text[32];
                std::snprintf(text, sizeof text, "%g", factor[i]);
                fail(path_, std::string("Radiance HDR EXPOSURE/COLORCORR lines multiply to ") + text +
                                ", past the float range");
            }
        }
        std::string resolution = line();
        while (!resolution.empty() && (resolution.back() == ' ' || resolution.back() == '\t')) resolution.pop_back();
        int height = 0, width = 0;
        char tail = 0;
        if (std::sscanf(resolution.c_str(), "-Y %d +X %d%c", &height, &width, &tail) != 2)
            fail(path_, "unsupported Radiance HDR resolution line '" + resolution + "' (only '-Y H +X W')");
        if (width <= 0 || height <= 0 || width > (1 << 20) || height > (1 << 20) ||
            std::size_t(width) * std::size_t(height) > (std::size_t(1) << 28))
            fail(path_, "Radiance HDR size " + std::to_string(width) + "x" + std::to_string(height) + " is not plausible");
        // A short header can claim gigabytes of pixels; the least the claim takes on disk is checked before
        // the image is allocated, so a cut-off or forged file costs no more memory than it could describe.
        const std::size_t needed = std::size_t(height) * minScanlineBytes(width);
        if (bytes_.size() - pos_ < needed)
            fail(path_, "truncated Radiance HDR pixel data (" + std::to_string(width) + "x" + std::to_string(height) +
                            " needs at least " + std::to_string(needed) + " bytes, the file has " +
                            std::to_string(bytes_.size() - pos_) + ")");

        Image image(width, height, 3);
        std::vector<unsigned char> scanline(std::size_t(width) * 4);
        for (int y = 0; y < height; ++y) {
            readScanline(scanline, width, y);
            float* out = image.pixels.data() + std::size_t(y) * std::size_t(width) * 3;
            for (int x = 0; x < width; ++x) {
                const unsigned char* rgbe = &scanline[std::size_t(x) * 4];
                const float scale = rgbe[3] ? std::ldexp(1.0f, int(rgbe[3]) - (128 + 8)) : 0.0f;
                for (int c = 0; c < 3; ++c) out[x * 3 + c] = float(rgbe[c]) * scale;
            }
        }
        if (unscale != std::array<float, 3>{1.0f, 1.0f, 1.0f})
            for (std::size_t i = 0; i < image.pixels.size(); ++i) {
                const float stored = image.pixels[i];
                image.pixels[i] *= unscale[i % 3];
                // The file's value is finite; the division by a tiny EXPOSURE is what overflowed, and the message
                // said only "radiance ... is inf".
                if (!std::isfinite(image.pixels[i]))
                    fail(path_, "pixel (" + std::to_string(i / 3 % std::size_t(width)) + ", " +
                                    std::to_string(i / 3 / std::size_t(width)) + ") is " + numberText(stored) +
                                    " as stored; divided by its EXPOSURE/COLORCORR it is past the float range");
            }
        return image;
    }

private:
    // The positive numbers after a header line's '=': one for EXPOSURE, three for COLORCORR.
    std::array<double, 3> headerFactors(const std::string& header, int count) const {
        std::array<double, 3> values{1.0, 1.0, 1.0};
        const std::string text = header.substr(header.find('=') + 1);
        const char* p = text.c_str();
        for (int i = 0; i < count; ++i) {
            while (*p == ' ' || *p == '\t') ++p;
            double v = 0.0;
            const auto [end, error] = std::from_chars(p, text.c_str() + text.size(), v);
            if (error != std::errc() || !(v > 0.0) || !std::isfinite(v))
                fail(path_, "Radiance HDR header '" + header + "' needs " +
                                (count == 1 ? "a positive number" : "three positive numbers"));
            values[std::size_t(i)] = v;
            p = end;
        }
        while (*p == ' ' || *p == '\t' || *p == '\r') ++p;
        if (*p != '\0')
            fail(path_, "Radiance HDR header '" + header + "' needs " +
                            (count == 1 ? "a positive number" : "three positive numbers"));
        return values;
    }

    std::string line() {
        std::string text;
        while (true) {
            if (pos_ >= bytes_.size()) fail(path_, "truncated Radiance HDR header");
            const char c = char(bytes_[pos_++]);
            if (c == '\n') {
                // A file written with CRLF line ends: its magic line read "#?RADIANCE\r", refused as no HDR file.
                if (!text.empty() && text.back() == '\r') text.pop_back();
                return text;
            }
            if (text.size() > 4096) fail(path_, "Radiance HDR header line too long");
            text.push_back(c);
        }
    }

    static bool runLengthWidth(int width) { return width >= 8 && width < 32768; }

    // Flat scanlines take 4 bytes a pixel; run-length ones at least their 4-byte tag and, for each of the four
    // components, one 2-byte run per 127 pixels.
    static std::size_t minScanlineBytes(int width) {
        const std::size_t w = std::size_t(width);
        return runLengthWidth(width) ? 4 + 4 * 2 * ((w + 126) / 127) : 4 * w;
    }

    unsigned char byte(int y) {
        if (pos_ >= bytes_.size()) fail(path_, "truncated Radiance HDR pixel data at scanline " + std::to_string(y));
        return bytes_[pos_++];
    }

    void readScanline(std::vector<unsigned char>& scanline, int width, int y) {
        const bool runLength = runLengthWidth(width) && pos_ + 4 <= bytes_.size() && bytes_[pos_] == 2 &&
                               bytes_[pos_ + 1] == 2 && (bytes_[pos_ + 2] & 0x80) == 0;
        if (!runLength) {
            for (auto& b : scanline) b = byte(y);
            return;
        }
        const int encodedWidth = (bytes_[pos_ + 2] << 8) | bytes_[pos_ + 3];
        if (encodedWidth != width)
            fail(path_, "corrupt Radiance HDR scanline " + std::to_string(y) + " (length " +
                            std::to_string(encodedWidth) + ", expected " + std::to_string(width) + ")");
        pos_ += 4;
        // Each of the four components is stored separately as runs and literal spans.
        for (int c = 0; c < 4; ++c) {
            for (int x = 0; x < width;) {
                int count = byte(y);
                const bool run = count > 128;
                if (run) count -= 128;
                if (count == 0 || x + count > width)
                    fail(path_, "corrupt Radiance HDR run-length data at scanline " + std::to_string(y));
                if (run) {
                    const unsigned char value = byte(y);
                    for (int i = 0; i < count; ++i) scanline[std::size_t(x++) * 4 + std::size_t(c)] = value;
                } else {
                    for (int i = 0; i < count; ++i) scanline[std::size_t(x++) * 4 + std::size_t(c)] = byte(y);
                }
            }
        }
    }

    const std::string& path_;
    const std::vector<unsigned char>& bytes_;
    std::size_t pos_ = 0;
};

} // namespace

Image readHdr(const std::string& path) {
    const std::vector<unsigned char> bytes = readFileBytes(path);
    return HdrReader(path, bytes).read();
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
