// glTF import (precompute/plants/gltf_import.h): the valid asset becomes a one-rod plant, each
// kind of unusable asset is refused with a message naming the file and the problem.
#include "core/error.h"
#include "plants/gltf_import.h"
#include "scratch_dir.h"

#include <OpenImageIO/imageio.h>
#include <cstring>
#include <fstream>
#include <glm/gtc/constants.hpp>
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

// --- User plants (tests/data/gltf/README.md) --------------------------------------------------

nlohmann::json readJson(const std::filesystem::path& path) {
    nlohmann::json doc;
    std::ifstream(path) >> doc;
    return doc;
}

std::filesystem::path scratch(const std::string& name) {
    static const test::ScratchDir dir("meadow-gltf-test");
    return dir.path() / name;
}

std::filesystem::path writeJson(const std::string& name, const nlohmann::json& doc) {
    auto path = scratch(name);
    std::ofstream(path) << doc.dump();
    return path;
}

std::string base64(const std::string& bytes) {
    const char* alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    for (size_t i = 0; i < bytes.size(); i += 3) {
        uint32_t n = static_cast<uint8_t>(bytes[i]) << 16;
        if (i + 1 < bytes.size())
            n |= static_cast<uint8_t>(bytes[i + 1]) << 8;
        if (i + 2 < bytes.size())
            n |= static_cast<uint8_t>(bytes[i + 2]);
        out += alphabet[(n >> 18) & 63];
        out += alphabet[(n >> 12) & 63];
        out += i + 1 < bytes.size() ? alphabet[(n >> 6) & 63] : '=';
        out += i + 2 < bytes.size() ? alphabet[n & 63] : '=';
    }
    return out;
}

// A one-primitive glTF of the given triangles (positions and 32-bit indices), embedded.
std::filesystem::path writeMesh(const std::string& name, const std::vector<glm::vec3>& positions,
                                const std::vector<uint32_t>& indices) {
    std::string blob(reinterpret_cast<const char*>(positions.data()), positions.size() * sizeof(glm::vec3));
    const size_t indexOffset = blob.size();
    blob.append(reinterpret_cast<const char*>(indices.data()), indices.size() * 4);
    nlohmann::json doc = {
        {"asset", {{"version", "2.0"}}},
        {"scene", 0},
        {"scenes", {{{"nodes", {0}}}}},
        {"nodes", {{{"mesh", 0}}}},
        {"meshes", {{{"primitives", {{{"attributes", {{"POSITION", 0}}}, {"indices", 1}}}}}}},
        {"buffers", {{{"byteLength", blob.size()}, {"uri", "data:application/octet-stream;base64," + base64(blob)}}}},
        {"bufferViews",
         {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", indexOffset}},
          {{"buffer", 0}, {"byteOffset", indexOffset}, {"byteLength", indices.size() * 4}}}},
        {"accessors",
         {{{"bufferView", 0}, {"componentType", 5126}, {"count", positions.size()}, {"type", "VEC3"}},
          {{"bufferView", 1}, {"componentType", 5125}, {"count", indices.size()}, {"type", "SCALAR"}}}}};
    return writeJson(name + ".gltf", doc);
}

// A closed tube of radius r and height h along y (n sides, capped), welded.
void closedCylinder(float r, float h, uint32_t n, std::vector<glm::vec3>& p, std::vector<uint32_t>& ix) {
    for (uint32_t ring = 0; ring < 2; ++ring)
        for (uint32_t i = 0; i < n; ++i) {
            float a = 2.0f * glm::pi<float>() * float(i) / float(n);
            p.emplace_back(r * std::cos(a), h * float(ring), r * std::sin(a));
        }
    const uint32_t bottom = static_cast<uint32_t>(p.size()), top = bottom + 1;
    p.emplace_back(0.0f, 0.0f, 0.0f);
    p.emplace_back(0.0f, h, 0.0f);
    for (uint32_t i = 0; i < n; ++i) {
        uint32_t j = (i + 1) % n;
        ix.insert(ix.end(), {i, n + i, j, j, n + i, n + j, bottom, i, j, top, n + j, n + i});
    }
}

const std::string kNotAPlant = "not a plant: meadow simulates thin blades and stems on elastic rods";

