// The bake's CSV and PLY writers: what their text and headers promise (docs/FORMATS.md).
#include "obscura/bake.h"
#include "obscura/bake_io.h"

#include <gtest/gtest.h>

#include <charconv>
#include <clocale>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

using namespace obscura;
using namespace obscura::bake;

namespace {

// One triangle whose coordinates and values need 9 significant digits to read back as the same floats.
struct Fixture {
    Scene scene;
    BakeResult result;
    Fixture() {
        Mesh m;
        m.positions = {{0.1f, 1234.5677f, -3.3333333f}, {1.0000001f, 0.0f, 0.0f}, {0.0f, 0.0f, 1.7014118e38f}};
        m.indices = {0, 1, 2};
        scene.add(std::move(m));
        result.channels = 2;
        result.instanceFirst = {0, 3};
        result.values = {0.66464001f, 0.33172730f, 0.1f, 0.99999994f, 1e-8f, 0.5f};
    }
};

std::vector<std::string> split(const std::string& line) {
    std::vector<std::string> fields;
    std::stringstream in(line);
    for (std::string field; std::getline(in, field, ',');) fields.push_back(field);
    return fields;
}

float parse(const std::string& text) {
    float value = 0.0f;
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
    EXPECT_EQ(error, std::errc()) << text;
    EXPECT_EQ(end, text.data() + text.size()) << text;
    return value;
}

} // namespace

// Every number reads back as the float written (%.7g did not, for the AO columns), and the text does not
// follow the C locale: a host program under a locale with decimal commas got 10 fields instead of 7.
TEST(BakeOutput, CsvNumbersReadBackExactlyInAnyLocale) {
    const Fixture x;
    const std::string path = (std::filesystem::path(::testing::TempDir()) / "bake_output_test.csv").string();
    const char* german = nullptr;
    for (const char* name : {"de_DE.UTF-8", "de_DE.utf8", "fr_FR.UTF-8", "fr_FR.utf8"})
        if (std::setlocale(LC_NUMERIC, name)) {
            german = name;
            break;
        }
    writeBakedCsv(x.scene, x.result, ArtistControls{}, path);
    std::setlocale(LC_NUMERIC, "C");
    std::printf("[ locale ] %s\n", german ? german : "no decimal-comma locale installed: the C locale only");
    std::ifstream in(path);
    std::string line;
    ASSERT_TRUE(std::getline(in, line));
    EXPECT_EQ(line, "index,x,y,z,short,long,blended");
    const Mesh& m = x.scene.meshes[0];
    for (std::size_t v = 0; v < 3; ++v) {
        ASSERT_TRUE(std::getline(in, line)) << v;
        const std::vector<std::string> f = split(line);
        ASSERT_EQ(f.size(), 7u) << line;
        EXPECT_EQ(f[0], std::to_string(v));
        EXPECT_EQ(parse(f[1]), m.positions[v].x) << line;
        EXPECT_EQ(parse(f[2]), m.positions[v].y) << line;
        EXPECT_EQ(parse(f[3]), m.positions[v].z) << line;
        const float s = x.result.values[2 * v], l = x.result.values[2 * v + 1];
        EXPECT_EQ(parse(f[4]), s) << line;
        EXPECT_EQ(parse(f[5]), l) << line;
        EXPECT_EQ(parse(f[6]), ArtistControls{}.blended(s, l)) << line;
    }
    EXPECT_FALSE(std::getline(in, line));
}
