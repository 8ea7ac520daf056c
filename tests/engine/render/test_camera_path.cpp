// Camera paths: the spline through the keyframes, the JSON format, and the rejection of bad
// files with messages that name the file and the problem.
#include "core/error.h"
#include "render/camera_path.h"

#include <fstream>
#include <gtest/gtest.h>
#include <unistd.h>

using namespace meadow;

namespace {

// Float comparisons: the spline is evaluated in double and rounded to float once, so a few
// float ulps at coordinates of tens of metres.
constexpr float kTolerance = 1e-4f;

void expectNear(glm::vec3 a, glm::vec3 b, float tolerance, const std::string& what) {
    EXPECT_NEAR(a.x, b.x, tolerance) << what;
    EXPECT_NEAR(a.y, b.y, tolerance) << what;
    EXPECT_NEAR(a.z, b.z, tolerance) << what;
}

CameraPath curvedPath() {
    CameraPath p;
    p.keyframes = {{0.0, {0, 2, 0}, {0, 1, 10}},
                   {1.0, {4, 3, 1}, {5, 0, 10}},
                   {3.0, {6, 2, 8}, {0, 0, 20}},
                   {3.5, {9, 5, 9}, {20, 1, 9}}};
    return p;
}

class CameraPathFiles : public ::testing::Test {
  protected:
    void SetUp() override {
        dir = std::filesystem::temp_directory_path() / ("meadow-camera-path-" + std::to_string(getpid()));
        std::filesystem::create_directories(dir);
    }
    void TearDown() override { std::filesystem::remove_all(dir); }
    std::filesystem::path write(const std::string& name, const std::string& text) {
        std::filesystem::path file = dir / name;
        std::ofstream(file) << text;
        return file;
    }
    // The error message loading `text` gives; fails the test when it loads.
    std::string loadError(const std::string& text) {
        std::filesystem::path file = write("bad.json", text);
        try {
            loadCameraPath(file);
        } catch (const Error& e) {
            std::string message = e.what();
            EXPECT_NE(message.find(file.string()), std::string::npos) << "the message names the file: " << message;
            return message;
        }
        ADD_FAILURE() << "loaded: " << text;
        return "";
    }
    std::filesystem::path dir;
};

} // namespace

TEST(CameraPath, PassesThroughEveryKeyframe) {
    CameraPath p = curvedPath();
    for (const CameraKeyframe& k : p.keyframes) {
        CameraPose pose = sampleCameraPath(p, k.time);
        expectNear(pose.eye, k.eye, kTolerance, "eye at t=" + std::to_string(k.time));
        expectNear(pose.target, k.target, kTolerance, "target at t=" + std::to_string(k.time));
    }
}

TEST(CameraPath, ClampsOutsideItsKeyframes) {
    CameraPath p = curvedPath();
    expectNear(sampleCameraPath(p, -5.0).eye, p.keyframes.front().eye, 0.0f, "before the start");
    expectNear(sampleCameraPath(p, 100.0).eye, p.keyframes.back().eye, 0.0f, "after the end");
    expectNear(sampleCameraPath(p, 100.0).target, p.keyframes.back().target, 0.0f, "after the end");
}

TEST(CameraPath, OneKeyframeIsAStillCamera) {
    CameraPath p;
    p.keyframes = {{2.0, {1, 2, 3}, {4, 5, 6}}};
    validateCameraPath(p, "test");
    for (double t : {0.0, 2.0, 7.0})
        expectNear(sampleCameraPath(p, t).eye, {1, 2, 3}, 0.0f, "still");
}

// Finite-difference tangents reproduce a camera moving at constant velocity exactly, however
// unevenly its keys are spaced (a Catmull-Rom with uniform parameters would not).
TEST(CameraPath, ReproducesConstantVelocityWithUnevenKeys) {
    const glm::vec3 e0(1, 2, 3), ve(2, -0.5f, 1), t0(10, 0, 10), vt(-1, 0.25f, 3);
    CameraPath p;
    for (double t : {0.0, 0.3, 1.7, 2.0, 4.5})
        p.keyframes.push_back({t, e0 + float(t) * ve, t0 + float(t) * vt});
    for (double t = 0.0; t <= 4.5; t += 0.05) {
        CameraPose pose = sampleCameraPath(p, t);
        expectNear(pose.eye, e0 + float(t) * ve, kTolerance, "eye at t=" + std::to_string(t));
        expectNear(pose.target, t0 + float(t) * vt, kTolerance, "target at t=" + std::to_string(t));
    }
}

// C1 in time: the velocity just before a keyframe equals the velocity just after it.
TEST(CameraPath, VelocityIsContinuousAcrossKeyframes) {
    CameraPath p = curvedPath();
    const double h = 1e-4;
    for (size_t i = 1; i + 1 < p.keyframes.size(); ++i) {
        const double t = p.keyframes[i].time;
        glm::vec3 before = (sampleCameraPath(p, t).eye - sampleCameraPath(p, t - h).eye) / float(h);
        glm::vec3 after = (sampleCameraPath(p, t + h).eye - sampleCameraPath(p, t).eye) / float(h);
        // One-sided differences differ by the acceleration jump times h (~1e-3 here) plus
        // float rounding of positions (~1e-6 / 1e-4 = 1e-2 m/s).
        expectNear(before, after, 0.05f, "velocity at keyframe " + std::to_string(i));
    }
}

TEST(CameraPath, KeepsADirectionWhenTheTargetMeetsTheEye) {
    // Eye and target swap places between the keys: at the middle they coincide.
    CameraPath p;
    p.keyframes = {{0.0, {0, 1, 0}, {0, 1, 2}}, {1.0, {0, 1, 2}, {0, 1, 0}}};
    CameraPose mid = sampleCameraPath(p, 0.5);
    EXPECT_GT(glm::length(mid.target - mid.eye), 1.0f);
}