TEST(GltfImport, ImportsTheHandMadePlants) {
    for (const char* file : {"three_blades.gltf", "reed.gltf", "low_tuft.gltf", "painted.gltf", "plant.gltf"}) {
        SCOPED_TRACE(file);
        ImportedPlant plant = importGltfPlantWithMaterials(kAssets / file);
        ASSERT_EQ(plant.vertexMaterial.size(), plant.clump.mesh.vertexCount());
        ASSERT_EQ(plant.materials.size(), 1u);
        // Only painted.gltf has a material; the others keep meadow's leaf green.
        EXPECT_EQ(plant.materials[0].leafGreen, std::string(file) != "painted.gltf");
    }
    EXPECT_NEAR(importGltfPlant(kAssets / "reed.gltf").rods[0].restNodes.back().y, 1.8f, 0.2f);
    EXPECT_NEAR(importGltfPlant(kAssets / "low_tuft.gltf").rods[0].restNodes.back().y, 0.15f, 0.03f);
}

TEST(GltfImport, RefusesAClosedSolid) {
    expectRejected("red_cube.gltf", "is a closed solid enclosing 100% of its bounding box (1.00 m³)");
    expectRejected("red_cube.gltf", kNotAPlant);
}

TEST(GltfImport, ClosedButSlenderOrFlatShapesArePlants) {
    // A closed stem 1 m tall, 1 cm in radius: it fills 79% of its box, but is 1% as thick as long.
    std::vector<glm::vec3> p;
    std::vector<uint32_t> ix;
    closedCylinder(0.01f, 1.0f, 12, p, ix);
    EXPECT_NO_THROW(importGltfPlant(writeMesh("closed_stem", p, ix)));
    // The same tube 40 cm wide is a solid lump.
    p.clear(), ix.clear();
    closedCylinder(0.2f, 1.0f, 12, p, ix);
    try {
        importGltfPlant(writeMesh("fat_tube", p, ix));
        FAIL() << "a fat closed tube was imported";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find(kNotAPlant), std::string::npos) << e.what();
    }
    // A double-sided leaf (two sheets sharing their vertices) encloses nothing.
    p = {{-0.05f, 0, 0}, {0.05f, 0, 0}, {0.05f, 0.5f, 0}, {-0.05f, 0.5f, 0}};
    ix = {0, 1, 2, 0, 2, 3, 0, 2, 1, 0, 3, 2};
    EXPECT_NO_THROW(importGltfPlant(writeMesh("double_sided", p, ix)));
    // An open box (the cube without its top) is not closed.
    p = {{0, 0, 0}, {1, 0, 0}, {1, 0, 1}, {0, 0, 1}, {0, 1, 0}, {1, 1, 0}, {1, 1, 1}, {0, 1, 1}};
    ix = {0, 2, 1, 0, 3, 2, 0, 1, 5, 0, 5, 4, 1, 2, 6, 1, 6, 5, 2, 3, 7, 2, 7, 6, 3, 0, 4, 3, 4, 7};
    EXPECT_NO_THROW(importGltfPlant(writeMesh("open_box", p, ix)));
    // ... and with its top it is refused.
    ix.insert(ix.end(), {4, 5, 6, 4, 6, 7});
    EXPECT_THROW(importGltfPlant(writeMesh("closed_box", p, ix)), Error);
}

TEST(GltfImport, StemDiameterSetsStiffnessAndMass) {
    GltfImportOptions options;
    options.stemDiameter = 0.03f;
    const Rod stiff = importGltfPlant(kAssets / "reed.gltf", options).rods[0];
    EXPECT_FLOAT_EQ(stiff.thickness, 0.03f);
    const double rigidity = double(kImportStemModulus) * glm::pi<double>() * std::pow(0.03, 4.0) / 64.0;
    EXPECT_NEAR(stiff.bendRigidity, rigidity, 1e-5 * rigidity);
    EXPECT_NEAR(stiff.linearDensity, kImportStemDensity * glm::pi<float>() * 0.25f * 0.03f * 0.03f, 1e-5f);
    options.stemDiameter = 0.0008f;
    const Rod soft = importGltfPlant(kAssets / "reed.gltf", options).rods[0];
    // Stiffness goes as d^4.
    EXPECT_NEAR(stiff.bendRigidity / soft.bendRigidity, std::pow(0.03 / 0.0008, 4.0), 1.0);
}

