// OpenEXR reading (any channel type, as float) and writing (32-bit float, ZIP), through OpenEXR 3.
#include "obscura/camera.h"
#include "obscura/error.h"
#include "obscura/image_io.h"
#include "obscura/parallel.h"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfStdIO.h>
#include <OpenEXR/ImfThreading.h>
#include <OpenEXR/ImfTiledInputFile.h>
#include <OpenEXR/ImfVersion.h>

#include <algorithm>
#include <cctype>
#include <cassert>
#include <cstdint>
#include <exception>
#include <filesystem>
#include <mutex>
#include <new>
#include <set>
#include <string>
#include <string_view>
#include <system_error>
#include <utility>
#include <vector>

namespace obscura {

namespace {

// A corrupt header can claim any data window; refusing absurd sizes up front keeps a bad file from
// turning into a multi-gigabyte allocation (8 GiB of floats is far beyond any image Obscura makes).
constexpr std::int64_t kMaxValues = std::int64_t(1) << 31;
// The most values one chunk of a file (a tile, or a compression's band of scanlines) may hold, and so the most one
// band of decoding takes beyond a chunk's rows: 256 MiB of floats. A 32768-pixel row of 8 channels in DWAB's
// 256-line chunks is this size.
constexpr std::int64_t kMaxChunkValues = std::int64_t(1) << 26;
constexpr int kBandRows = 256;

// OpenEXR compresses and decompresses a file's chunks on a thread pool of its own, which is empty (every chunk
// on the calling thread) until it is sized. It is sized to the threads the rest of Obscura may use, so that
// --threads bounds it too, and no larger than the hardware's (TBB starts no more workers either); the files are
// the same bytes whatever the count. One thread leaves the pool empty: a single worker would only add hand-offs.
int exrThreads() {
    const int allowed = std::min(allowedThreads(), hardwareThreads());
    const int threads = allowed > 1 ? allowed : 0;
    static std::mutex mutex;
    const std::lock_guard lock(mutex);
    if (Imf::globalThreadCount() != threads) Imf::setGlobalThreadCount(threads);
    return threads;
}

// OpenEXR messages can run to several lines, and most repeat the path we already put in front
// ('Cannot read image file "a.exr". Early end of file ...'); ours are one line that names it once.
std::string openExrProblem(const std::string& path, const char* message) {
    std::string line(message ? message : "");
    line = line.substr(0, line.find('\n'));
    for (const std::string& repeated : {" from image file \"" + path + "\".", " image file \"" + path + "\"."}) {
        if (const std::size_t at = line.find(repeated); at != std::string::npos) {
            line.replace(at, repeated.size(), ":");
            break;
        }
    }
    return line.empty() ? "unknown OpenEXR error" : line;
}

// Without this, OpenEXR's own "cannot open" message repeats the path we already put in front.
void requireRegularFile(const std::string& path) {
    std::error_code ec;
    const auto status = std::filesystem::status(path, ec);
    if (!std::filesystem::exists(status)) fail(path, "no such file");
    if (std::filesystem::is_directory(status)) fail(path, "is a directory, not an image file");
}

int linesPerChunk(Imf::Compression compression) {
    switch (compression) {
    case Imf::NO_COMPRESSION:
    case Imf::RLE_COMPRESSION:
    case Imf::ZIPS_COMPRESSION: return 1;
    case Imf::ZIP_COMPRESSION:
    case Imf::PXR24_COMPRESSION: return 16;
    case Imf::PIZ_COMPRESSION:
    case Imf::B44_COMPRESSION:
    case Imf::B44A_COMPRESSION:
    case Imf::DWAA_COMPRESSION: return 32;
    default: return 256; // DWAB; the largest, so a buffer of this many lines holds any chunk
    }
}

// The bytes one pixel of every channel takes in the file, uncompressed.
std::size_t pixelBytes(const Imf::Header& header) {
    std::size_t bytes = 0;
    for (auto it = header.channels().begin(); it != header.channels().end(); ++it)
        bytes += it.channel().type == Imf::HALF ? 2u : 4u;
    return bytes;
}

// Scanlines a band of decoding should hold a multiple of, so that no chunk is decoded twice: the compression's
// lines per chunk, or a tile's height (a tile row is cached whole, so a taller tile needs no alignment).
std::int64_t bandAlignment(const Imf::Header& header) {
    if (!header.hasTileDescription()) return linesPerChunk(header.compression());
    const unsigned tileHeight = header.tileDescription().ySize;
    return tileHeight <= unsigned(kBandRows) ? std::int64_t(std::max(tileHeight, 1u)) : 1;
}

void checkDataWindow(const std::string& path, const Imf::Header& header) {
    std::size_t channelCount = 0;
    for (auto it = header.channels().begin(); it != header.channels().end(); ++it) ++channelCount;
    const Imath::Box2i& window = header.dataWindow();
    const std::int64_t width = std::int64_t(window.max.x) - window.min.x + 1;
    const std::int64_t height = std::int64_t(window.max.y) - window.min.y + 1;
    const std::string size = std::to_string(width) + "x" + std::to_string(height);
    if (width <= 0 || height <= 0) fail(path, "has an empty data window");
    // Obscura makes no image wider or taller (kMaxImageSide), so no file it reads needs to be.
    if (width > kMaxImageSide || height > kMaxImageSide)
        fail(path, "data window " + size + " is too large (at most " + std::to_string(kMaxImageSide) + "x" +
                       std::to_string(kMaxImageSide) + ")");
    const std::int64_t channels = std::int64_t(std::max<std::size_t>(channelCount, 1));
    if (width * height > kMaxValues / channels)
        fail(path, "data window " + size + " with " + std::to_string(channelCount) + " channels is too large (at most " +
                       std::to_string(kMaxValues) + " values)");
    // A chunk is decoded whole, and a band of decoding holds at least one (bandAlignment's rows), so their size is
    // allocated before any of their data is read: 32768 pixels by 65536 channels is 8 GiB of floats from a header
    // of about 1.4 MB (22 bytes a channel). A tile is decoded as far as it overlaps the data window (a tile taller
    // than the image costs nothing). Each product is at most 256 times kMaxValues, checked above.
    const bool tiled = header.hasTileDescription();
    std::int64_t atATime = std::min<std::int64_t>(bandAlignment(header), height) * width * channels;
    if (tiled)
        atATime = std::max(atATime, std::min<std::int64_t>(header.tileDescription().xSize, width) *
                                        std::min<std::int64_t>(header.tileDescription().ySize, height) * channels);
    if (atATime > kMaxChunkValues) {
        const std::int64_t lines = linesPerChunk(header.compression());
        fail(path, (tiled ? "tiles of " + std::to_string(header.tileDescription().xSize) + "x" +
                                std::to_string(header.tileDescription().ySize) + " pixels"
                          : "chunks of " + std::to_string(lines) + (lines == 1 ? " scanline" : " scanlines")) +
                       " with " + std::to_string(channelCount) + (channelCount == 1 ? " channel" : " channels") +
                       " in a data window of " + size + " take " + std::to_string(atATime) +
                       " values at a time, more than " + std::to_string(kMaxChunkValues));
    }
}

// OpenEXR sizes its line buffers from the header as soon as a file is opened (gigabytes for a forged data
// window), so the header is read once on its own first. One that does not parse is left to InputFile, whose
// message says what is wrong with it.
void checkDataWindowBeforeOpening(const std::string& path) {
    Imf::Header header;
    try {
        Imf::StdIFStream stream(path.c_str());
        char start[8] = {};
        stream.read(start, sizeof start);
        if (!Imf::isImfMagic(start)) return;
        int version = 0;
        for (int i = 7; i >= 4; --i) version = version << 8 | int(static_cast<unsigned char>(start[i]));
        header.readFrom(stream, version);
    } catch (const std::exception&) {
        return;
    }
    checkDataWindow(path, header);
}

// OpenEXR 3.1 decodes a chunk with no data as zeros, so a file whose chunks were emptied reads as a black
// image (or a depth of 0) without a word. No writer stores an empty chunk, nor an uncompressed one of any
// size but its pixels', so those are refused before the band is decoded. Tiled files: checkTiles.
class ChunkCheck {
public:
    ChunkCheck(const std::string& path, const Imf::Header& header, std::int64_t width)
        : path_(path), compression_(header.compression()), lines_(linesPerChunk(compression_)),
          maxY_(header.dataWindow().max.y), rowBytes_(std::size_t(width) * pixelBytes(header)) {
        if (!header.hasTileDescription()) buffer_.resize(rowBytes_ * std::size_t(lines_));
    }

