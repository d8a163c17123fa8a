// Tests for image_io.h: EXR/PNG/HDR round trips, files written by other writers, errors and atomic writes.
#include "obscura/camera.h"
#include "obscura/error.h"
#include "obscura/image_io.h"
#include "obscura/parallel.h"
#include "obscura/render.h"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfDeepFrameBuffer.h>
#include <OpenEXR/ImfDeepScanLineOutputFile.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfMultiPartOutputFile.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfOutputPart.h>
#include <OpenEXR/ImfPartType.h>
#include <OpenEXR/ImfThreading.h>
#include <OpenEXR/ImfTileDescription.h>
#include <OpenEXR/ImfTiledOutputFile.h>
#include <gtest/gtest.h>

// The test target gets neither stb's nor Imath's include path, so stb comes in by its full name and
// EXR inputs are built byte by byte below (which also keeps them independent of the code under test).
#include <stb/stb_image.h>
#include <stb/stb_image_write.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <limits>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;
using obscura::Image;

constexpr float kInf = std::numeric_limits<float>::infinity();

// Each test gets its own directory, so listing it shows exactly what the code under test left behind.
class ImageIoTest : public ::testing::Test {
protected:
    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir_ = fs::temp_directory_path() /
               ("obscura_image_io_" + std::to_string(getpid()) + "_" + info->test_suite_name() + "_" + info->name());
        fs::remove_all(dir_);
        fs::create_directories(dir_);
    }
    void TearDown() override {
        std::error_code ignored;
        fs::remove_all(dir_, ignored);
    }

    std::string file(const std::string& name) const { return (dir_ / name).string(); }

    std::vector<std::string> listDirectory() const {
        std::vector<std::string> names;
        for (const auto& entry : fs::directory_iterator(dir_)) names.push_back(entry.path().filename().string());
        std::sort(names.begin(), names.end());
        return names;
    }

    void writeBytes(const std::string& path, const std::string& bytes) const {
        std::ofstream out(path, std::ios::binary);
        out << bytes;
        ASSERT_TRUE(out.good()) << path;
    }

    static std::string readBytes(const std::string& path) {
        std::ifstream in(path, std::ios::binary);
        return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    }

    fs::path dir_;
};

// EXPECT_THROW of obscura::Error that also hands back the message for content checks.
std::string thrownMessage(const std::function<void()>& action) {
    std::string message;
    EXPECT_THROW(
        {
            try {
                action();
            } catch (const obscura::Error& e) {
                message = e.what();
                throw;
            }
        },
        obscura::Error);
    return message;
}

void expectMessage(const std::string& message, const std::string& path, const std::string& problem) {
    EXPECT_NE(message.find(path), std::string::npos) << "message does not name the file: " << message;
    EXPECT_NE(message.find(problem), std::string::npos) << "message does not say '" << problem << "': " << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << "message is not one line: " << message;
}

// OpenEXR stores channels sorted by name, so a round trip is compared channel by channel, by name.
int channelIndex(const Image& image, const std::string& name) {
    const auto it = std::find(image.channelNames.begin(), image.channelNames.end(), name);
    return it == image.channelNames.end() ? -1 : int(it - image.channelNames.begin());
}

void expectSameByName(const Image& expected, const Image& actual) {
    ASSERT_EQ(actual.width, expected.width);
    ASSERT_EQ(actual.height, expected.height);
    ASSERT_EQ(actual.channels, expected.channels);
    ASSERT_EQ(actual.channelNames.size(), std::size_t(actual.channels));
    for (int c = 0; c < expected.channels; ++c) {
        const int a = channelIndex(actual, expected.channelNames[std::size_t(c)]);
        ASSERT_GE(a, 0) << "missing channel " << expected.channelNames[std::size_t(c)];
        for (int y = 0; y < expected.height; ++y)
            for (int x = 0; x < expected.width; ++x)
                EXPECT_EQ(actual.at(x, y, a), expected.at(x, y, c)) << "x=" << x << " y=" << y << " c=" << c;
    }
}

// Values that a lossy or half-precision path would change: non-dyadic fractions, a denormal, a huge
// value, negatives and infinities (sky depth is +inf).
float awkwardValue(int x, int y, int c) {
    const float table[] = {0.1f, -1.0f / 3.0f, 1e-40f, 3.0e38f, -0.0f, kInf, -kInf, 123456.789f};
    return table[(x + 3 * y + 5 * c) % 8] + float(x * 1000 + y * 10 + c) * 1e-3f;
}

// ---- hand-made EXR files ------------------------------------------------------------------------
// Just enough of the OpenEXR file layout (openexr.com "OpenEXR File Layout") to write an uncompressed
// single-part scanline file and to read back the header attributes of one.

static_assert(std::endian::native == std::endian::little, "EXR files are little-endian; so is this writer");

template <typename T>
void appendRaw(std::string& out, const T& value) {
    out.append(reinterpret_cast<const char*>(&value), sizeof(T));
}

void appendAttribute(std::string& out, const std::string& name, const std::string& type, const std::string& value) {
    out += name + '\0' + type + '\0';
    appendRaw(out, std::int32_t(value.size()));
    out += value;
}

struct HandChannel {
    std::string name;
    std::int32_t pixelType; // 0 UINT, 1 HALF, 2 FLOAT
    std::string rows;       // per row: width samples, little-endian; rows back to back
};

// Channels must be given in alphabetical order, as OpenEXR keeps them; no compression, one row a chunk.
std::string handMadeExr(int x0, int y0, int width, int height, const std::vector<HandChannel>& channels) {
    std::string header;
    appendRaw(header, std::int32_t(20000630)); // magic
    appendRaw(header, std::int32_t(2));        // version 2, single-part scanline
    std::string chlist;
    for (const HandChannel& c : channels) {
        chlist += c.name + '\0';
        appendRaw(chlist, c.pixelType);
        appendRaw(chlist, std::int32_t(0)); // pLinear and three reserved bytes
        appendRaw(chlist, std::int32_t(1)); // xSampling
        appendRaw(chlist, std::int32_t(1)); // ySampling
    }
    chlist += '\0';
    std::string box;
    for (std::int32_t v : {x0, y0, x0 + width - 1, y0 + height - 1}) appendRaw(box, v);
    std::string one, zeroPair;
    appendRaw(one, 1.0f);
    appendRaw(zeroPair, 0.0f);
    appendRaw(zeroPair, 0.0f);
    appendAttribute(header, "channels", "chlist", chlist);
    appendAttribute(header, "compression", "compression", std::string(1, '\0'));
    appendAttribute(header, "dataWindow", "box2i", box);
    appendAttribute(header, "displayWindow", "box2i", box);
    appendAttribute(header, "lineOrder", "lineOrder", std::string(1, '\0'));
    appendAttribute(header, "pixelAspectRatio", "float", one);
    appendAttribute(header, "screenWindowCenter", "v2f", zeroPair);
    appendAttribute(header, "screenWindowWidth", "float", one);
    header += '\0';

    std::string chunks, offsets;
    const std::uint64_t chunksStart = header.size() + sizeof(std::uint64_t) * std::size_t(height);
    for (int row = 0; row < height; ++row) {
        std::string data;
        for (const HandChannel& c : channels) {
            const std::size_t rowBytes = c.rows.size() / std::size_t(height);
            data += c.rows.substr(rowBytes * std::size_t(row), rowBytes);
        }
        appendRaw(offsets, std::uint64_t(chunksStart + chunks.size()));
        appendRaw(chunks, std::int32_t(y0 + row));
        appendRaw(chunks, std::int32_t(data.size()));
        chunks += data;
    }
    return header + offsets + chunks;
}