TEST(GltfImport, DefaultStemCarriesThePlantsWeight) {
    for (const char* file : {"three_blades.gltf", "reed.gltf", "low_tuft.gltf"}) {
        SCOPED_TRACE(file);
        const PlantClump plant = importGltfPlant(kAssets / file);
        const Rod& rod = plant.rods[0];
        // The foliage: the mesh's one-sided area at the leaf areal density, on the nodes.
        double area = 0.0;
        const PlantMesh& m = plant.mesh;
        for (size_t i = 0; i < m.indices.size(); i += 3)
            area += 0.5 * glm::length(glm::cross(m.positions[m.indices[i + 1]] - m.positions[m.indices[i]],
                                                 m.positions[m.indices[i + 2]] - m.positions[m.indices[i]]));
        double foliage = 0.0;
        ASSERT_EQ(rod.nodeMass.size(), kImportRodNodes);
        for (float mass : rod.nodeMass)
            foliage += mass;
        EXPECT_NEAR(foliage, area * kImportLeafArealDensity, 1e-4 * foliage);
        // Held out level, its weight would bend its tip by kImportDefaultSag of its height.
        const double height = rodLength(rod);
        const double weight = (foliage + double(rod.linearDensity) * height) * 9.81;
        const double sag = weight / height * std::pow(height, 4.0) / (8.0 * rod.bendRigidity);
        EXPECT_NEAR(sag / height, kImportDefaultSag, 1e-3);
        EXPECT_NEAR(rod.bendRigidity, kImportStemModulus * glm::pi<float>() * std::pow(rod.thickness, 4.0f) / 64.0f,
                    1e-4f * rod.bendRigidity);
    }
}

// The sRGB texel nearest to a UV.
glm::ivec4 texelAt(const TextureAtlas& atlas, glm::vec2 uv) {
    const uint32_t x = std::min(static_cast<uint32_t>(uv.x * float(atlas.width)), atlas.width - 1);
    const uint32_t y = std::min(static_cast<uint32_t>(uv.y * float(atlas.height)), atlas.height - 1);
    const uint8_t* p = &atlas.rgba[(size_t(y) * atlas.width + x) * 4];
    return {p[0], p[1], p[2], p[3]};
}

bool insideImportCell(const TextureAtlas& atlas, size_t byte) {
    const AtlasCell cell = importAtlasCell(atlas.width);
    const size_t texel = byte / 4, x = texel % atlas.width, y = texel / atlas.width;
    return x >= cell.x0 && x < cell.x1 && y >= cell.y0 && y < cell.y1;
}

void expectOnlyImportCellChanged(const TextureAtlas& painted, const TextureAtlas& fresh) {
    ASSERT_EQ(painted.rgba.size(), fresh.rgba.size());
    size_t changed = 0;
    for (size_t i = 0; i < fresh.rgba.size(); ++i)
        if (painted.rgba[i] != fresh.rgba[i]) {
            ASSERT_TRUE(insideImportCell(fresh, i)) << "byte " << i << " outside the import cell changed";
            ++changed;
        }
    EXPECT_GT(changed, 0u);
}