TEST(CameraPath, RejectsBadPathsByKeyframe) {
    auto expectError = [](const CameraPath& p, const std::string& part) {
        try {
            validateCameraPath(p, "where");
            ADD_FAILURE() << "accepted; expected: " << part;
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
        }
    };
    expectError(CameraPath{}, "no keyframes");
    CameraPath p = curvedPath();
    p.keyframes[2].time = 1.0; // same as the one before
    expectError(p, "keyframe 2: 'time' 1 is not after the previous keyframe's 1");
    p = curvedPath();
    p.keyframes[1].target = p.keyframes[1].eye;
    expectError(p, "keyframe 1: the target must differ from the eye");
    p = curvedPath();
    p.keyframes[3].target = p.keyframes[3].eye + glm::vec3(0, -5, 0);
    expectError(p, "keyframe 3: the camera looks straight up or down");
    p = curvedPath();
    p.keyframes[0].eye.x = std::numeric_limits<float>::infinity();
    expectError(p, "keyframe 0: eye and target must be finite");
}

TEST_F(CameraPathFiles, SavesAndLoadsBitForBit) {
    CameraPath p = curvedPath();
    p.keyframes[1].eye = {0.1f, -1.0f / 3.0f, 123.456f};
    p.keyframes[2].time = 2.0 / 3.0 + 1.0;
    std::filesystem::path file = dir / "path.json";
    saveCameraPath(file, p);
    CameraPath back = loadCameraPath(file);
    ASSERT_EQ(back.keyframes.size(), p.keyframes.size());
    for (size_t i = 0; i < p.keyframes.size(); ++i) {
        EXPECT_EQ(back.keyframes[i].time, p.keyframes[i].time);
        EXPECT_EQ(back.keyframes[i].eye, p.keyframes[i].eye);
        EXPECT_EQ(back.keyframes[i].target, p.keyframes[i].target);
    }
    // Written as the shortest decimals that read back the same.
    std::ifstream in(file);
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    EXPECT_NE(text.find("[0.1,-0.33333334,123.456]"), std::string::npos) << text;
    // No temporary left beside it.
    size_t files = 0;
    for (auto& entry : std::filesystem::directory_iterator(dir)) {
        (void)entry;
        ++files;
    }
    EXPECT_EQ(files, 1u);
}

TEST_F(CameraPathFiles, SaveRefusesAnInvalidPathAndWritesNothing) {
    std::filesystem::path file = dir / "empty.json";
    EXPECT_THROW(saveCameraPath(file, CameraPath{}), Error);
    EXPECT_FALSE(std::filesystem::exists(file));
    EXPECT_THROW(saveCameraPath(dir / "no-such-folder" / "p.json", curvedPath()), Error);
}

TEST_F(CameraPathFiles, LoadNamesTheFileAndTheProblem) {
    EXPECT_NE(loadError("{ \"keyframes\": [ ").find("invalid JSON"), std::string::npos);
    EXPECT_NE(loadError("[1, 2]").find("a JSON object with 'keyframes'"), std::string::npos);
    EXPECT_NE(loadError("{}").find("'keyframes' is missing"), std::string::npos);
    EXPECT_NE(loadError("{\"keyframes\": {}}").find("'keyframes' is not an array"), std::string::npos);
    EXPECT_NE(loadError("{\"keyframes\": []}").find("no keyframes"), std::string::npos);
    EXPECT_NE(loadError("{\"version\": 2, \"keyframes\": []}").find("unsupported version 2"), std::string::npos);
    EXPECT_NE(loadError("{\"keyframes\": [], \"speed\": 3}").find("unknown field 'speed'"), std::string::npos);
    const std::string eye = "\"eye\": [0, 1, 0], ";
    EXPECT_NE(loadError("{\"keyframes\": [{\"time\": 0, " + eye + "\"taget\": [1, 1, 1]}]}")
                  .find("keyframe 0: unknown field 'taget'"),
              std::string::npos);
    EXPECT_NE(loadError("{\"keyframes\": [{\"time\": 0, \"eye\": [0, 1, 0]}]}").find("keyframe 0: 'target' is missing"),
              std::string::npos);
    EXPECT_NE(loadError("{\"keyframes\": [{\"time\": \"now\", " + eye + "\"target\": [1, 1, 1]}]}")
                  .find("'time' is not a number"),
              std::string::npos);
    EXPECT_NE(loadError("{\"keyframes\": [{\"time\": 0, \"eye\": [0, 1], \"target\": [1, 1, 1]}]}")
                  .find("'eye' is not an array of three numbers"),
              std::string::npos);
    EXPECT_NE(loadError("{\"keyframes\": [{\"time\": 0, \"eye\": [0, 1, 1e39], \"target\": [1, 1, 1]}]}")
                  .find("too large for a float"),
              std::string::npos);
    EXPECT_NE(loadError("{\"keyframes\": [{\"time\": 1, " + eye + "\"target\": [1, 1, 1]}, {\"time\": 0.5, " + eye +
                        "\"target\": [1, 1, 1]}]}")
                  .find("keyframe 1: 'time' 0.5 is not after the previous keyframe's 1"),
              std::string::npos);
}

TEST_F(CameraPathFiles, LoadRejectsMissingFilesAndFolders) {
    try {
        loadCameraPath(dir / "absent.json");
        FAIL();
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("absent.json: no such file"), std::string::npos) << e.what();
    }
    EXPECT_THROW(loadCameraPath(dir), Error);
}