// Header attributes of an EXR file: name -> (type, value bytes).
std::map<std::string, std::pair<std::string, std::string>> exrAttributes(const std::string& file) {
    std::map<std::string, std::pair<std::string, std::string>> attributes;
    std::size_t at = 8; // after magic and version
    auto readString = [&] {
        const std::size_t end = file.find('\0', at);
        std::string s = file.substr(at, end - at);
        at = end + 1;
        return s;
    };
    while (at < file.size() && file[at] != '\0') {
        const std::string name = readString();
        const std::string type = readString();
        std::int32_t size = 0;
        std::memcpy(&size, file.data() + at, sizeof(size));
        at += sizeof(size);
        attributes[name] = {type, file.substr(at, std::size_t(size))};
        at += std::size_t(size);
    }
    return attributes;
}

// ---- EXR ----------------------------------------------------------------------------------------

TEST_F(ImageIoTest, ExrRoundTripThreeChannelsIsExactAndKeepsNames) {
    Image image(7, 5, 3);
    image.channelNames = {"R", "G", "B"};
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x)
            for (int c = 0; c < 3; ++c) image.at(x, y, c) = awkwardValue(x, y, c);
    const std::string path = file("rgb.exr");
    obscura::writeExr(path, image);

    const Image back = obscura::readExr(path);
    // The file keeps them alphabetically (B, G, R); they come back in their usual order.
    EXPECT_EQ(back.channelNames, (std::vector<std::string>{"R", "G", "B"}));
    expectSameByName(image, back);
}

TEST_F(ImageIoTest, ExrRoundTripOneChannelDepthKeepsInfinity) {
    Image depth(4, 3, 1);
    depth.channelNames = {"Z"};
    for (int y = 0; y < depth.height; ++y)
        for (int x = 0; x < depth.width; ++x) depth.at(x, y) = 0.25f + float(x) * 1.7f + float(y) * 0.013f;
    depth.at(0, 0) = kInf;
    depth.at(3, 2) = kInf;
    const std::string path = file("depth.exr");
    obscura::writeExr(path, depth);

    const Image back = obscura::readImage(path);
    EXPECT_EQ(back.channelNames, (std::vector<std::string>{"Z"}));
    expectSameByName(depth, back);
    EXPECT_EQ(back.at(0, 0), kInf);
}

// Taller than one read band (256 rows) and not a multiple of it, so band joins and the short last band
// are both crossed.
TEST_F(ImageIoTest, ExrRoundTripTallImageAcrossReadBands) {
    Image image(3, 600, 2);
    image.channelNames = {"U", "V"};
    for (std::size_t i = 0; i < image.pixels.size(); ++i) image.pixels[i] = float(i) * 0.37f - 100.0f;
    const std::string path = file("tall.exr");
    obscura::writeExr(path, image);
    expectSameByName(image, obscura::readExr(path));
}

// OpenEXR's thread pool follows ThreadLimit (empty for one thread, at most the hardware's): one thread and two
// write the same bytes and read the same values.
TEST_F(ImageIoTest, ExrFilesAreTheSameWhateverTheThreads) {
    Image image(301, 517, 3);  // 33 ZIP chunks of 16 lines, the last short; 3 bands of 256 lines
    image.channelNames = {"R", "G", "B"};
    for (std::size_t i = 0; i < image.pixels.size(); ++i) image.pixels[i] = std::sin(float(i) * 0.01f) * float(i % 97);
    std::string bytes[2];
    for (int threads : {1, 2}) {
        const obscura::ThreadLimit limit(threads);
        EXPECT_EQ(obscura::allowedThreads(), threads);
        const std::string path = file("threads" + std::to_string(threads) + ".exr");
        obscura::writeExr(path, image);
        const int pool = std::min(threads, obscura::hardwareThreads());
        EXPECT_EQ(Imf::globalThreadCount(), pool > 1 ? pool : 0) << threads << " threads";
        bytes[threads - 1] = readBytes(path);
        EXPECT_EQ(obscura::readExr(path).pixels, image.pixels) << threads << " threads";
    }
    EXPECT_EQ(bytes[0], bytes[1]);
}

TEST_F(ImageIoTest, ExrDefaultChannelNames) {
    Image gray(2, 2, 1, 0.5f);
    obscura::writeExr(file("y.exr"), gray);
    EXPECT_EQ(obscura::readExr(file("y.exr")).channelNames, (std::vector<std::string>{"Y"}));

    Image rgba(2, 2, 4, 0.5f);
    rgba.channelNames = {"only", "two"}; // not one per channel, so the defaults apply
    obscura::writeExr(file("rgba.exr"), rgba);
    EXPECT_EQ(obscura::readExr(file("rgba.exr")).channelNames, (std::vector<std::string>{"R", "G", "B", "A"}));
}

// The file keeps its channels alphabetically; they are read layer by layer in their usual order, so that the
// first three of an RGB file are R, G, B (an environment map) and of an XYZ one X, Y, Z (a normal buffer).
TEST_F(ImageIoTest, ExrChannelsComeBackInTheirUsualOrder) {
    const std::vector<std::pair<std::vector<std::string>, std::vector<std::string>>> cases = {
        // written as, read as
        {{"B", "G", "R"}, {"R", "G", "B"}},
        {{"Z", "A", "b", "g", "r"}, {"r", "g", "b", "A", "Z"}},
        {{"Z", "Y", "X"}, {"X", "Y", "Z"}},
        // The combined G-buffer: the base layer, then N, then albedo, each in component order.
        {{"albedo.B", "N.Z", "Z", "albedo.R", "N.X", "albedo.G", "N.Y"},
         {"Z", "N.X", "N.Y", "N.Z", "albedo.R", "albedo.G", "albedo.B"}},
        // Components without a usual order follow, by name; a layer's own name may hold dots.
        {{"view.diffuse.G", "id", "view.diffuse.R", "mask", "Y"}, {"Y", "id", "mask", "view.diffuse.R", "view.diffuse.G"}},
        {{"V", "U"}, {"U", "V"}},
    };
    for (const auto& [written, read] : cases) {
        Image image(3, 2, int(written.size()));
        image.channelNames = written;
        for (std::size_t i = 0; i < image.pixels.size(); ++i) image.pixels[i] = float(i);
        obscura::writeExr(file("order.exr"), image);
        const Image back = obscura::readExr(file("order.exr"));
        EXPECT_EQ(back.channelNames, read);
        expectSameByName(image, back);
    }
}

TEST_F(ImageIoTest, ExrIsWrittenAsZipCompressedFloat) {
    Image image(3, 2, 2, 1.0f);
    image.channelNames = {"U", "V"};
    obscura::writeExr(file("zip.exr"), image);

    const auto attributes = exrAttributes(readBytes(file("zip.exr")));
    ASSERT_EQ(attributes.count("compression"), 1u);
    EXPECT_EQ(attributes.at("compression").second, std::string(1, '\3')); // ZIP_COMPRESSION
    ASSERT_EQ(attributes.count("channels"), 1u);
    std::string expectedChannels;
    for (const char* name : {"U", "V"}) {
        expectedChannels += std::string(name) + '\0';
        for (std::int32_t v : {2, 0, 1, 1}) appendRaw(expectedChannels, v); // FLOAT, pLinear 0, sampling 1x1
    }
    EXPECT_EQ(attributes.at("channels").second, expectedChannels + '\0');
}