TEST(GltfImport, PaintsTheBaseColourTextureIntoTheAtlas) {
    ImportedPlant plant = importGltfPlantWithMaterials(kAssets / "painted.gltf");
    const ImportedMaterial& material = plant.materials[0];
    EXPECT_EQ(material.width, 8u);
    EXPECT_EQ(material.height, 8u);
    EXPECT_FALSE(material.mask);
    const std::vector<glm::vec2> assetUvs = plant.clump.mesh.uvs;
    const TextureAtlas fresh = makeIrisAtlas(256, 3);
    TextureAtlas atlas = fresh;
    paintImportedPlant(plant, atlas);
    expectOnlyImportCellChanged(atlas, fresh);
    // Towards the tips (v = 0) orange, towards the bases (v = 1) blue: the texture's own sRGB bytes
    // times a factor of 1. (At v = 0 and 1 themselves REPEAT blends the two, as the GPU would.)
    size_t tips = 0, bases = 0;
    for (size_t v = 0; v < assetUvs.size(); ++v) {
        const glm::vec2 uv = plant.clump.mesh.uvs[v];
        const glm::ivec4 texel = texelAt(atlas, uv);
        EXPECT_EQ(texel.a, 255);
        if (assetUvs[v].y > 0.1f && assetUvs[v].y < 0.4f) {
            EXPECT_LE(glm::length(glm::vec3(texel) - glm::vec3(255, 140, 0)), 2.0f)
                << texel.r << "," << texel.g << "," << texel.b;
            ++tips;
        } else if (assetUvs[v].y > 0.6f && assetUvs[v].y < 0.9f) {
            EXPECT_LE(glm::length(glm::vec3(texel) - glm::vec3(20, 60, 255)), 2.0f)
                << texel.r << "," << texel.g << "," << texel.b;
            ++bases;
        }
    }
    EXPECT_GT(tips, 0u);
    EXPECT_GT(bases, 0u);
    // Same input, same bytes.
    ImportedPlant again = importGltfPlantWithMaterials(kAssets / "painted.gltf");
    TextureAtlas second = fresh;
    paintImportedPlant(again, second);
    EXPECT_EQ(second.rgba, atlas.rgba);
    EXPECT_EQ(again.clump.mesh.uvs, plant.clump.mesh.uvs);
}

TEST(GltfImport, FactorIsLinearAndMultipliesTheSrgbTexture) {
    nlohmann::json doc = readJson(kAssets / "painted.gltf");
    doc["materials"][0]["pbrMetallicRoughness"]["baseColorFactor"] = {0.5, 1.0, 1.0, 1.0};
    ImportedPlant plant = importGltfPlantWithMaterials(writeJson("half_red.gltf", doc));
    TextureAtlas atlas = makeIrisAtlas(256, 3);
    const std::vector<glm::vec2> assetUvs = plant.clump.mesh.uvs;
    paintImportedPlant(plant, atlas);
    const int halfRed = linearToSrgb(0.5f * srgbToLinear(255)); // 188, not 128
    EXPECT_EQ(halfRed, 188);
    for (size_t v = 0; v < assetUvs.size(); ++v)
        if (assetUvs[v].y > 0.1f && assetUvs[v].y < 0.4f) {
            const glm::ivec4 texel = texelAt(atlas, plant.clump.mesh.uvs[v]);
            EXPECT_NEAR(texel.r, halfRed, 2);
            EXPECT_NEAR(texel.g, 140, 2);
        }
}

TEST(GltfImport, FactorWithoutTextureIsAFlatColour) {
    nlohmann::json doc = readJson(kAssets / "three_blades.gltf");
    doc["materials"] = {{{"name", "red"}, {"pbrMetallicRoughness", {{"baseColorFactor", {0.8, 0.0, 0.0, 1.0}}}}}};
    doc["meshes"][0]["primitives"][0]["material"] = 0;
    ImportedPlant plant = importGltfPlantWithMaterials(writeJson("red_blades.gltf", doc));
    ASSERT_EQ(plant.materials.size(), 1u);
    EXPECT_FALSE(plant.materials[0].leafGreen);
    EXPECT_EQ(plant.materials[0].width, 0u);
    const TextureAtlas fresh = makeIrisAtlas(256, 3);
    TextureAtlas atlas = fresh;
    paintImportedPlant(plant, atlas);
    expectOnlyImportCellChanged(atlas, fresh);
    for (const glm::vec2& uv : plant.clump.mesh.uvs) {
        EXPECT_EQ(uv, plant.clump.mesh.uvs[0]);
        EXPECT_EQ(texelAt(atlas, uv), glm::ivec4(linearToSrgb(0.8f), 0, 0, 255));
    }
}

TEST(GltfImport, NoMaterialKeepsMeadowsLeafGreen) {
    ImportedPlant plant = importGltfPlantWithMaterials(kAssets / "three_blades.gltf");
    const TextureAtlas fresh = makeIrisAtlas(256, 3);
    TextureAtlas atlas = fresh;
    paintImportedPlant(plant, atlas);
    EXPECT_EQ(atlas.rgba, fresh.rgba); // nothing painted
    const AtlasRegion leaf = irisAtlasRegion(PartKind::Leaf);
    for (const glm::vec2& uv : plant.clump.mesh.uvs)
        EXPECT_EQ(uv, 0.5f * (leaf.min + leaf.max));
}

