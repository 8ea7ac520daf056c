// User plants through the pipeline (plants/gltf_import.h): the imported plant's colours reach the
// library's atlas without touching the iris regions, and the cache key covers the stem diameter
// and the files the glTF names beside itself.
#include "pipeline/build_library.h"
#include "plants/atlas.h"
#include "plants/iris.h"
#include "scratch_dir.h"

#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

using namespace meadow;

namespace {

const std::filesystem::path kGltf = std::filesystem::path(MEADOW_SOURCE_DIR) / "tests/data/gltf";

const std::filesystem::path& scratchDir() {
    static const test::ScratchDir dir("meadow-unit-user-plants");
    return dir.path();
}

// The robustness corpus's micro scene (a library in seconds) with another plant.
std::filesystem::path microScene(const std::string& name, const std::filesystem::path& plant,
                                 std::optional<double> stemDiameter = std::nullopt) {
    nlohmann::json scene;
    std::ifstream(std::filesystem::path(MEADOW_SOURCE_DIR) / "tests/system/robustness/micro.json") >> scene;
    scene["plants"]["gltf"] = plant.string();
    if (stemDiameter)
        scene["plants"]["stemDiameter"] = *stemDiameter;
    const std::filesystem::path path = scratchDir() / (name + ".json");
    std::ofstream(path) << scene.dump(1);
    return path;
}

TEST(UserPlants, TexturedPlantColoursTheLibraryAtlasOnly) {
    const Scene scene = loadScene(microScene("painted", kGltf / "painted.gltf"), "ci", std::nullopt);
    const Library library = buildLibrary(scene, true);
    const TextureAtlas iris = makeIrisAtlas(irisParamsForPreset("ci").atlasSize, scene.seed);
    ASSERT_EQ(library.atlas.rgba.size(), iris.rgba.size());
    const AtlasCell cell = importAtlasCell(iris.width);
    for (size_t i = 0; i < iris.rgba.size(); ++i) {
        const size_t x = (i / 4) % iris.width, y = (i / 4) / iris.width;
        if (x < cell.x0 || x >= cell.x1 || y < cell.y0 || y >= cell.y1) {
            ASSERT_EQ(library.atlas.rgba[i], iris.rgba[i]) << "texel " << x << ", " << y;
        }
    }
    // The clump's vertices sample orange tips and blue bases.
    size_t orange = 0, blue = 0;
    ASSERT_EQ(library.clumps.size(), 1u);
    for (const auto& vertex : library.clumps[0].mesh.vertices) {
        const float u = vertex.positionU.w, v = vertex.normalV.w;
        const uint32_t x = std::min(uint32_t(u * float(iris.width)), iris.width - 1);
        const uint32_t y = std::min(uint32_t(v * float(iris.height)), iris.height - 1);
        EXPECT_TRUE(x >= cell.x0 && x < cell.x1 && y >= cell.y0 && y < cell.y1);
        const uint8_t* p = &library.atlas.rgba[(size_t(y) * iris.width + x) * 4];
        orange += p[0] > 240 && p[1] > 120 && p[1] < 160 && p[2] < 20;
        blue += p[0] < 40 && p[1] < 80 && p[2] > 240;
    }
    EXPECT_GT(orange, 0u);
    EXPECT_GT(blue, 0u);
}

TEST(UserPlants, StemDiameterAndImagesBesideTheGltfAreCacheInputs) {
    // painted.gltf with its texture in a file beside it.
    const std::filesystem::path dir = scratchDir();
    nlohmann::json doc;
    std::ifstream(kGltf / "painted.gltf") >> doc;
    doc["images"][0]["uri"] = "texture.png";
    std::ofstream(dir / "external.gltf") << doc.dump();
    std::ofstream(dir / "texture.png", std::ios::binary) << "first bytes";
    const Scene plain = loadScene(microScene("external", dir / "external.gltf"), "ci", std::nullopt);
    const uint64_t before = libraryInputHash(plain);
    EXPECT_EQ(libraryInputHash(plain), before);
    std::ofstream(dir / "texture.png", std::ios::binary) << "other bytes";
    EXPECT_NE(libraryInputHash(plain), before);
    const Scene stiff = loadScene(microScene("external-stiff", dir / "external.gltf", 0.03), "ci", std::nullopt);
    const Scene soft = loadScene(microScene("external-soft", dir / "external.gltf", 0.0008), "ci", std::nullopt);
    EXPECT_NE(libraryInputHash(stiff), libraryInputHash(soft));
    EXPECT_NE(libraryInputHash(stiff), libraryInputHash(plain));
}

} // namespace

// The tests' scratch folders go when their process ends (scratch_dir.h): runs leave nothing in /tmp.
TEST(ScratchDir, RemovesItsFolderAndItsFilesWhenDestroyed) {
    std::filesystem::path path;
    {
        const test::ScratchDir dir("meadow-unit-scratch");
        path = dir.path();
        EXPECT_TRUE(std::filesystem::is_directory(path));
        std::filesystem::create_directories(path / "inner");
        std::ofstream(path / "inner" / "file.txt") << "x";
    }
    EXPECT_FALSE(std::filesystem::exists(path)) << path;
}