// A 3x2 file whose data window starts at (10, 20), with two HALF channels and one UINT channel,
// uncompressed and made by hand, so the expected floats are known bit for bit.
TEST_F(ImageIoTest, ExrReadsHalfAndUintChannelsAndHonoursDataWindow) {
    constexpr int width = 3, height = 2, x0 = 10, y0 = 20;
    // {half bits, value}: 1, 0.5, -2, 65504 (largest half), 2^-24 (smallest denormal), +inf.
    const std::uint16_t gBits[height][width] = {{0x3C00, 0x3800, 0xC000}, {0x7BFF, 0x0001, 0x7C00}};
    const float gValues[height][width] = {{1.0f, 0.5f, -2.0f}, {65504.0f, std::ldexp(1.0f, -24), kInf}};
    const std::uint16_t rBits[height][width] = {{0x3555, 0x0000, 0x8000}, {0x6400, 0xBC00, 0x3400}};
    const float rValues[height][width] = {{0.333251953125f, 0.0f, -0.0f}, {1024.0f, -1.0f, 0.25f}};
    // UINT converts to float; these are exact in float (4e9 = 15625000 * 2^8).
    const std::uint32_t idValues[height][width] = {{0, 7, 4000000000u}, {123, 16777216u, 1}};

    auto raw = [](const auto& table) { return std::string(reinterpret_cast<const char*>(table), sizeof(table)); };
    const std::string path = file("half.exr");
    writeBytes(path, handMadeExr(x0, y0, width, height,
                                 {{"G", 1, raw(gBits)}, {"R", 1, raw(rBits)}, {"id", 0, raw(idValues)}}));

    const Image image = obscura::readExr(path);
    ASSERT_EQ(image.width, width);
    ASSERT_EQ(image.height, height);
    ASSERT_EQ(image.channelNames, (std::vector<std::string>{"R", "G", "id"}));
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            EXPECT_EQ(image.at(x, y, 1), gValues[y][x]) << x << "," << y;
            EXPECT_EQ(image.at(x, y, 0), rValues[y][x]) << x << "," << y;
            EXPECT_EQ(image.at(x, y, 2), float(idValues[y][x])) << x << "," << y;
        }
    }
    EXPECT_TRUE(std::signbit(image.at(2, 0, 0))); // -0 survives
}

// Files that belong together are written all or none: a writer that fails leaves the files that were there as
// they were and no temporary, and its message names the file (gbuffer once removed, on a failed camera.json,
// the EXR it had already replaced).
TEST_F(ImageIoTest, FilesWrittenTogetherAreAllOrNone) {
    writeBytes(file("a.exr"), "old a");
    writeBytes(file("b.json"), "old b");
    const Image image(2, 2, 1, 0.5f);
    const std::string message = thrownMessage([&] {
        obscura::writeFilesTogether({{file("a.exr"), [&](const std::string& p) { obscura::writeExr(p, image); }},
                                     {file("b.json"), [&](const std::string& p) { obscura::fail(p, "no room"); }}});
    });
    EXPECT_EQ(message, file("b.json") + ": no room");
    EXPECT_EQ(readBytes(file("a.exr")), "old a");
    EXPECT_EQ(readBytes(file("b.json")), "old b");
    for (const auto& e : std::filesystem::directory_iterator(dir_))
        EXPECT_EQ(e.path().filename().string().find(".tmp-"), std::string::npos) << e.path();
    obscura::writeFilesTogether({{file("a.exr"), [&](const std::string& p) { obscura::writeExr(p, image); }},
                                 {file("b.json"), [&](const std::string& p) { writeBytes(p, "new b"); }}});
    EXPECT_EQ(obscura::readExr(file("a.exr")).pixels, image.pixels);
    EXPECT_EQ(readBytes(file("b.json")), "new b");
}

// A multi-part file was read as its first part, and a deep one as its samples composited, both without a word:
// a depth in part 1 read part 0's channel Y as depth (AO 1 everywhere), and two half-transparent samples gave a
// depth no surface has. Both are refused, naming the file.
TEST_F(ImageIoTest, MultiPartAndDeepExrAreRefused) {
    constexpr int w = 4, h = 3;
    std::vector<float> values(std::size_t(w) * h, 2.0f);
    const std::string multi = file("multi.exr");
    {
        std::vector<Imf::Header> headers;
        for (const char* channel : {"Y", "Z"}) {
            Imf::Header header(w, h);
            header.setName(std::string("part ") + channel);
            header.setType(Imf::SCANLINEIMAGE);
            header.channels().insert(channel, Imf::Channel(Imf::FLOAT));
            headers.push_back(header);
        }
        Imf::MultiPartOutputFile out(multi.c_str(), headers.data(), 2);
        for (int part = 0; part < 2; ++part) {
            Imf::OutputPart output(out, part);
            Imf::FrameBuffer frame;
            frame.insert(part == 0 ? "Y" : "Z", Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(values.data()),
                                                           sizeof(float), sizeof(float) * w));
            output.setFrameBuffer(frame);
            output.writePixels(h);
        }
    }
    expectMessage(thrownMessage([&] { obscura::readExr(multi); }), multi, "is a multi-part EXR");
    const std::string deep = file("deep.exr");
    {
        Imf::Header header(w, h);
        header.setType(Imf::DEEPSCANLINE);
        header.compression() = Imf::ZIPS_COMPRESSION;
        header.channels().insert("Z", Imf::Channel(Imf::FLOAT));
        header.channels().insert("A", Imf::Channel(Imf::FLOAT));
        std::vector<unsigned> counts(std::size_t(w) * h, 1);
        std::vector<float> z(std::size_t(w) * h, 2.0f), a(std::size_t(w) * h, 1.0f);
        std::vector<float*> zp, ap;
        for (std::size_t i = 0; i < z.size(); ++i) {
            zp.push_back(&z[i]);
            ap.push_back(&a[i]);
        }
        Imf::DeepFrameBuffer frame;
        frame.insertSampleCountSlice(
            Imf::Slice(Imf::UINT, reinterpret_cast<char*>(counts.data()), sizeof(unsigned), sizeof(unsigned) * w));
        frame.insert("Z", Imf::DeepSlice(Imf::FLOAT, reinterpret_cast<char*>(zp.data()), sizeof(float*),
                                         sizeof(float*) * w, sizeof(float)));
        frame.insert("A", Imf::DeepSlice(Imf::FLOAT, reinterpret_cast<char*>(ap.data()), sizeof(float*),
                                         sizeof(float*) * w, sizeof(float)));
        Imf::DeepScanLineOutputFile out(deep.c_str(), header);
        out.setFrameBuffer(frame);
        out.writePixels(h);
    }
    expectMessage(thrownMessage([&] { obscura::readExr(deep); }), deep, "holds deep data");
}