// A synthetic plant of one material with the given UVs, for the painting rules alone.
ImportedPlant syntheticPlant(const ImportedMaterial& material, const std::vector<glm::vec2>& uvs) {
    ImportedPlant plant;
    plant.clump.name = "synthetic";
    plant.clump.mesh.uvs = uvs;
    plant.materials = {material};
    plant.vertexMaterial.assign(uvs.size(), 0);
    return plant;
}

// Two texels across: red on the left (u < 0.5), green on the right; alpha 255 and 0.
ImportedMaterial redGreen(int wrap) {
    ImportedMaterial m;
    m.name = "red-green";
    m.width = 2;
    m.height = 1;
    m.texels = {255, 0, 0, 255, 0, 255, 0, 0};
    m.wrapS = m.wrapT = wrap;
    return m;
}

// Mostly red or mostly green (bilinear filtering of a two-texel texture blends a little).
bool red(glm::ivec4 c) {
    return c.r > 200 && c.g < 100 && c.b == 0;
}
bool green(glm::ivec4 c) {
    return c.g > 200 && c.r < 100 && c.b == 0;
}

// The atlas colour at `u` of the texture, through the plant's own UV mapping (vertex 0 at u0,
// vertex 1 at u1, linear between).
glm::ivec4 colourAtTextureU(const TextureAtlas& atlas, const ImportedPlant& plant, float u0, float u1, float u) {
    const glm::vec2 a = plant.clump.mesh.uvs[0], b = plant.clump.mesh.uvs[1];
    return texelAt(atlas, glm::mix(a, b, (u - u0) / (u1 - u0)));
}

TEST(GltfImport, UvsOutsideTheUnitSquareAreBakedDownOverWholePeriods) {
    TextureAtlas atlas = makeIrisAtlas(256, 3);
    // REPEAT over u 0..3: the cell holds three periods, red-green-red-green-red-green.
    ImportedPlant plant = syntheticPlant(redGreen(10497), {{0.0f, 0.5f}, {3.0f, 0.5f}});
    paintImportedPlant(plant, atlas);
    const AtlasCell cell = importAtlasCell(256);
    EXPECT_GE(plant.clump.mesh.uvs[0].x * 256.0f, float(cell.x0));
    EXPECT_LE(plant.clump.mesh.uvs[1].x * 256.0f, float(cell.x1));
    for (float period : {0.0f, 1.0f, 2.0f}) {
        EXPECT_TRUE(red(colourAtTextureU(atlas, plant, 0.0f, 3.0f, period + 0.25f))) << period;
        EXPECT_TRUE(green(colourAtTextureU(atlas, plant, 0.0f, 3.0f, period + 0.75f))) << period;
    }
    // MIRRORED_REPEAT: the second period is reversed.
    plant = syntheticPlant(redGreen(33648), {{0.0f, 0.5f}, {2.0f, 0.5f}});
    paintImportedPlant(plant, atlas);
    EXPECT_TRUE(red(colourAtTextureU(atlas, plant, 0.0f, 2.0f, 0.25f)));
    EXPECT_TRUE(green(colourAtTextureU(atlas, plant, 0.0f, 2.0f, 1.25f)));
    // UVs within one period away from the unit square (2.2 .. 2.8) get that period alone.
    plant = syntheticPlant(redGreen(10497), {{2.2f, -0.7f}, {2.8f, -0.3f}});
    paintImportedPlant(plant, atlas);
    EXPECT_TRUE(red(colourAtTextureU(atlas, plant, 2.2f, 2.8f, 2.25f)));
    EXPECT_TRUE(green(colourAtTextureU(atlas, plant, 2.2f, 2.8f, 2.75f)));
    // A texture repeated a million times fades to its mean instead of failing or aliasing.
    plant = syntheticPlant(redGreen(10497), {{0.0f, 0.0f}, {1.0e6f, 1.0f}});
    paintImportedPlant(plant, atlas);
    const glm::ivec4 mean = texelAt(atlas, 0.5f * (plant.clump.mesh.uvs[0] + plant.clump.mesh.uvs[1]));
    EXPECT_NEAR(mean.r, linearToSrgb(0.5f), 12);
    EXPECT_NEAR(mean.g, linearToSrgb(0.5f), 12);
}

