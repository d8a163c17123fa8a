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
    for (Case c : {Case{"{not json", "not a JSON object"},
                   Case{R"({"target":[0,0,0],"fovY":60,"width":4,"height":4})", "missing \"position\""},
                   Case{R"({"position":[0,1],"target":[0,0,0],"fovY":60,"width":4,"height":4})", "array of 3 numbers"},
                   Case{R"({"position":[0,1,2],"target":[0,0,0],"fovY":60,"width":0,"height":4})", "image size"},
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
    EXPECT_THROW(readCameraJson("/nonexistent/cam.json"), Error);
}