// An environment's pixels are positions in its panorama, which the display window frames: a map cropped to
// its non-black rows (display 64x32, data rows 0-15, the sky at 1) was read as the data window alone, 64x16,
// and lit the ground as the sky (E(down) = pi, for 0). Read into the display window it is the full-frame map:
// the same irradiance, to float rounding. Overscan (a data window past the display window) is cut off.
TEST_F(ImageIoTest, EnvironmentsAreReadInTheirDisplayWindow) {
    auto write = [&](const std::string& name, Imath::Box2i display, Imath::Box2i data) {
        Imf::Header header(display, data);
        const int w = data.max.x - data.min.x + 1, h = data.max.y - data.min.y + 1;
        std::vector<float> values(std::size_t(w) * std::size_t(h));
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) values[std::size_t(y) * std::size_t(w) + std::size_t(x)] = float(data.min.y + y < 16);
        Imf::FrameBuffer frame;
        for (const char* c : {"R", "G", "B"}) {
            header.channels().insert(c, Imf::Channel(Imf::FLOAT));
            // OpenEXR addresses a slice from the window's origin: base = first pixel - origin.
            char* base = reinterpret_cast<char*>(values.data()) -
                         (std::ptrdiff_t(data.min.y) * w + data.min.x) * std::ptrdiff_t(sizeof(float));
            frame.insert(c, Imf::Slice(Imf::FLOAT, base, sizeof(float), sizeof(float) * std::size_t(w)));
        }
        Imf::OutputFile out(file(name).c_str(), header);
        out.setFrameBuffer(frame);
        out.writePixels(h);
        return file(name);
    };
    Image full(64, 32, 3, 0.0f);
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 64; ++x)
            for (int c = 0; c < 3; ++c) full.at(x, y, c) = 1.0f;
    const obscura::render::SH9 reference = obscura::render::projectEnvironment(full);
    const obscura::Vec3 up{0, 1, 0}, down{0, -1, 0};
    const std::string cropped = write("cropped.exr", Imath::Box2i({0, 0}, {63, 31}), Imath::Box2i({0, 0}, {63, 15}));
    EXPECT_EQ(obscura::readExr(cropped).height, 16);  // readExr: the data window, as before
    const Image env = obscura::readEnvironmentImage(cropped);
    ASSERT_EQ(env.width, 64);
    ASSERT_EQ(env.height, 32);
    const obscura::render::SH9 sh = obscura::render::projectEnvironment(env);
    EXPECT_NEAR(obscura::render::irradiance(sh, up).x, obscura::render::irradiance(reference, up).x, 1e-5f);
    EXPECT_NEAR(obscura::render::irradiance(sh, down).x, obscura::render::irradiance(reference, down).x, 1e-5f);
    EXPECT_LT(obscura::render::irradiance(sh, down).x, 0.05f);
    // Overscan: 4 pixels past every edge of the display window, left out.
    const std::string overscan = write("overscan.exr", Imath::Box2i({0, 0}, {63, 31}), Imath::Box2i({-4, -4}, {67, 35}));
    const Image o = obscura::readEnvironmentImage(overscan);
    ASSERT_EQ(o.width, 64);
    ASSERT_EQ(o.height, 32);
    EXPECT_EQ(o.pixels, full.pixels);
    // A display window past the values' cap, around a 64x16 data window: 32768x32768x3 once asked for 12.9 GB.
    const std::string huge = write("huge_display.exr", Imath::Box2i({0, 0}, {32767, 32767}), Imath::Box2i({0, 0}, {63, 15}));
    expectMessage(thrownMessage([&] { obscura::readEnvironmentImage(huge); }), huge,
                  "display window 32768x32768 with 3 channels is too large (at most 2147483648 values)");
}

// A header-only file claiming a data window of 8388608x256 (2^31 floats, 8 GiB) once had a whole band sized
// before any pixel was decoded; the camera's 32768 a side now bounds it before OpenEXR opens the file.
TEST_F(ImageIoTest, ExrHugeDataWindowIsRefusedBeforeAllocating) {
    const std::string huge = file("huge.exr");
    writeBytes(huge, handMadeExr(0, 0, 8388608, 256, {{"Z", 2, ""}}));
    EXPECT_LT(fs::file_size(huge), 8192u);
    expectMessage(thrownMessage([&] { obscura::readExr(huge); }), huge,
                  "data window 8388608x256 is too large (at most 32768x32768)");

    // One row made, then its data window stretched to 32769 rows: the header alone must stop it.
    std::string tallBytes = handMadeExr(0, -5, 1, 1, {{"Z", 2, ""}});
    std::string window = std::string("dataWindow\0box2i\0", 17);
    appendRaw(window, std::int32_t(16));
    const std::size_t at = tallBytes.find(window);
    ASSERT_NE(at, std::string::npos);
    const std::int32_t maxY = -5 + 32769 - 1;
    std::memcpy(tallBytes.data() + at + window.size() + 12, &maxY, sizeof maxY);
    const std::string tall = file("tall.exr");
    writeBytes(tall, tallBytes);
    expectMessage(thrownMessage([&] { obscura::readImage(tall); }), tall,
                  "data window 1x32769 is too large (at most 32768x32768)");

    // The limit itself is readable.
    Image widest(32768, 1, 1);
    widest.pixels.back() = 7.0f;
    obscura::writeExr(file("widest.exr"), widest);
    const Image back = obscura::readExr(file("widest.exr"));
    EXPECT_EQ(back.width, 32768);
    EXPECT_EQ(back.pixels.back(), 7.0f);
}

// The whole window within 2^31 values, but one row of it 2^27: a chunk of that size was allocated (twice: the
// chunk check's buffer and the band) before its missing data was noticed. 4096 channels make a header of 90 kB.
TEST_F(ImageIoTest, ExrChunkOfTooManyValuesIsRefusedBeforeAllocating) {
    std::vector<HandChannel> many;
    for (int c = 0; c < 4096; ++c) {
        char name[8];
        std::snprintf(name, sizeof name, "c%04d", c);  // alphabetical, as the helper needs
        many.push_back({name, 1, ""});
    }
    const std::string wide = file("wide.exr");
    writeBytes(wide, handMadeExr(0, 0, 32768, 1, many));
    EXPECT_LT(fs::file_size(wide), 200000u);
    expectMessage(thrownMessage([&] { obscura::readExr(wide); }), wide,
                  "chunks of 1 scanline with 4096 channels in a data window of 32768x1 take 134217728 values at a "
                  "time, more than 67108864");

    // Half as many channels is the limit itself: refused only for its missing pixels.
    many.resize(2048);
    writeBytes(wide, handMadeExr(0, 0, 32768, 1, many));
    expectMessage(thrownMessage([&] { obscura::readExr(wide); }), wide,
                  "chunk at scanline 0 holds 0 bytes of pixel data, expected 134217728");
}

// Obscura writes scanline files, but other tools write tiles, and a tiled file is read a row of tiles at a time:
// the bands follow the tiles' height, and a tile's size is bounded like a chunk's.
// A tiled file of `width` x `height` single-channel pixels holding 0, 1, 2, ... in row order, as other tools
// write them (Obscura writes scanlines). With MIPMAP_LEVELS the reduced levels hold copies of the first pixels.
void writeTiledExr(const std::string& path, int width, int height, int tileWidth, int tileHeight,
                   Imf::Compression compression = Imf::ZIP_COMPRESSION, Imf::LevelMode levels = Imf::ONE_LEVEL) {
    Imf::Header header(width, height);
    header.compression() = compression;
    header.channels().insert("Y", Imf::Channel(Imf::FLOAT));
    header.setTileDescription(Imf::TileDescription(unsigned(tileWidth), unsigned(tileHeight), levels));
    std::vector<float> values(std::size_t(width) * std::size_t(height));
    for (std::size_t i = 0; i < values.size(); ++i) values[i] = float(i);
    Imf::TiledOutputFile out(path.c_str(), header);
    Imf::FrameBuffer frameBuffer;
    frameBuffer.insert("Y", Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(values.data()), sizeof(float),
                                       sizeof(float) * std::size_t(width)));
    out.setFrameBuffer(frameBuffer);
    for (int level = 0; level < out.numLevels(); ++level)
        out.writeTiles(0, out.numXTiles(level) - 1, 0, out.numYTiles(level) - 1, level);
}