TEST(GltfImport, MaskCutsOutWhereAlphaIsBelowTheCutoffOpaqueDoesNot) {
    TextureAtlas atlas = makeIrisAtlas(256, 3);
    ImportedMaterial material = redGreen(33071);
    ImportedPlant plant = syntheticPlant(material, {{0.0f, 0.0f}, {1.0f, 1.0f}});
    paintImportedPlant(plant, atlas);
    EXPECT_EQ(colourAtTextureU(atlas, plant, 0.0f, 1.0f, 0.75f).a, 255); // opaque: alpha ignored
    material.mask = true;
    plant = syntheticPlant(material, {{0.0f, 0.0f}, {1.0f, 1.0f}});
    paintImportedPlant(plant, atlas);
    EXPECT_EQ(colourAtTextureU(atlas, plant, 0.0f, 1.0f, 0.25f).a, 255);
    EXPECT_EQ(colourAtTextureU(atlas, plant, 0.0f, 1.0f, 0.75f).a, 0);
    // The cutoff applies to the texture's alpha times the factor's.
    material.factor.a = 0.4f;
    plant = syntheticPlant(material, {{0.0f, 0.0f}, {1.0f, 1.0f}});
    paintImportedPlant(plant, atlas);
    EXPECT_EQ(colourAtTextureU(atlas, plant, 0.0f, 1.0f, 0.25f).a, 0);
    // Through the importer: alphaMode MASK and alphaCutoff are read.
    nlohmann::json doc = readJson(kAssets / "painted.gltf");
    doc["materials"][0]["alphaMode"] = "MASK";
    doc["materials"][0]["alphaCutoff"] = 0.3;
    ImportedPlant masked = importGltfPlantWithMaterials(writeJson("masked.gltf", doc));
    EXPECT_TRUE(masked.materials[0].mask);
    EXPECT_FLOAT_EQ(masked.materials[0].alphaCutoff, 0.3f);
}

TEST(GltfImport, SeveralMaterialsGetCellsOfTheirOwn) {
    nlohmann::json doc = readJson(kAssets / "painted.gltf");
    // A second primitive: the same blades under a flat yellow material.
    doc["materials"].push_back({{"name", "yellow"}, {"pbrMetallicRoughness", {{"baseColorFactor", {1, 1, 0, 1}}}}});
    nlohmann::json second = doc["meshes"][0]["primitives"][0];
    second["material"] = 1;
    doc["meshes"][0]["primitives"].push_back(second);
    ImportedPlant plant = importGltfPlantWithMaterials(writeJson("two_materials.gltf", doc));
    ASSERT_EQ(plant.materials.size(), 2u);
    TextureAtlas atlas = makeIrisAtlas(256, 3);
    paintImportedPlant(plant, atlas);
    const size_t half = plant.clump.mesh.vertexCount() / 2;
    for (size_t v = 0; v < half; ++v)
        EXPECT_NE(texelAt(atlas, plant.clump.mesh.uvs[v]), glm::ivec4(255, 255, 0, 255));
    for (size_t v = half; v < 2 * half; ++v)
        EXPECT_EQ(texelAt(atlas, plant.clump.mesh.uvs[v]), glm::ivec4(255, 255, 0, 255));
}

std::string pngBytesOf(const nlohmann::json& painted) {
    const std::string uri = painted["images"][0]["uri"];
    const std::string text = uri.substr(uri.find(',') + 1);
    std::string bytes;
    uint32_t bits = 0;
    int count = 0;
    for (char c : text) {
        const char* alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
        const char* at = std::strchr(alphabet, c);
        if (c == '=' || at == nullptr)
            break;
        bits = (bits << 6) | static_cast<uint32_t>(at - alphabet);
        if (++count % 4 == 0) {
            bytes.push_back(static_cast<char>(bits >> 16));
            bytes.push_back(static_cast<char>(bits >> 8));
            bytes.push_back(static_cast<char>(bits));
            bits = 0;
        }
    }
    if (count % 4 == 2)
        bytes.push_back(static_cast<char>(bits >> 4));
    if (count % 4 == 3) {
        bytes.push_back(static_cast<char>(bits >> 10));
        bytes.push_back(static_cast<char>(bits >> 2));
    }
    return bytes;
}

