// glTF import (precompute/plants/gltf_import.h): the valid asset becomes a one-rod plant, each
// kind of unusable asset is refused with a message naming the file and the problem.
#include "core/error.h"
#include "plants/gltf_import.h"

#include <cstring>
#include <fstream>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <unistd.h>

namespace meadow {
namespace {

const std::filesystem::path kAssets = std::filesystem::path(MEADOW_SOURCE_DIR) / "tests/data/gltf";

// The asset's two blades: 10 vertices, 6 triangles, 0.8 m tall in mesh space under a node
// scaled by 2 and a parent translated by 0.5 m along x.
constexpr size_t kPlantVertices = 10;
constexpr size_t kPlantTriangles = 6;

void expectValidPlant(const PlantClump& plant) {
    EXPECT_EQ(plant.plants, 1u);
    EXPECT_EQ(plant.mesh.vertexCount(), kPlantVertices);
    EXPECT_EQ(plant.mesh.triangleCount(), kPlantTriangles);
    ASSERT_EQ(plant.rods.size(), 1u);
    const Rod& rod = plant.rods[0];
    EXPECT_EQ(rod.kind, RodKind::Stem);
    ASSERT_EQ(rod.restNodes.size(), kImportRodNodes);
    // Moved to clump space: the rod starts at the origin and is as tall as the scaled plant.
    // 1e-5 m is float rounding of values near 1 m.
    EXPECT_LT(glm::length(rod.restNodes.front()), 1e-5f);
    EXPECT_LT(glm::length(rod.restNodes.back() - glm::vec3(0.0f, 1.6f, 0.0f)), 1e-5f);
    // Node transforms applied: the tip (0, 0.8, 0.05) scaled by 2, less the bounding box's
    // centre axis (x 0.5 after the parent's translation, z in the middle of [-0.04, 0.1]).
    EXPECT_LT(glm::length(plant.mesh.positions[4] - glm::vec3(0.0f, 1.6f, 0.07f)), 1e-5f);
    EXPECT_LT(glm::length(plant.mesh.positions[0] - glm::vec3(-0.04f, 0.0f, -0.03f)), 1e-5f);
    for (size_t v = 0; v < plant.mesh.vertexCount(); ++v) {
        EXPECT_LT(glm::length(boundRestPosition(plant.rods, plant.mesh.skin[v]) - plant.mesh.positions[v]), 1e-5f);
        // NORMAL is absent from the asset, so normals were computed: unit length up to rounding.
        EXPECT_NEAR(glm::length(plant.mesh.normals[v]), 1.0f, 1e-5f);
        EXPECT_EQ(plant.mesh.parts[v], PartKind::Other);
    }
    // TEXCOORD_0 came through: the tip vertex has v = 1.
    EXPECT_EQ(plant.mesh.uvs[4], glm::vec2(0.5f, 1.0f));
    // The lowest vertex binds to the first segment at t = 0, the tip to the last at t = 1.
    EXPECT_EQ(plant.mesh.skin[0].segment, 0u);
    EXPECT_EQ(plant.mesh.skin[4].segment, kImportRodNodes - 2);
    EXPECT_NEAR(plant.mesh.skin[4].t, 1.0f, 1e-5f);
}

TEST(GltfImport, ImportsTheValidPlant) {
    PlantClump plant = importGltfPlant(kAssets / "plant.gltf");
    EXPECT_EQ(plant.name, "plant");
    expectValidPlant(plant);
}

// The same asset as a .glb, assembled here (a 12-byte header, a JSON chunk, a BIN chunk) so the
// repository holds no binary file.
TEST(GltfImport, ImportsGlb) {
    nlohmann::json gltf;
    std::ifstream(kAssets / "plant.gltf") >> gltf;
    std::string uri = gltf["buffers"][0]["uri"];
    std::string base64 = uri.substr(uri.find(',') + 1);
    std::string bin;
    uint32_t bits = 0;
    int count = 0;
    for (char c : base64) {
        const char* alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
        const char* at = std::strchr(alphabet, c);
        if (c == '=' || at == nullptr)
            break;
        bits = (bits << 6) | static_cast<uint32_t>(at - alphabet);
        if (++count % 4 == 0) {
            bin.push_back(static_cast<char>(bits >> 16));
            bin.push_back(static_cast<char>(bits >> 8));
            bin.push_back(static_cast<char>(bits));
            bits = 0;
        }
    }
    // A final group of two or three characters carries one or two bytes.
    if (count % 4 == 2)
        bin.push_back(static_cast<char>(bits >> 4));
    if (count % 4 == 3) {
        bin.push_back(static_cast<char>(bits >> 10));
        bin.push_back(static_cast<char>(bits >> 2));
    }
    ASSERT_EQ(bin.size(), gltf["buffers"][0]["byteLength"].get<size_t>());
    gltf["buffers"][0].erase("uri");
    std::string json = gltf.dump();
    while (json.size() % 4 != 0)
        json.push_back(' ');
    while (bin.size() % 4 != 0)
        bin.push_back('\0');
    auto word = [](std::string& out, uint32_t w) { out.append(reinterpret_cast<const char*>(&w), 4); };
    std::string glb;
    word(glb, 0x46546C67); // "glTF"
    word(glb, 2);
    word(glb, static_cast<uint32_t>(12 + 8 + json.size() + 8 + bin.size()));
    word(glb, static_cast<uint32_t>(json.size()));
    word(glb, 0x4E4F534A); // "JSON"
    glb += json;
    word(glb, static_cast<uint32_t>(bin.size()));
    word(glb, 0x004E4942); // "BIN"
    glb += bin;

    auto path = std::filesystem::temp_directory_path() / ("meadow-plant-" + std::to_string(getpid()) + ".glb");
    std::ofstream(path, std::ios::binary) << glb;
    PlantClump plant = importGltfPlant(path);
    std::filesystem::remove(path);
    EXPECT_EQ(plant.name, path.stem().string());
    expectValidPlant(plant);
}

// Each refusal must name the file and say what is wrong.
void expectRejected(const std::string& file, const std::string& reason) {
    std::filesystem::path path = kAssets / file;
    try {
        importGltfPlant(path);
        FAIL() << file << " was imported";
    } catch (const Error& e) {
        std::string message = e.what();
        EXPECT_NE(message.find(path.string()), std::string::npos) << message;
        EXPECT_NE(message.find(reason), std::string::npos) << message;
    }
}

TEST(GltfImport, RejectsSkinnedAssets) {
    expectRejected("skinned.gltf", "uses skinning, which meadow cannot use");
}

TEST(GltfImport, RejectsNonTrianglePrimitives) {
    expectRejected("points.gltf", "draws POINTS; meadow imports only TRIANGLES primitives");
}

TEST(GltfImport, RejectsMalformedJson) {
    expectRejected("malformed.gltf", "cannot parse");
}

TEST(GltfImport, RejectsAssetsWithoutMesh) {
    expectRejected("no_mesh.gltf", "has no mesh");
}

TEST(GltfImport, RejectsMissingPosition) {
    expectRejected("no_position.gltf", "has no POSITION attribute");
}

TEST(GltfImport, RejectsWrongUnits) {
    expectRejected("millimetres.gltf", "wrong units? the plant is 1600 m tall");
}

TEST(GltfImport, RejectsMissingFiles) {
    expectRejected("absent.gltf", "cannot open");
}

} // namespace
} // namespace meadow
