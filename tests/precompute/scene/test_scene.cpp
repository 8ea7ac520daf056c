#include "core/error.h"
#include "scene/scene.h"

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

const char* kMinimal = R"({"name": "t", "seed": 5, "field": {"tilesX": 4, "tilesY": 3, "tileSize": 5.5},
  "presets": {"ci": {"field": {"tilesX": 2}}}})";

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
    EXPECT_EQ(full.field.tilesX, 4u);
    EXPECT_EQ(full.field.tilesY, 3u);
    EXPECT_EQ(full.field.tileSize, 5.5f);
    Scene ci = loadScene(p, "ci", std::nullopt);
    EXPECT_EQ(ci.field.tilesX, 2u); // overridden
    EXPECT_EQ(ci.field.tilesY, 3u); // kept from the base
    EXPECT_EQ(ci.seed, 5u);
    Scene seeded = loadScene(p, "ci", 99);
    EXPECT_EQ(seeded.seed, 99u);
    EXPECT_EQ(seeded.resolved["seed"], 99);
}

TEST(Scene, BundledDefaultSceneLoadsInBothPresets) {
    for (const char* preset : kPresetNames) {
        Scene s = loadScene(MEADOW_SOURCE_DIR "/data/scenes/irises.json", preset, std::nullopt);
        EXPECT_EQ(s.name, "irises");
        EXPECT_GT(s.field.tilesX * s.field.tilesY, 0u);
    }
}

TEST(Scene, ErrorsNameTheFileAndTheKey) {
    EXPECT_NE(errorOf(writeScene("bad-json.json", "{ nope")).find("invalid JSON"), std::string::npos);
    EXPECT_NE(errorOf(writeScene("missing.json", R"({"name": "t", "seed": 1})")).find("field is missing"),
              std::string::npos);
    std::string typo = errorOf(writeScene("typo.json", R"({"name": "t", "seed": 1, "tesField": {}})"));
    EXPECT_NE(typo.find("typo.json"), std::string::npos) << typo;
    EXPECT_NE(typo.find("tesField is not a known key"), std::string::npos) << typo;
    std::string range =
        errorOf(writeScene("range.json", R"({"name": "t", "seed": 1, "field": {"tilesX": 0, "tilesY": 1}})"));
    EXPECT_NE(range.find("field.tilesX must be between 1 and 1024"), std::string::npos) << range;
    std::string type = errorOf(
        writeScene("type.json", R"({"name": "t", "seed": 1, "field": {"tilesX": 1, "tilesY": 1, "tileSize": "far"}})"));
    EXPECT_NE(type.find("field.tileSize must be a number"), std::string::npos) << type;
    std::string terrain = errorOf(writeScene(
        "terrain.json", R"({"name": "t", "seed": 1, "field": {"tilesX": 1, "tilesY": 1, "terrain": {"height": 2}}})"));
    EXPECT_NE(terrain.find("field.terrain.height is not a known key"), std::string::npos) << terrain;
    EXPECT_NE(errorOf(writeScene("name.json", R"({"name": "../x", "seed": 1})")).find("name may hold only"),
              std::string::npos);
    EXPECT_NE(errorOf(writeScene("nofile.json", kMinimal), "medium").find("unknown preset"), std::string::npos);
    EXPECT_NE(errorOf("/nonexistent/scene.json").find("cannot open"), std::string::npos);
}

TEST(Scene, SkyTakesPresetDefaultsAndOverrides) {
    auto base = writeScene("sky-default.json", kMinimal);
    EXPECT_EQ(loadScene(base, "ci", std::nullopt).sky.params.frames, 48u);
    EXPECT_EQ(loadScene(base, "full", std::nullopt).sky.params.frames, 288u);
    EXPECT_TRUE(loadScene(base, "full", std::nullopt).sky.maps.empty());
    auto p = writeScene("sky.json", R"({"name": "t", "seed": 5, "field": {"tilesX": 1, "tilesY": 1},
      "sky": {"latitude": -33.9, "dayOfYear": 355, "turbidity": 2.5, "frames": 96, "imageWidth": 32,
              "maps": ["skies/dawn.exr", "skies/noon.hdr"]}})");
    Scene s = loadScene(p, "full", std::nullopt);
    EXPECT_NEAR(s.sky.params.latitudeDegrees, -33.9, 1e-5); // stored through a float
    EXPECT_EQ(s.sky.params.dayOfYear, 355.0);
    EXPECT_NEAR(s.sky.params.daylight.turbidity, 2.5, 1e-6);
    EXPECT_EQ(s.sky.params.frames, 96u);
    EXPECT_EQ(s.sky.params.imageWidth, 32u);
    EXPECT_EQ(s.sky.params.imageHeight, 16u);
    ASSERT_EQ(s.sky.maps.size(), 2u);
    EXPECT_EQ(s.sky.maps[0], p.parent_path() / "skies/dawn.exr"); // relative to the scene file
}

TEST(Scene, SkyErrorsNameTheKey) {
    auto scene = [](const std::string& sky) {
        return R"({"name": "t", "seed": 5, "field": {"tilesX": 1, "tilesY": 1}, "sky": )" + sky + "}";
    };
    EXPECT_NE(errorOf(writeScene("s1.json", scene(R"({"latitude": 95})"))).find("sky.latitude must be between"),
              std::string::npos);
    EXPECT_NE(errorOf(writeScene("s2.json", scene(R"({"imageWidth": 33})"))).find("sky.imageWidth must be even"),
              std::string::npos);
    EXPECT_NE(errorOf(writeScene("s3.json", scene(R"({"maps": []})"))).find("sky.maps must be an array"),
              std::string::npos);
    EXPECT_NE(errorOf(writeScene("s4.json", scene(R"({"maps": [3]})"))).find("sky.maps[0] must be a file name"),
              std::string::npos);
    EXPECT_NE(errorOf(writeScene("s5.json", scene(R"({"sun": 1})"))).find("sky.sun is not a known key"),
              std::string::npos);
    EXPECT_NE(errorOf(writeScene("s6.json", scene(R"({"turbidity": 1.0})"))).find("sky.turbidity must be between"),
              std::string::npos);
}