// Obscura writes scanline files, but other tools write tiles, and a tiled file is read a row of tiles at a time:
// the bands follow the tiles' height, and a tile's size is bounded like a chunk's.
TEST_F(ImageIoTest, ExrTiledFilesAreReadAndTheirTileSizeBounded) {
    // 517 rows: the last band a partial row of tiles; then one tile taller than the image.
    for (const auto& [tileWidth, tileHeight] : {std::pair{64, 64}, std::pair{300, 700}}) {
        const std::string path = file("tiled.exr");
        writeTiledExr(path, 300, 517, tileWidth, tileHeight);
        const Image image = obscura::readExr(path);
        ASSERT_EQ(image.width, 300);
        ASSERT_EQ(image.height, 517);
        ASSERT_EQ(image.channels, 1);
        for (std::size_t i = 0; i < image.pixels.size(); ++i)
            ASSERT_EQ(image.pixels[i], float(i)) << "tiles " << tileWidth << "x" << tileHeight << ", value " << i;
    }
    // An 8x8 image in one 8192x16384 tile: decoded as far as the image reaches, so it is read.
    writeTiledExr(file("big-tile.exr"), 8, 8, 8192, 16384);
    EXPECT_EQ(obscura::readExr(file("big-tile.exr")).pixels.back(), 63.0f);

    // A header whose tile rows are 2^30 values (the file as OpenEXR leaves it when no tile is written): refused
    // from the header alone.
    const std::string wide = file("wide-tiles.exr");
    {
        Imf::Header header(32768, 8);
        for (int c = 0; c < 4096; ++c) {
            char name[8];
            std::snprintf(name, sizeof name, "c%04d", c);
            header.channels().insert(name, Imf::Channel(Imf::HALF));
        }
        header.setTileDescription(Imf::TileDescription(64, 64, Imf::ONE_LEVEL));
        Imf::TiledOutputFile out(wide.c_str(), header);
    }
    EXPECT_LT(fs::file_size(wide), 1000000u);
    expectMessage(thrownMessage([&] { obscura::readExr(wide); }), wide,
                  "tiles of 64x64 pixels with 4096 channels in a data window of 32768x8 take 1073741824 values at a "
                  "time, more than 67108864");
}

// An emptied tile read as whatever OpenEXR's buffer held (1.0327e+35 where 4 was written): each tile is held to
// the scanline chunks' rule. A mipmapped file's reduced levels are skipped, and its full level read.
TEST_F(ImageIoTest, ExrTileWithoutItsPixelDataIsAnError) {
    writeTiledExr(file("mip.exr"), 8, 8, 4, 4, Imf::ZIP_COMPRESSION, Imf::MIPMAP_LEVELS);
    const Image mip = obscura::readExr(file("mip.exr"));
    ASSERT_EQ(mip.pixels.size(), 64u);
    for (std::size_t i = 0; i < 64; ++i) ASSERT_EQ(mip.pixels[i], float(i));

    for (const auto& [compression, expected] : {std::pair{Imf::NO_COMPRESSION, std::string("expected 64")},
                                                std::pair{Imf::ZIP_COMPRESSION, std::string("expected at least 1")}}) {
        writeTiledExr(file("tiles.exr"), 8, 8, 4, 4, compression);
        std::string bytes = readBytes(file("tiles.exr"));
        ASSERT_EQ(obscura::readExr(file("tiles.exr")).pixels.back(), 63.0f);
        // Tile (1, 0) of level (0, 0): its chunk opens with those four numbers, then its data's size.
        std::string opening;
        for (std::int32_t v : {1, 0, 0, 0}) appendRaw(opening, v);
        const std::size_t at = bytes.find(opening);
        ASSERT_NE(at, std::string::npos);
        const std::int32_t zero = 0;
        std::memcpy(bytes.data() + at + opening.size(), &zero, sizeof zero);
        writeBytes(file("emptied.exr"), bytes);
        expectMessage(thrownMessage([&] { obscura::readExr(file("emptied.exr")); }), file("emptied.exr"),
                      "tile (1, 0) holds 0 bytes of pixel data, " + expected);
    }
    // An uncompressed tile cut short.
    writeTiledExr(file("tiles.exr"), 8, 8, 4, 4, Imf::NO_COMPRESSION);
    std::string bytes = readBytes(file("tiles.exr"));
    std::string opening;
    for (std::int32_t v : {1, 1, 0, 0, 64}) appendRaw(opening, v);
    const std::size_t at = bytes.find(opening);
    ASSERT_NE(at, std::string::npos);
    const std::int32_t half = 32;
    std::memcpy(bytes.data() + at + 16, &half, sizeof half);
    writeBytes(file("short.exr"), bytes);
    expectMessage(thrownMessage([&] { obscura::readExr(file("short.exr")); }), file("short.exr"),
                  "tile (1, 1) holds 32 bytes of pixel data, expected 64");
}

// OpenEXR 3.1 decodes a chunk without data as zeros; a depth or environment map emptied that way must not
// read as a valid all-zero image.
TEST_F(ImageIoTest, ExrChunkWithoutItsPixelDataIsAnError) {
    const std::string rows = std::string(reinterpret_cast<const char*>(std::array<float, 6>{1, 2, 3, 4, 5, 6}.data()),
                                         6 * sizeof(float));
    writeBytes(file("good.exr"), handMadeExr(0, 20, 3, 2, {{"Y", 2, rows}}));
    EXPECT_EQ(obscura::readExr(file("good.exr")).pixels, (std::vector<float>{1, 2, 3, 4, 5, 6}));

    const std::string empty = file("empty.exr");
    writeBytes(empty, handMadeExr(0, 20, 3, 2, {{"Y", 2, ""}}));
    expectMessage(thrownMessage([&] { obscura::readExr(empty); }), empty,
                  "chunk at scanline 20 holds 0 bytes of pixel data, expected 12");

    const std::string shortRows = file("short.exr");
    writeBytes(shortRows, handMadeExr(0, 20, 3, 2, {{"Y", 2, rows.substr(0, 16)}}));
    expectMessage(thrownMessage([&] { obscura::readExr(shortRows); }), shortRows,
                  "chunk at scanline 20 holds 8 bytes of pixel data, expected 12");

    // The same emptied file marked RLE-compressed: no compressor writes an empty chunk either.
    std::string rle = handMadeExr(0, 20, 3, 2, {{"Y", 2, ""}});
    const std::string compression = std::string("compression\0compression\0", 24) + std::string("\1\0\0\0", 4);
    const std::size_t at = rle.find(compression);
    ASSERT_NE(at, std::string::npos);
    rle[at + compression.size()] = '\1'; // RLE_COMPRESSION
    writeBytes(file("rle.exr"), rle);
    expectMessage(thrownMessage([&] { obscura::readExr(file("rle.exr")); }), file("rle.exr"),
                  "chunk at scanline 20 holds 0 bytes of pixel data, expected at least 1");
}

// ---- PNG and HDR --------------------------------------------------------------------------------

TEST_F(ImageIoTest, PngRoundTripIsExactForEightBitValues) {
    for (int channels = 1; channels <= 4; ++channels) {
        Image image(16, 17, channels);
        for (std::size_t i = 0; i < image.pixels.size(); ++i) image.pixels[i] = float((i * 37 + 11) % 256) / 255.0f;
        image.pixels[0] = 0.0f;
        image.pixels[1] = 1.0f;
        const std::string path = file("rt" + std::to_string(channels) + ".png");
        obscura::writePng(path, image);

        const Image back = obscura::readPng(path);
        ASSERT_EQ(back.width, image.width);
        ASSERT_EQ(back.height, image.height);
        ASSERT_EQ(back.channels, channels);
        for (std::size_t i = 0; i < image.pixels.size(); ++i)
            ASSERT_EQ(back.pixels[i], image.pixels[i]) << "channels=" << channels << " i=" << i;
    }
}