    // Band rows start on a chunk boundary: readExr's bands are whole chunks (bandAlignment).
    void check(Imf::InputFile& file, int firstY, int lastY) {
        if (buffer_.empty()) return;
        for (std::int64_t y = firstY; y <= lastY; y += lines_) {
            int size = int(buffer_.size());
            try {
                file.rawPixelDataToBuffer(int(y), buffer_.data(), size);
            } catch (const std::exception&) {
                return; // a chunk that cannot be read at all is readPixels' to report, in its usual words
            }
            const std::size_t expected = rowBytes_ * std::size_t(std::min<std::int64_t>(lines_, maxY_ - y + 1));
            const bool uncompressed = compression_ == Imf::NO_COMPRESSION;
            if (size <= 0 || (uncompressed && std::size_t(size) != expected))
                fail(path_, "chunk at scanline " + std::to_string(y) + " holds " + std::to_string(size) +
                                " bytes of pixel data, expected " +
                                (uncompressed ? std::to_string(expected) : std::string("at least 1")));
        }
    }

private:
    const std::string& path_;
    Imf::Compression compression_;
    int lines_;
    std::int64_t maxY_;
    std::size_t rowBytes_;
    std::vector<char> buffer_;
};

// An emptied tile is worse than an emptied scanline chunk: OpenEXR 3.1 leaves its pixels as whatever its buffer
// held (an 8x8 file read 1.0327e+35 where a tile had been emptied). So every tile of the full-resolution level is
// held to the scanline chunks' rule before any is decoded: some bytes, and exactly its pixels' if uncompressed.
// rawTileData reads the tiles in file order without decompressing them, on a second handle of the file; a tile
// it cannot read at all is left to readPixels, which says so in OpenEXR's words.
void checkTiles(const std::string& path, const Imf::Header& header) {
    const std::size_t bytes = pixelBytes(header);
    const bool uncompressed = header.compression() == Imf::NO_COMPRESSION;
    Imf::TiledInputFile tiles(path.c_str(), 0);
    std::int64_t count = 0;
    for (int lx = 0; lx < tiles.numXLevels(); ++lx)
        for (int ly = 0; ly < tiles.numYLevels(); ++ly)
            if (tiles.isValidLevel(lx, ly)) count += std::int64_t(tiles.numXTiles(lx)) * tiles.numYTiles(ly);
    for (std::int64_t t = 0; t < count; ++t) {
        int dx = 0, dy = 0, lx = 0, ly = 0, size = 0;
        const char* data = nullptr;
        try {
            tiles.rawTileData(dx, dy, lx, ly, data, size);
        } catch (const std::exception&) {
            return;
        }
        if (lx != 0 || ly != 0) continue;  // the reduced levels are not read
        const Imath::Box2i box = tiles.dataWindowForTile(dx, dy, 0, 0);
        const std::size_t expected =
            std::size_t(box.max.x - box.min.x + 1) * std::size_t(box.max.y - box.min.y + 1) * bytes;
        if (size <= 0 || (uncompressed && std::size_t(size) != expected))
            fail(path, "tile (" + std::to_string(dx) + ", " + std::to_string(dy) + ") holds " + std::to_string(size) +
                           " bytes of pixel data, expected " +
                           (uncompressed ? std::to_string(expected) : std::string("at least 1")));
    }
}

// A channel's layer (its name up to the last '.') and its component's place in the layer: R G B A, then X Y Z,
// then the rest (7, left in name order).
std::pair<std::string, int> layerAndRank(const std::string& name) {
    const std::size_t dot = name.rfind('.');
    const std::size_t start = dot == std::string::npos ? 0 : dot + 1;
    // A component of one letter has a place; any other (and '\0', which the list lacks) has none.
    const char letter = name.size() == start + 1 ? char(std::toupper(static_cast<unsigned char>(name[start]))) : '\0';
    const std::size_t rank = std::string_view("RGBAXYZ").find(letter);
    return {name.substr(0, start == 0 ? 0 : dot), rank == std::string_view::npos ? 7 : int(rank)};
}

// OpenEXR keeps a file's channels sorted by name, whatever order they were written in, so R, G, B come back as
// B, G, R: an environment map lit the scene in swapped colours, and normals named R, G, B swapped x and z. So
// the layers (a name up to its last '.') keep their name order, the base layer first, and within a layer the
// components take their usual order, as OpenEXR's own RGBA interface reads them: R G B A, then X Y Z, then the
// rest by name. What writeExr wrote in that order (every file Obscura writes) reads back in it.
void sortChannelsConventionally(std::vector<std::string>& names) {
    std::stable_sort(names.begin(), names.end(),
                     [](const std::string& a, const std::string& b) { return layerAndRank(a) < layerAndRank(b); });
}

std::vector<std::string> exrChannelNames(const std::string& path, const Image& image) {
    if (image.channelNames.size() == std::size_t(image.channels)) {
        std::set<std::string> seen;
        for (const std::string& name : image.channelNames) {
            if (name.empty()) fail(path, "cannot write an EXR channel with an empty name");
            // OpenEXR keys channels by name, so a duplicate would silently drop data.
            if (!seen.insert(name).second) fail(path, "duplicate channel name '" + name + "'");
        }
        return image.channelNames;
    }
    if (image.channels == 1) return {"Y"};
    if (image.channels <= 4) {
        const std::vector<std::string> rgba = {"R", "G", "B", "A"};
        return {rgba.begin(), rgba.begin() + image.channels};
    }
    fail(path, std::to_string(image.channels) + " channels need channelNames (defaults cover 1 to 4)");
}

} // namespace

namespace {

// readExr, and the file's display and data windows where asked for.
Image readExrWindows(const std::string& path, Imath::Box2i* displayWindow, Imath::Box2i* dataWindow) {
    requireRegularFile(path);
    try {
        checkDataWindowBeforeOpening(path);
        Imf::InputFile file(path.c_str(), exrThreads());
        // InputFile reads the first part of a multi-part file and composites deep samples into one value, both
        // without a word: a depth in part 1 read part 0's channel Y as depth, and two half-transparent samples
        // averaged a depth that no surface has.
        if (Imf::isMultiPart(file.version()))
            fail(path, "is a multi-part EXR, and only single-part files are read (write the buffer as one part)");
        if (Imf::isNonImage(file.version()))
            fail(path, "holds deep data, which is not read (flatten it to a scanline or tiled image of one sample)");
        const Imf::Header& header = file.header();
        const Imath::Box2i window = header.dataWindow();
        if (displayWindow) *displayWindow = header.displayWindow();
        if (dataWindow) *dataWindow = window;
        const std::int64_t width = std::int64_t(window.max.x) - window.min.x + 1;
        const std::int64_t height = std::int64_t(window.max.y) - window.min.y + 1;

        std::vector<std::string> names;
        for (auto it = header.channels().begin(); it != header.channels().end(); ++it) {
            // Subsampled (chroma) channels would need resampling to share one pixel grid.
            if (it.channel().xSampling != 1 || it.channel().ySampling != 1)
                fail(path, "channel '" + std::string(it.name()) + "' is subsampled, which is not supported");
            names.emplace_back(it.name());
        }
        if (names.empty()) fail(path, "has no channels");
        sortChannelsConventionally(names);
        checkDataWindow(path, header);
        ChunkCheck chunks(path, header, width);
        if (header.hasTileDescription()) checkTiles(path, header);

        // Decoding a band at a time means memory grows only with data that actually decodes: a corrupt
        // header claiming a huge window fails on its first band instead of zero-filling gigabytes.
        Image image;
        image.width = int(width);
        image.height = int(height);
        image.channels = int(names.size());
        image.channelNames = names;
        const std::size_t xStride = sizeof(float) * names.size();
        const std::size_t rowValues = std::size_t(width) * names.size();
        // Growing band by band moved the decoded image about twice over (a 3840x2160 RGB read on one thread took
        // 1.39 s, and 0.84 s with its room reserved; docs/PERFORMANCE.md). Room for all of it is taken up front
        // where the file could plausibly hold it: deflate packs at most 1032:1, so a header that claims over 4096
        // times the file's bytes is most likely forged, and is left to grow band by band and fail on its first
        // missing chunk. Either way the same pixels are read; only the copies differ.
        std::error_code sizeError;
        const std::uintmax_t fileBytes = std::filesystem::file_size(path, sizeError);
        const double imageBytes = double(rowValues) * double(height) * sizeof(float);
        if (!sizeError && imageBytes <= double(fileBytes) * 4096.0)
            image.pixels.reserve(rowValues * std::size_t(height));
        // Up to kBandRows, fewer where rows are wide, but whole chunks: a band starts on a chunk boundary.
        const std::int64_t chunk = bandAlignment(header);
        const std::int64_t bandRows =
            std::max<std::int64_t>(chunk, std::min<std::int64_t>(kBandRows, kMaxChunkValues / std::int64_t(rowValues)) /
                                              chunk * chunk);
        for (int y = window.min.y; y <= window.max.y;) {
            const int rows = int(std::min<std::int64_t>(bandRows, std::int64_t(window.max.y) - y + 1));
            chunks.check(file, y, y + rows - 1);
            const std::size_t done = image.pixels.size();
            image.pixels.resize(done + rowValues * std::size_t(rows));
            Imf::FrameBuffer frameBuffer;
            for (std::size_t c = 0; c < names.size(); ++c) {
                // Make() offsets the base pointer by the band's origin, so pixel (min.x, y) lands at done.
                frameBuffer.insert(names[c], Imf::Slice::Make(Imf::FLOAT, image.pixels.data() + done + c,
                                                              Imath::V2i(window.min.x, y), width, rows, xStride,
                                                              xStride * std::size_t(width)));
            }
            file.setFrameBuffer(frameBuffer);
            file.readPixels(y, y + rows - 1);
            y += rows;
        }
        return image;
    } catch (const Error&) {
        throw;
    } catch (const std::bad_alloc&) {
        fail(path, "out of memory");
    } catch (const std::exception& e) {
        fail(path, openExrProblem(path, e.what()));
    }
}

} // namespace

Image readExr(const std::string& path) { return readExrWindows(path, nullptr, nullptr); }

Image readExrFrame(const std::string& path) {
    Imath::Box2i display, window;
    Image data = readExrWindows(path, &display, &window);
    const auto box = [](const Imath::Box2i& b) {
        std::string text = "(";  // appended, not "(" + ...: GCC 12 warns (-Wrestrict) of that falsely
        text += std::to_string(b.min.x) + ", " + std::to_string(b.min.y) + ")-(" + std::to_string(b.max.x) + ", " +
                std::to_string(b.max.y) + ")";
        return text;
    };
    if (!(display == window))
        fail(path, "data window " + box(window) + " is not its display window " + box(display) +
                       ": a G-buffer's pixels must fill the camera's frame");
    return data;
}

Image readExrDisplayWindow(const std::string& path) {
    Imath::Box2i display, window;
    Image data = readExrWindows(path, &display, &window);
    if (display == window) return data;
    const std::int64_t width = std::int64_t(display.max.x) - display.min.x + 1;
    const std::int64_t height = std::int64_t(display.max.y) - display.min.y + 1;
    if (width < 1 || height < 1 || width > kMaxImageSide || height > kMaxImageSide)
        fail(path, "display window is " + std::to_string(width) + "x" + std::to_string(height) + ", outside [1, " +
                       std::to_string(kMaxImageSide) + "] per side");
    // The data window's cap holds for the image made of the display window: a 2 KB file whose display window
    // was 32768x32768 asked for 12.9 GB, beyond any data it holds.
    if (width * height > kMaxValues / std::max<std::int64_t>(data.channels, 1))
        fail(path, "display window " + std::to_string(width) + "x" + std::to_string(height) + " with " +
                       std::to_string(data.channels) + " channels is too large (at most " + std::to_string(kMaxValues) +
                       " values)");
    Image out;
    try {
        out = Image(int(width), int(height), data.channels, 0.0f);
    } catch (const std::bad_alloc&) {
        fail(path, "out of memory for its " + std::to_string(width) + "x" + std::to_string(height) + " display window");
    }
    out.channelNames = data.channelNames;
    for (int y = 0; y < data.height; ++y) {
        const std::int64_t oy = std::int64_t(window.min.y) + y - display.min.y;
        if (oy < 0 || oy >= height) continue;
        for (int x = 0; x < data.width; ++x) {
            const std::int64_t ox = std::int64_t(window.min.x) + x - display.min.x;
            if (ox < 0 || ox >= width) continue;
            for (int c = 0; c < data.channels; ++c) out.at(int(ox), int(oy), c) = data.at(x, y, c);
        }
    }
    return out;
}

void writeExr(const std::string& path, const Image& image) {
    if (image.empty()) fail(path, "image has zero size");
    assert(image.pixels.size() == image.pixelCount() * std::size_t(image.channels));
    const std::vector<std::string> names = exrChannelNames(path, image);

    writeAtomically(path, [&](const std::string& tempPath) {
        try {
            Imf::Header header(image.width, image.height);
            header.compression() = Imf::ZIP_COMPRESSION;
            const std::size_t xStride = sizeof(float) * std::size_t(image.channels);
            Imf::FrameBuffer frameBuffer;
            for (std::size_t c = 0; c < names.size(); ++c) {
                header.channels().insert(names[c], Imf::Channel(Imf::FLOAT));
                // Slice takes a mutable pointer for reading and writing alike; OutputFile only reads it.
                char* base = const_cast<char*>(reinterpret_cast<const char*>(image.pixels.data() + c));
                frameBuffer.insert(names[c], Imf::Slice(Imf::FLOAT, base, xStride,
                                                        xStride * std::size_t(image.width)));
            }
            Imf::OutputFile file(tempPath.c_str(), header, exrThreads());
            file.setFrameBuffer(frameBuffer);
            file.writePixels(image.height);
        } catch (const Error&) {
            throw;
        } catch (const std::exception& e) {
            // Name the target, not the temporary: the temporary is gone by the time anyone reads this.
            fail(path, "cannot write: " + openExrProblem(tempPath, e.what()));
        }
    });
}

} // namespace obscura
