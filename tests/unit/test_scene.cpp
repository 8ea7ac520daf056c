#include "core/error.h"
#include "scene.h"

#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>

using namespace meadow;

namespace {

std::filesystem::path writeScene(const std::string& name, const std::string& text) {
    std::filesystem::path dir = std::filesystem::temp_directory_path() / "meadow-unit-scenes";
    std::filesystem::create_directories(dir);
    std::filesystem::path p = dir / name;
    std::ofstream(p) << text;
    return p;
}

const char* kMinimal = R"({"name": "t", "seed": 5, "testField": {"countX": 4, "countZ": 3, "spacing": 1.5},
  "presets": {"ci": {"testField": {"countX": 2}}}})";

std::string errorOf(const std::filesystem::path& p, const std::string& preset = "full") {
    try {
        loadScene(p, preset, std::nullopt);
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

} // namespace

TEST(Scene, PresetMergesOverBase) {
    auto p = writeScene("minimal.json", kMinimal);
    Scene full = loadScene(p, "full", std::nullopt);
    EXPECT_EQ(full.testField.countX, 4u);
    EXPECT_EQ(full.testField.countZ, 3u);
    Scene ci = loadScene(p, "ci", std::nullopt);
    EXPECT_EQ(ci.testField.countX, 2u); // overridden
    EXPECT_EQ(ci.testField.countZ, 3u); // kept from the base
    EXPECT_EQ(ci.seed, 5u);
    Scene seeded = loadScene(p, "ci", 99);
    EXPECT_EQ(seeded.seed, 99u);
    EXPECT_EQ(seeded.resolved["seed"], 99);
}

TEST(Scene, BundledDefaultSceneLoadsInBothPresets) {
    for (const char* preset : kPresetNames) {
        Scene s = loadScene(MEADOW_SOURCE_DIR "/data/scenes/irises.json", preset, std::nullopt);
        EXPECT_EQ(s.name, "irises");
        EXPECT_GT(s.testField.countX * s.testField.countZ, 0u);
    }
}

TEST(Scene, ErrorsNameTheFileAndTheKey) {
    EXPECT_NE(errorOf(writeScene("bad-json.json", "{ nope")).find("invalid JSON"), std::string::npos);
    EXPECT_NE(errorOf(writeScene("missing.json", R"({"name": "t", "seed": 1})")).find("testField is missing"),
              std::string::npos);
    std::string typo = errorOf(writeScene("typo.json", R"({"name": "t", "seed": 1, "tesField": {}})"));
    EXPECT_NE(typo.find("typo.json"), std::string::npos) << typo;
    EXPECT_NE(typo.find("tesField is not a known key"), std::string::npos) << typo;
    std::string range = errorOf(
        writeScene("range.json", R"({"name": "t", "seed": 1, "testField": {"countX": 0, "countZ": 1, "spacing": 1}})"));
    EXPECT_NE(range.find("testField.countX must be between 1 and 4096"), std::string::npos) << range;
    std::string type = errorOf(writeScene(
        "type.json", R"({"name": "t", "seed": 1, "testField": {"countX": 1, "countZ": 1, "spacing": "far"}})"));
    EXPECT_NE(type.find("testField.spacing must be a number"), std::string::npos) << type;
    EXPECT_NE(errorOf(writeScene("name.json", R"({"name": "../x", "seed": 1})")).find("name may hold only"),
              std::string::npos);
    EXPECT_NE(errorOf(writeScene("nofile.json", kMinimal), "medium").find("unknown preset"), std::string::npos);
    EXPECT_NE(errorOf("/nonexistent/scene.json").find("cannot open"), std::string::npos);
}