TEST_F(ImageIoTest, PngWriteClampsAndRoundsToNearest) {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    // in -> expected 8-bit code: clamped below and above, NaN to 0, nearest code either side of a half.
    const std::vector<std::pair<float, int>> cases = {
        {-1.0f, 0}, {2.0f, 255}, {kInf, 255}, {-kInf, 0}, {nan, 0}, {100.4f / 255.0f, 100}, {100.6f / 255.0f, 101}};
    Image image(int(cases.size()), 1, 1);
    for (std::size_t i = 0; i < cases.size(); ++i) image.pixels[i] = cases[i].first;
    obscura::writePng(file("clamp.png"), image);
    const Image back = obscura::readImage(file("clamp.png"));
    for (std::size_t i = 0; i < cases.size(); ++i)
        EXPECT_EQ(back.pixels[i], float(cases[i].second) / 255.0f) << "input " << cases[i].first;
}

TEST_F(ImageIoTest, HdrReadsFileWrittenByStb) {
    constexpr int width = 5, height = 4;
    // RGBE shares one exponent per pixel and stb truncates the mantissas, so a component v of a pixel
    // whose largest is m comes back within (m / v) / 128 relative: components stay within 15% of each
    // other (error under 0.92%) while pixels span 0.01 to about 2000.
    std::vector<float> rgb;
    for (int p = 0; p < width * height; ++p) {
        const float base = 0.01f * std::pow(1.9f, float(p));
        for (float ratio : {1.0f, 0.95f, 0.85f}) rgb.push_back(base * ratio);
    }
    const std::string path = file("sky.hdr");
    ASSERT_NE(stbi_write_hdr(path.c_str(), width, height, 3, rgb.data()), 0);

    const Image image = obscura::readImage(path);
    ASSERT_EQ(image.width, width);
    ASSERT_EQ(image.height, height);
    ASSERT_EQ(image.channels, 3);
    for (std::size_t i = 0; i < rgb.size(); ++i) EXPECT_NEAR(image.pixels[i], rgb[i], 0.01f * rgb[i]) << i;
}

// Our RGBE decoder against stb's on a file stb wrote with run-length scanlines (width >= 8): the two
// implementations must agree bit for bit.
TEST_F(ImageIoTest, HdrRunLengthScanlinesMatchStbDecoder) {
    constexpr int width = 37, height = 6;
    std::vector<float> rgb;
    for (int p = 0; p < width * height; ++p) {
        // Runs of equal pixels and literal spans both occur, so both RLE branches are exercised.
        const float v = (p / 5) % 2 ? 0.25f : 0.001f * float(p * p % 997);
        for (float ratio : {1.0f, 0.5f, 2.0f}) rgb.push_back(v * ratio);
    }
    const std::string path = file("wide.hdr");
    ASSERT_NE(stbi_write_hdr(path.c_str(), width, height, 3, rgb.data()), 0);

    int w = 0, h = 0, c = 0;
    float* reference = stbi_loadf(path.c_str(), &w, &h, &c, 3);
    ASSERT_NE(reference, nullptr);
    const Image image = obscura::readHdr(path);
    ASSERT_EQ(image.width, width);
    ASSERT_EQ(image.height, height);
    ASSERT_EQ(image.channels, 3);
    for (std::size_t i = 0; i < image.pixels.size(); ++i) EXPECT_EQ(image.pixels[i], reference[i]) << i;
    stbi_image_free(reference);
}

// Every cut of a flat and of a run-length file is an error naming the file, never a silently black map.
TEST_F(ImageIoTest, TruncatedHdrIsAnErrorAtEveryLength) {
    for (int width : {4, 16}) {
        std::vector<float> rgb(std::size_t(width) * 3 * 3, 0.5f);
        for (std::size_t i = 0; i < rgb.size(); ++i) rgb[i] = 0.01f * float(i % 17);
        const std::string path = file("cut.hdr");
        ASSERT_NE(stbi_write_hdr(path.c_str(), width, 3, 3, rgb.data()), 0);
        const std::string bytes = readBytes(path);
        for (std::size_t size = 0; size < bytes.size(); ++size) {
            writeBytes(path, bytes.substr(0, size));
            const std::string message = thrownMessage([&] { obscura::readHdr(path); });
            EXPECT_EQ(message.rfind(path, 0), 0u) << "width " << width << ", " << size << " bytes: " << message;
        }
    }
}

// A 2 KB file whose header claims 16384x16384 once had 3 GiB allocated before the data ran out.
TEST_F(ImageIoTest, HdrClaimingMorePixelsThanItHoldsIsRefusedBeforeAllocating) {
    const std::string path = file("claims.hdr");
    std::string bytes = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 16384 +X 16384\n";
    while (bytes.size() < 2048) bytes += std::string("\x02\x02\x40\x00\xff\x01", 6);
    bytes.resize(2048);
    writeBytes(path, bytes);
    // 16384 rows of at least 4 + 4 * 2 * ceil(16384 / 127) = 1044 bytes, after a 53-byte header.
    expectMessage(thrownMessage([&] { obscura::readHdr(path); }), path,
                  "truncated Radiance HDR pixel data (16384x16384 needs at least 17104896 bytes, the file has 1995)");
}

// The bound is the least a scanline can take, not more: stb writes a constant 254-pixel row as two 127-pixel
// runs per component, 4 + 4 * 2 * 2 = 20 bytes, and such a file still reads.
TEST_F(ImageIoTest, HdrAtTheSmallestRunLengthSizeIsRead) {
    constexpr int width = 254, height = 3;
    const std::vector<float> rgb(std::size_t(width) * height * 3, 0.5f);
    const std::string path = file("flat.hdr");
    ASSERT_NE(stbi_write_hdr(path.c_str(), width, height, 3, rgb.data()), 0);
    const std::string bytes = readBytes(path);
    const std::string resolution = "-Y 3 +X 254\n";
    ASSERT_NE(bytes.find(resolution), std::string::npos);
    EXPECT_EQ(bytes.size() - (bytes.find(resolution) + resolution.size()), std::size_t(height) * 20);

    const Image image = obscura::readHdr(path);
    ASSERT_EQ(image.width, width);
    ASSERT_EQ(image.height, height);
    EXPECT_EQ(image.pixels.front(), 0.5f);
    EXPECT_EQ(image.pixels.back(), 0.5f);

    writeBytes(path, bytes.substr(0, bytes.size() - 1));
    expectMessage(thrownMessage([&] { obscura::readHdr(path); }), path,
                  "truncated Radiance HDR pixel data (254x3 needs at least 60 bytes, the file has 59)");
}