TEST(GltfImport, ReadsExternalPngAndJpegImages) {
    nlohmann::json doc = readJson(kAssets / "painted.gltf");
    std::ofstream(scratch("painted texture.png"), std::ios::binary) << pngBytesOf(doc);
    doc["images"][0]["uri"] = "painted%20texture.png";
    ImportedPlant png = importGltfPlantWithMaterials(writeJson("external_png.gltf", doc));
    EXPECT_EQ(png.materials[0].width, 8u);
    EXPECT_EQ(png.materials[0].texels[0], 255); // orange, row 0
    // A JPEG written here (4 x 4, one colour: JPEG keeps flat colours within a step or two).
    const std::filesystem::path jpeg = scratch("flat.jpg");
    {
        auto out = OIIO::ImageOutput::create(jpeg.string());
        ASSERT_TRUE(out);
        std::vector<uint8_t> pixels(4 * 4 * 3);
        for (size_t i = 0; i < pixels.size(); i += 3)
            pixels[i] = 200, pixels[i + 1] = 100, pixels[i + 2] = 50;
        OIIO::ImageSpec spec(4, 4, 3, OIIO::TypeDesc::UINT8);
        spec.attribute("CompressionQuality", 100);
        ASSERT_TRUE(out->open(jpeg.string(), spec) && out->write_image(OIIO::TypeDesc::UINT8, pixels.data()) &&
                    out->close());
    }
    doc["images"][0]["uri"] = "flat.jpg";
    ImportedPlant jpg = importGltfPlantWithMaterials(writeJson("external_jpg.gltf", doc));
    ASSERT_EQ(jpg.materials[0].width, 4u);
    EXPECT_NEAR(jpg.materials[0].texels[0], 200, 3);
    EXPECT_NEAR(jpg.materials[0].texels[1], 100, 3);
    EXPECT_NEAR(jpg.materials[0].texels[2], 50, 3);
    EXPECT_EQ(jpg.materials[0].texels[3], 255);
}

void expectImageRefused(const nlohmann::json& doc, const std::string& name, const std::string& reason) {
    const std::filesystem::path path = writeJson(name, doc);
    try {
        importGltfPlantWithMaterials(path);
        FAIL() << name << " was imported";
    } catch (const Error& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find(path.string()), std::string::npos) << message;
        EXPECT_NE(message.find(reason), std::string::npos) << message;
    }
}

TEST(GltfImport, RefusesImagesItCannotDecode) {
    nlohmann::json doc = readJson(kAssets / "painted.gltf");
    doc["images"][0]["uri"] = "data:image/png;base64," + base64("not an image at all");
    expectImageRefused(doc, "garbage_image.gltf",
                       "material 'painted' base colour texture: image 0 is neither PNG nor JPEG");
    doc["images"][0]["uri"] = "data:image/png;base64," + base64(std::string("\x89PNG\r\n\x1a\n", 8) + "broken");
    expectImageRefused(doc, "broken_png.gltf", "material 'painted' base colour texture: image 0 cannot be decoded");
    doc["images"][0]["uri"] = "missing.png";
    expectImageRefused(doc, "missing_image.gltf", "image 0 ('missing.png') cannot be read (no such file?)");
    doc = readJson(kAssets / "painted.gltf");
    doc["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]["texCoord"] = 1;
    expectImageRefused(doc, "texcoord1.gltf", "uses TEXCOORD_1; meadow reads only TEXCOORD_0");
    // An unused image is never decoded: the plant imports.
    doc = readJson(kAssets / "three_blades.gltf");
    doc["images"] = {{{"uri", "data:image/png;base64," + base64("not an image")}}};
    EXPECT_NO_THROW(importGltfPlantWithMaterials(writeJson("unused_image.gltf", doc)));
}

} // namespace
} // namespace meadow
