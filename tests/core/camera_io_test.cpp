// Camera JSON: round trip, and one-line errors for malformed files.
#include "obscura/camera_io.h"
#include "obscura/error.h"

#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>

using namespace obscura;

TEST(CameraIo, RoundTrip) {
    Camera c;
    c.position = {1.5f, -2, 3.25f};
    c.target = {0, 0.5f, -1};
    c.up = {0, 0, 1};
    c.fovY = 42.5f;
    c.nearZ = 0.05f;
    c.farZ = 250;
    c.width = 333;
    c.height = 197;
    auto path = (std::filesystem::temp_directory_path() / ("obscura_camera_io_" + std::to_string(getpid()) + ".json")).string();
    writeCameraJson(path, c);
    Camera r = readCameraJson(path);
    std::filesystem::remove(path);
    EXPECT_EQ(r.position, c.position);
    EXPECT_EQ(r.target, c.target);
    EXPECT_EQ(r.up, c.up);
    EXPECT_EQ(r.fovY, c.fovY);
    EXPECT_EQ(r.nearZ, c.nearZ);
    EXPECT_EQ(r.farZ, c.farZ);
    EXPECT_EQ(r.width, 333);
    EXPECT_EQ(r.height, 197);
}

TEST(CameraIo, ErrorsNameTheFileAndProblem) {
    struct Case {
        const char* text;
        const char* problem;
    };
    // A syntax error says where it is (every one read "not a JSON object"), text past a NUL byte is refused (the
    // parser stopped there), and Camera::validate's words name the file's field, fovY, once ("cam.json: camera:
    // fov must be ...").
    for (Case c : {Case{"{not json", "not valid JSON: parse error at line 1, column 3"},
                   Case{"{\"position\": [0, 1, 2],}", "not valid JSON: parse error at line 1, column 24"},
                   Case{"[1, 2]", "not a JSON object"},
                   Case{R"({"position":[0,1,2],"target":[0,0,0],"fovY":1e999,"width":4,"height":4})",
                        "not valid JSON: number overflow parsing '1e999'"},
                   Case{R"({"position":[0,1,2],"target":[0,0,0],"fovY":0,"width":4,"height":4})", "cam.json: fovY must be in"},
                   Case{R"({"target":[0,0,0],"fovY":60,"width":4,"height":4})", "missing \"position\""},
                   Case{R"({"position":[0,1],"target":[0,0,0],"fovY":60,"width":4,"height":4})", "array of 3 numbers"},
                   Case{R"({"position":[0,1,2],"target":[0,0,0],"fovY":60,"width":0,"height":4})", "\"width\" must be"},
                   Case{R"({"position":[0,1,2],"target":[0,0,0],"fovY":"wide","width":4,"height":4})", "must be a number"}}) {
        try {
            cameraFromJson(c.text, "cam.json");
            FAIL() << "accepted: " << c.text;
        } catch (const Error& e) {
            std::string m = e.what();
            EXPECT_EQ(m.rfind("cam.json: ", 0), 0u) << m;
            EXPECT_NE(m.find(c.problem), std::string::npos) << m;
            EXPECT_EQ(m.find('\n'), std::string::npos) << m;
        }
    }
    try {
        cameraFromJson(std::string("{}\0 garbage", 11), "cam.json");
        FAIL() << "accepted text past a NUL byte";
    } catch (const Error& e) {
        EXPECT_EQ(std::string(e.what()), "cam.json: not valid JSON: holds a NUL byte");
    }
    EXPECT_THROW(readCameraJson("/nonexistent/cam.json"), Error);
    // A directory was "not a JSON object".
    const std::string dir = ::testing::TempDir();
    try {
        readCameraJson(dir);
        FAIL() << "accepted a directory";
    } catch (const Error& e) {
        EXPECT_EQ(std::string(e.what()), dir + ": is a directory, not a camera JSON file");
    }
}

// Sizes were read with get<int>(): 4294967360 wrapped to 64, 64.9 was cut to 64 and 1e30 was undefined.
TEST(CameraIo, SizesMustBeWholeNumbersInRange) {
    const std::string start = R"({"position":[0,1,2],"target":[0,0,0],"fovY":60,)";
    for (const char* key : {"width", "height"}) {
        const char* other = std::string(key) == "width" ? "height" : "width";
        for (const char* value : {"4294967360", "64.9", "1e30", "-1", "0", "32769", "-2147483648"}) {
            const std::string text = start + "\"" + other + "\":48,\"" + key + "\":" + value + "}";
            try {
                cameraFromJson(text, "cam.json");
                FAIL() << "accepted: " << text;
            } catch (const Error& e) {
                const std::string expected = std::string("cam.json: \"") + key +
                                             "\" must be a whole number from 1 to 32768, got " +
                                             (std::string(value) == "1e30" ? "1e+30" : value);
                EXPECT_EQ(std::string(e.what()), expected);
            }
        }
        for (const auto& [value, expected] : {std::pair{"1", 1}, std::pair{"64.0", 64}, std::pair{"32768", 32768}}) {
            const Camera c = cameraFromJson(start + "\"" + other + "\":48,\"" + key + "\":" + value + "}", "cam.json");
            EXPECT_EQ(std::string(key) == "width" ? c.width : c.height, expected) << value;
        }
    }
}

// "far": 1e39 read as a float is inf; it was accepted and written back as "far": null.
TEST(CameraIo, FarBeyondFloatIsRefused) {
    EXPECT_THROW(cameraFromJson(R"({"position":[0,0,5],"target":[0,0,0],"fovY":60,"far":1e39,"width":4,"height":4})",
                                "c.json"),
                 Error);
}

TEST(CameraIo, EveryValidCameraRoundTrips) {
    Camera c;
    c.farZ = 3e38f;
    const std::string text = cameraToJson(c);
    EXPECT_EQ(text.find("null"), std::string::npos) << text;
    EXPECT_EQ(cameraFromJson(text, "c.json").farZ, c.farZ);
}