// field.tiling chooses the scan-line (default) or the hash tiling; nothing else.
TEST(Scene, FieldTilingIsScanlineOrHash) {
    auto scene = [](const std::string& tiling) {
        return R"({"name": "t", "seed": 5, "field": {"tilesX": 1, "tilesY": 1)" + tiling + "}}";
    };
    EXPECT_EQ(loadScene(writeScene("t1.json", scene("")), "ci", std::nullopt).field.tiling, "scanline");
    EXPECT_EQ(loadScene(writeScene("t2.json", scene(R"(, "tiling": "hash")")), "ci", std::nullopt).field.tiling,
              "hash");
    const std::string e = errorOf(writeScene("t3.json", scene(R"(, "tiling": "spiral")")));
    EXPECT_NE(e.find(R"(field.tiling must be "scanline" or "hash" (got "spiral"))"), std::string::npos) << e;
}

// Bounds are printed as written in the code, not as the double nearest their float.
TEST(Scene, RangeMessagesPrintTheBoundsAsWritten) {
    const std::string e = errorOf(
        writeScene("r1.json", R"({"name": "t", "seed": 5, "field": {"tilesX": 1, "tilesY": 1, "cellSize": 7}})"));
    EXPECT_NE(e.find("field.cellSize must be between 0.002 and 1.0 (got 7)"), std::string::npos) << e;
}

TEST(Scene, LodFractionsAreCheckedInOrder) {
    auto scene = [](const std::string& lod) {
        return R"({"name": "t", "seed": 5, "field": {"tilesX": 1, "tilesY": 1}, "lod": )" + lod + "}";
    };
    Scene s = loadScene(writeScene("lod.json", scene(R"({"triangleFractions": [1, 0.5, 0.2, 0.1, 0.05]})")), "full",
                        std::nullopt);
    EXPECT_EQ(s.lod.triangleFractions[3], 0.1f);
    EXPECT_NE(errorOf(writeScene("lod1.json", scene(R"({"triangleFractions": [1, 0.5, 0.6, 0.1, 0.05]})")))
                  .find("lod.triangleFractions[2] must not exceed"),
              std::string::npos);
    EXPECT_NE(errorOf(writeScene("lod2.json", scene(R"({"triangleFractions": [0.9, 0.5, 0.2, 0.1, 0.05]})")))
                  .find("lod.triangleFractions[0] must be 1"),
              std::string::npos);
    EXPECT_NE(errorOf(writeScene("lod3.json", scene(R"({"triangleFractions": [1, 0.5]})"))).find("array of 5"),
              std::string::npos);
}

TEST(Scene, LightSectionOverridesTheBake) {
    auto p = writeScene("light.json", R"({"name": "t", "seed": 5, "field": {"tilesX": 1, "tilesY": 1},
      "light": {"raysPerVertex": 64, "bounces": 0, "framesPerLevel": 3}})");
    Scene s = loadScene(p, "full", std::nullopt);
    EXPECT_EQ(s.light.bake.raysPerVertex, 64u);
    EXPECT_EQ(s.light.bake.bounces, 0u);
    EXPECT_EQ(s.light.framesPerLevel, 3u);
    EXPECT_NE(errorOf(writeScene("light2.json", R"({"name": "t", "seed": 5, "field": {"tilesX": 1, "tilesY": 1},
      "light": {"framesPerLevel": 1}})"))
                  .find("light.framesPerLevel must be between 2"),
              std::string::npos);
}

TEST(Scene, StemDiameterIsForImportedPlantsAndRangeChecked) {
    auto scene = [](const std::string& plants) {
        return std::string(R"({"name": "t", "seed": 1, "field": {"tilesX": 1, "tilesY": 1}, "plants": )") + plants +
               "}";
    };
    Scene s =
        loadScene(writeScene("stem.json", scene(R"({"source": "gltf", "gltf": "reed.gltf", "stemDiameter": 0.03})")),
                  "ci", std::nullopt);
    ASSERT_TRUE(s.plants.stemDiameter.has_value());
    EXPECT_FLOAT_EQ(*s.plants.stemDiameter, 0.03f);
    EXPECT_EQ(s.resolved["plants"]["stemDiameter"], 0.03); // in the resolved scene, so in the library's input hash
    s = loadScene(writeScene("no-stem.json", scene(R"({"source": "gltf", "gltf": "reed.gltf"})")), "ci", std::nullopt);
    EXPECT_FALSE(s.plants.stemDiameter.has_value());
    std::string range =
        errorOf(writeScene("stem-range.json", scene(R"({"source": "gltf", "gltf": "a.gltf", "stemDiameter": 1})")));
    EXPECT_NE(range.find("stem-range.json: plants.stemDiameter must be between 0.0005 and 0.5 (got 1)"),
              std::string::npos)
        << range;
    std::string type = errorOf(
        writeScene("stem-type.json", scene(R"({"source": "gltf", "gltf": "a.gltf", "stemDiameter": "thick"})")));
    EXPECT_NE(type.find("plants.stemDiameter must be a number"), std::string::npos) << type;
    std::string iris = errorOf(writeScene("stem-iris.json", scene(R"({"stemDiameter": 0.01})")));
    EXPECT_NE(iris.find("plants.stemDiameter applies only to plants.source \"gltf\""), std::string::npos) << iris;
}