// Radiance's EXPOSURE and COLORCORR lines record multipliers already applied to the values (several
// multiply up): the radiance is the values divided by their product. A map saved with exposure 2 once lit
// the scene twice as bright.
TEST_F(ImageIoTest, HdrExposureAndColourCorrectionAreDividedOut) {
    constexpr int width = 3, height = 2;
    const std::vector<float> rgb(std::size_t(width) * height * 3, 0.5f);
    const std::string plain = file("plain.hdr");
    ASSERT_NE(stbi_write_hdr(plain.c_str(), width, height, 3, rgb.data()), 0);
    const std::string bytes = readBytes(plain);
    const std::size_t blank = bytes.find("\n\n");
    ASSERT_NE(blank, std::string::npos);
    const auto withHeader = [&](const std::string& name, const std::string& lines) {
        const std::string path = file(name);
        writeBytes(path, bytes.substr(0, blank + 1) + lines + bytes.substr(blank + 1));
        return path;
    };

    const Image exposed = obscura::readHdr(withHeader("exposed.hdr", "EXPOSURE=2\nEXPOSURE= 0.5e1\n"));
    for (float v : exposed.pixels) EXPECT_EQ(v, 0.05f);
    const Image corrected = obscura::readHdr(withHeader("corrected.hdr", "COLORCORR=1 0.25\t4\nEXPOSURE=.5\n"));
    const float expected[3] = {1.0f, 4.0f, 0.25f};
    for (std::size_t i = 0; i < corrected.pixels.size(); ++i) EXPECT_EQ(corrected.pixels[i], expected[i % 3]) << i;

    for (const char* bad : {"EXPOSURE=0", "EXPOSURE=-1", "EXPOSURE=nan", "EXPOSURE=", "EXPOSURE=2 3", "COLORCORR=1 1"}) {
        const std::string path = withHeader("bad.hdr", std::string(bad) + "\n");
        expectMessage(thrownMessage([&] { obscura::readHdr(path); }), path,
                      std::string("Radiance HDR header '") + bad + "' needs");
    }
    const std::string tiny = withHeader("tiny.hdr", "EXPOSURE=1e-30\nEXPOSURE=1e-30\n");
    expectMessage(thrownMessage([&] { obscura::readHdr(tiny); }), tiny,
                  "Radiance HDR EXPOSURE/COLORCORR lines multiply to 1e-60, past the float range");
    // A product in range that takes a large value past it is named as such: the message said only that the
    // environment's radiance was inf.
    const std::vector<float> large(std::size_t(width) * height * 3, 1e30f);
    const std::string big = file("big.hdr");
    ASSERT_NE(stbi_write_hdr(big.c_str(), width, height, 3, large.data()), 0);
    const std::string bigBytes = readBytes(big);
    const std::size_t bigBlank = bigBytes.find("\n\n");
    writeBytes(big, bigBytes.substr(0, bigBlank + 1) + "EXPOSURE=1e-10\n" + bigBytes.substr(bigBlank + 1));
    const std::string message = thrownMessage([&] { obscura::readHdr(big); });
    expectMessage(message, big, "pixel (0, 0) is ");
    EXPECT_NE(message.find("divided by its EXPOSURE/COLORCORR it is past the float range"), std::string::npos) << message;
}

// Written with CRLF line ends, or with a space after the resolution: the same image (the magic line read
// "#?RADIANCE\r" and the file was refused as no HDR file; the space made the resolution line unsupported).
TEST_F(ImageIoTest, HdrHeaderToleratesCrlfAndTrailingSpace) {
    constexpr int width = 3, height = 2;
    std::vector<float> rgb(std::size_t(width) * height * 3);
    for (std::size_t i = 0; i < rgb.size(); ++i) rgb[i] = 0.25f * float(i % 5);
    const std::string plain = file("plain.hdr");
    ASSERT_NE(stbi_write_hdr(plain.c_str(), width, height, 3, rgb.data()), 0);
    const std::string bytes = readBytes(plain);
    const Image reference = obscura::readHdr(plain);
    // The header is the lines up to and including the resolution line, the one after the blank line.
    const std::size_t blank = bytes.find("\n\n");
    ASSERT_NE(blank, std::string::npos);
    const std::size_t resolutionEnd = bytes.find('\n', blank + 2);
    ASSERT_NE(resolutionEnd, std::string::npos);
    std::string crlf;
    for (std::size_t i = 0; i <= resolutionEnd; ++i) crlf += bytes[i] == '\n' ? std::string("\r\n") : std::string(1, bytes[i]);
    writeBytes(file("crlf.hdr"), crlf + bytes.substr(resolutionEnd + 1));
    EXPECT_EQ(obscura::readHdr(file("crlf.hdr")).pixels, reference.pixels);
    writeBytes(file("space.hdr"), bytes.substr(0, resolutionEnd) + " \t" + bytes.substr(resolutionEnd));
    EXPECT_EQ(obscura::readHdr(file("space.hdr")).pixels, reference.pixels);
}

TEST_F(ImageIoTest, ExtensionDispatchIsCaseInsensitive) {
    EXPECT_EQ(obscura::fileExtension("a/b.EXR"), ".exr");
    EXPECT_EQ(obscura::fileExtension("a.tar.Gz"), ".gz");
    EXPECT_EQ(obscura::fileExtension("dir.d/noext"), "");

    Image image(2, 2, 3, 0.2f);
    obscura::writePng(file("UPPER.PNG"), image);
    EXPECT_EQ(obscura::readImage(file("UPPER.PNG")).channels, 3);
}

// ---- errors -------------------------------------------------------------------------------------

TEST_F(ImageIoTest, MissingFileSaysNoSuchFile) {
    for (const char* name : {"missing.exr", "missing.png", "missing.hdr"}) {
        const std::string path = file(name);
        expectMessage(thrownMessage([&] { obscura::readImage(path); }), path, "no such file");
    }
}

TEST_F(ImageIoTest, TruncatedExrIsAnErrorNotACrash) {
    Image image(64, 64, 3);
    for (std::size_t i = 0; i < image.pixels.size(); ++i) image.pixels[i] = float((i * 2654435761u) % 1000) * 0.001f;
    const std::string path = file("truncated.exr");
    obscura::writeExr(path, image);
    fs::resize_file(path, fs::file_size(path) / 2);

    // OpenEXR's words for a file that stops short; the path appears once, at the front.
    const std::string message = thrownMessage([&] { obscura::readExr(path); });
    expectMessage(message, path, "end of file");
    EXPECT_EQ(message.find(path, 1), std::string::npos) << message;
}

TEST_F(ImageIoTest, GarbageBytesAreRejectedPerFormat) {
    const std::string garbage = "this is not an image, just some text that is long enough to parse\n";
    const std::vector<std::pair<std::string, std::string>> cases = {
        {"garbage.exr", "not an image file"}, {"garbage.png", "not a PNG file"}, {"garbage.hdr", "not a Radiance HDR"}};
    for (const auto& [name, problem] : cases) {
        const std::string path = file(name);
        writeBytes(path, garbage);
        expectMessage(thrownMessage([&] { obscura::readImage(path); }), path, problem);
    }
}

TEST_F(ImageIoTest, CorruptPngAfterAGoodSignatureIsRefused) {
    const std::string path = file("corrupt.png");
    obscura::writePng(path, Image(8, 8, 3, 0.5f));
    std::string bytes = readBytes(path);
    bytes.resize(40); // signature and part of IHDR survive, the rest is gone
    writeBytes(path, bytes);
    expectMessage(thrownMessage([&] { obscura::readPng(path); }), path, "cannot read PNG");
}

// stb_image checks no chunk CRC (nor zlib's Adler-32): a PNG with one flipped bit in its pixel data decoded
// to other pixels without an error. Every chunk's CRC is checked now; the same bytes with the bit back read.
TEST_F(ImageIoTest, APngThatFailsAChunkCrcIsRefused) {
    const std::string path = file("flipped.png");
    Image image(8, 8, 3);
    for (std::size_t i = 0; i < image.pixels.size(); ++i) image.pixels[i] = float(i % 7) / 7.0f;
    obscura::writePng(path, image);
    std::string bytes = readBytes(path);
    const std::size_t idat = bytes.find("IDAT");
    ASSERT_NE(idat, std::string::npos);
    const std::size_t at = idat + 4 + 6;  // inside the compressed data, past its 2-byte zlib header
    bytes[at] = char(bytes[at] ^ 0x10);
    writeBytes(path, bytes);
    expectMessage(thrownMessage([&] { obscura::readPng(path); }), path, "chunk 'IDAT' at byte " + std::to_string(idat - 4) +
                                                                       " fails its CRC");
    bytes[at] = char(bytes[at] ^ 0x10);
    writeBytes(path, bytes);
    EXPECT_EQ(obscura::readPng(path).width, 8);
}

TEST_F(ImageIoTest, PngDataNamedHdrIsNotMistakenForHdr) {
    const std::string path = file("picture.hdr");
    obscura::writePng(file("picture.png"), Image(2, 2, 3, 0.5f));
    fs::rename(file("picture.png"), path);
    expectMessage(thrownMessage([&] { obscura::readHdr(path); }), path, "not a Radiance HDR");
}

TEST_F(ImageIoTest, UnknownExtensionNamesItAndTheChoices) {
    const std::string path = file("picture.xyz");
    writeBytes(path, "whatever");
    expectMessage(thrownMessage([&] { obscura::readImage(path); }), path,
                  "unknown image format '.xyz' (expected .exr, .png or .hdr)");
}

TEST_F(ImageIoTest, ZeroSizeImageIsNotWritten) {
    for (const Image& empty : {Image(), Image(0, 4, 3), Image(4, 0, 3), Image(4, 4, 0)}) {
        expectMessage(thrownMessage([&] { obscura::writeExr(file("empty.exr"), empty); }), file("empty.exr"),
                      "image has zero size");
        expectMessage(thrownMessage([&] { obscura::writePng(file("empty.png"), empty); }), file("empty.png"),
                      "image has zero size");
    }
    EXPECT_TRUE(listDirectory().empty());
}

TEST_F(ImageIoTest, UnwritableChannelLayoutsAreRejected) {
    Image five(2, 2, 5);
    expectMessage(thrownMessage([&] { obscura::writePng(file("five.png"), five); }), file("five.png"), "1 to 4");
    expectMessage(thrownMessage([&] { obscura::writeExr(file("five.exr"), five); }), file("five.exr"),
                  "need channelNames");
    Image twins(2, 2, 2);
    twins.channelNames = {"Z", "Z"};
    expectMessage(thrownMessage([&] { obscura::writeExr(file("twins.exr"), twins); }), file("twins.exr"),
                  "duplicate channel name 'Z'");
    EXPECT_TRUE(listDirectory().empty());
}

// ---- atomic writes ------------------------------------------------------------------------------

TEST_F(ImageIoTest, AtomicWriteIntoMissingDirectoryThrowsAndLeavesNothing) {
    const std::string path = file("no/such/dir/out.exr");
    expectMessage(thrownMessage([&] { obscura::writeExr(path, Image(2, 2, 1)); }), path, "cannot write");
    expectMessage(thrownMessage([&] { obscura::writePng(path, Image(2, 2, 1)); }), path, "cannot write");
    EXPECT_TRUE(listDirectory().empty());
}

TEST_F(ImageIoTest, AtomicWriteUsesTemporaryBesideTargetThenRenames) {
    const std::string path = file("out.bin");
    std::string seenTemp;
    obscura::writeAtomically(path, [&](const std::string& tempPath) {
        seenTemp = tempPath;
        EXPECT_TRUE(fs::exists(tempPath));
        std::ofstream(tempPath, std::ios::binary) << "payload";
    });
    EXPECT_EQ(seenTemp.rfind(path + ".tmp-" + std::to_string(getpid()) + "-", 0), 0u) << seenTemp;
    EXPECT_EQ(readBytes(path), "payload");
    EXPECT_EQ(listDirectory(), (std::vector<std::string>{"out.bin"}));
}

// An output name of 250 bytes is valid (NAME_MAX is 255 on Linux), but the temporary beside it, the name and
// ".tmp-PID-N", was not: the write failed with "File name too long". The temporary now keeps within it.
TEST_F(ImageIoTest, AtomicWriteTakesTheLongestNames) {
    const std::string png = std::string(246, 'n') + ".png", exr = std::string(246, 'n') + ".exr";
    ASSERT_EQ(png.size(), 250u);
    obscura::writePng(file(png), Image(2, 2, 3, 0.5f));
    EXPECT_EQ(obscura::readPng(file(png)).width, 2);
    obscura::writeExr(file(exr), Image(2, 2, 1, 0.5f));
    obscura::writeExr(file(exr), Image(2, 2, 1, 0.25f));  // and over it
    EXPECT_EQ(obscura::readExr(file(exr)).pixels[0], 0.25f);
    std::vector<std::string> names = listDirectory();
    std::sort(names.begin(), names.end());
    EXPECT_EQ(names, (std::vector<std::string>{exr, png}));
}

TEST_F(ImageIoTest, AtomicWriteThatThrowsMidwayLeavesNoFiles) {
    const std::string path = file("out.bin");
    EXPECT_THROW(obscura::writeAtomically(path,
                                          [](const std::string& tempPath) {
                                              std::ofstream(tempPath, std::ios::binary) << "half a file";
                                              throw std::runtime_error("writer failed midway");
                                          }),
                 std::runtime_error);
    EXPECT_TRUE(listDirectory().empty());
}

TEST_F(ImageIoTest, AtomicWriteFailureLeavesExistingTargetUntouched) {
    const std::string path = file("keep.png");
    const Image original(3, 3, 3, 0.25f);
    obscura::writePng(path, original);
    const std::string before = readBytes(path);

    EXPECT_THROW(obscura::writeAtomically(path,
                                          [](const std::string& tempPath) {
                                              std::ofstream(tempPath, std::ios::binary) << "broken";
                                              obscura::fail(tempPath, "simulated encoder failure");
                                          }),
                 obscura::Error);
    EXPECT_EQ(readBytes(path), before);
    EXPECT_EQ(listDirectory(), (std::vector<std::string>{"keep.png"}));

    // A successful write replaces it and still leaves no temporary behind.
    obscura::writePng(path, Image(3, 3, 3, 0.75f));
    EXPECT_EQ(obscura::readPng(path).pixels[0], 191.0f / 255.0f);
    EXPECT_EQ(listDirectory(), (std::vector<std::string>{"keep.png"}));
}

} // namespace

// A PNG wider than kMaxImageSide was read (camera.h: "the image readers all hold to it").
TEST_F(ImageIoTest, PngLargerThanTheLimitIsRefused) {
    const std::string path = file("wide.png");
    obscura::writePng(path, Image(obscura::kMaxImageSide + 1, 1, 1, 0.5f));
    EXPECT_THROW(obscura::readPng(path), obscura::Error);
}

// A 16-bit grey PNG 3x1 with values 0x8000, 0xFFFF, 0x00FF: read through stbi_load it came back cut to 8 bits,
// 0.501961, 1, 0 (0x00FF's 1/257 lost).
TEST_F(ImageIoTest, SixteenBitPngKeepsSixteenBits) {
    const unsigned char png[] = {
        0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a, 0x00, 0x00, 0x00, 0x0d, 0x49, 0x48, 0x44, 0x52, 0x00, 0x00,
        0x00, 0x03, 0x00, 0x00, 0x00, 0x01, 0x10, 0x00, 0x00, 0x00, 0x00, 0x6e, 0x1b, 0x97, 0x2b, 0x00, 0x00, 0x00,
        0x0f, 0x49, 0x44, 0x41, 0x54, 0x78, 0x9c, 0x63, 0x68, 0x60, 0xf8, 0xff, 0x9f, 0xe1, 0x3f, 0x00, 0x0a, 0xff,
        0x03, 0x7e, 0x54, 0x86, 0xfe, 0xaf, 0x00, 0x00, 0x00, 0x00, 0x49, 0x45, 0x4e, 0x44, 0xae, 0x42, 0x60, 0x82};
    const std::string path = file("g16.png");
    std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(png), sizeof png);
    const Image im = obscura::readPng(path);
    ASSERT_EQ(im.pixels.size(), 3u);
    EXPECT_NEAR(im.pixels[0], 32768.0f / 65535.0f, 1e-6f);
    EXPECT_NEAR(im.pixels[1], 1.0f, 1e-6f);
    EXPECT_NEAR(im.pixels[2], 255.0f / 65535.0f, 1e-6f);
}
