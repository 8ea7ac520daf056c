#include "core/error.h"
#include "library/library_file.h"
#include "pipeline/build_library.h"

#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>

using namespace meadow;

namespace {

std::filesystem::path tempPath(const std::string& name) {
    std::filesystem::path dir = std::filesystem::temp_directory_path() / "meadow-unit-library";
    std::filesystem::create_directories(dir);
    return dir / name;
}

std::vector<uint8_t> readAll(const std::filesystem::path& p) {
    std::ifstream in(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void writeAll(const std::filesystem::path& p, const std::vector<uint8_t>& bytes) {
    std::ofstream(p, std::ios::binary)
        .write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
}

std::string readError(const std::filesystem::path& p) {
    try {
        readLibraryFile(p);
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

} // namespace

TEST(LibraryFile, GoldenBytesPinTheFormat) {
    // One tiny section: header, one table entry, 8-byte aligned payload. If this changes, the
    // format changed: bump kLibraryFormatVersion.
    LibraryFile lib;
    lib.inputHash = 0x0102030405060708ull;
    lib.sections["ABCD"] = {0xAA, 0xBB};
    auto p = tempPath("golden.mlib");
    writeLibraryFile(p, lib);
    std::vector<uint8_t> bytes = readAll(p);
    ASSERT_EQ(bytes.size(), 32u + 32u + 2u);
    const uint8_t header[16] = {'M', 'E', 'A', 'D', 'O', 'W', 'L', 'B', 9, 0, 0, 0, 1, 0, 0, 0};
    EXPECT_EQ(std::vector<uint8_t>(bytes.begin(), bytes.begin() + 16), std::vector<uint8_t>(header, header + 16));
    EXPECT_EQ(bytes[16], 0x08); // inputHash, little-endian
    EXPECT_EQ(bytes[23], 0x01);
    EXPECT_EQ(std::string(bytes.begin() + 32, bytes.begin() + 36), "ABCD");
    EXPECT_EQ(bytes[40], 64); // payload offset
    EXPECT_EQ(bytes[48], 2);  // payload size
    EXPECT_EQ(bytes[64], 0xAA);
    EXPECT_EQ(bytes[65], 0xBB);
    EXPECT_EQ(fnv1a64("a", 1), 0xaf63dc4c8601ec8cull); // FNV-1a 64 reference value
}

TEST(LibraryFile, RoundTrips) {
    LibraryFile lib;
    lib.inputHash = 42;
    lib.sections["ONE_"] = {1, 2, 3};
    lib.sections["TWO_"] = std::vector<uint8_t>(1000, 7);
    auto p = tempPath("roundtrip.mlib");
    writeLibraryFile(p, lib);
    LibraryFile back = readLibraryFile(p);
    EXPECT_EQ(back.inputHash, 42u);
    EXPECT_EQ(back.sections, lib.sections);
    uint64_t hash = 0;
    EXPECT_TRUE(peekLibraryInputHash(p, hash));
    EXPECT_EQ(hash, 42u);
}

TEST(LibraryFile, RejectsCorruptionNamingTheFile) {
    LibraryFile lib;
    lib.sections["DATA"] = std::vector<uint8_t>(100, 9);
    auto good = tempPath("good.mlib");
    writeLibraryFile(good, lib);
    std::vector<uint8_t> bytes = readAll(good);

    auto flipped = tempPath("flipped.mlib");
    std::vector<uint8_t> f = bytes;
    f[f.size() - 10] ^= 1; // one bit in the payload
    writeAll(flipped, f);
    std::string e = readError(flipped);
    EXPECT_NE(e.find("flipped.mlib"), std::string::npos) << e;
    EXPECT_NE(e.find("checksum mismatch"), std::string::npos) << e;

    auto truncated = tempPath("truncated.mlib");
    writeAll(truncated, std::vector<uint8_t>(bytes.begin(), bytes.end() - 20));
    EXPECT_NE(readError(truncated).find("outside the file"), std::string::npos);

    auto magic = tempPath("magic.mlib");
    f = bytes;
    f[0] = 'X';
    writeAll(magic, f);
    EXPECT_NE(readError(magic).find("bad magic"), std::string::npos);

    auto version = tempPath("version.mlib");
    f = bytes;
    f[8] = 99;
    writeAll(version, f);
    EXPECT_NE(readError(version).find("format version 99"), std::string::npos);

    auto table = tempPath("table.mlib");
    f = bytes;
    f[40] ^= 0x10; // section offset
    writeAll(table, f);
    EXPECT_NE(readError(table).find("section table checksum"), std::string::npos);

    auto empty = tempPath("empty.mlib");
    writeAll(empty, {});
    EXPECT_NE(readError(empty).find("too short"), std::string::npos);
    EXPECT_NE(readError(tempPath("absent.mlib")).find("cannot open"), std::string::npos);
}

TEST(LibraryFile, HalfFloatsRoundTripWithinHalfPrecision) {
    const std::vector<float> values = {0.0f, 1.0f, -2.5f, 0.0021f, 3.0e-6f, 65504.0f, -1.0e-3f};
    ByteWriter w;
    w.f16s(values);
    std::vector<uint8_t> bytes = w.take();
    ASSERT_EQ(bytes.size(), 4u + 2u * values.size());
    EXPECT_EQ(bytes[4 + 2], 0x00); // 1.0 is 0x3c00, little-endian
    EXPECT_EQ(bytes[4 + 3], 0x3c);
    ByteReader r(bytes, "test");
    std::vector<float> back = r.f16s();
    ASSERT_EQ(back.size(), values.size());
    for (size_t i = 0; i < values.size(); ++i) {
        // Half precision: 11 significant bits for normal values, steps of 2^-24 below 2^-14.
        const float tolerance = std::max(std::abs(values[i]) * 1.0f / 1024.0f, 1.0f / 16777216.0f);
        EXPECT_NEAR(back[i], values[i], tolerance) << i;
    }
}

TEST(Library, SameSceneAndSeedGiveTheSameBytes) {
    const char* tiny = MEADOW_SOURCE_DIR "/tests/data/scenes/tiny.json";
    Scene scene = loadScene(tiny, "ci", std::nullopt);
    auto a = tempPath("det-a.mlib"), b = tempPath("det-b.mlib"), c = tempPath("det-c.mlib");
    buildLibrary(scene, a, true);
    buildLibrary(scene, b, true);
    EXPECT_EQ(readAll(a), readAll(b));
    Scene other = loadScene(tiny, "ci", scene.seed + 1);
    buildLibrary(other, c, true);
    EXPECT_NE(readAll(a), readAll(c));
    EXPECT_NE(libraryInputHash(scene), libraryInputHash(other));

    Library lib = loadLibrary(a);
    // The field: voxel-packed Wang tiles, none overlapping, on the terrain.
    EXPECT_GT(lib.field.clumpInstances.size(), 4u);
    EXPECT_EQ(lib.field.stats.tilesX, scene.field.tilesX);
    EXPECT_EQ(lib.field.stats.overlapViolations, 0u);
    EXPECT_EQ(lib.field.stats.overlapViolations3d, 0u);
    EXPECT_EQ(lib.field.rocks.size(), size_t(scene.field.rockVariants));
    // Rocks: five LODs made in the precompute, LOD 0 the whole mesh, each far one no larger.
    for (const LibraryRock& rock : lib.field.rocks) {
        EXPECT_EQ(rock.lods[0].indices.size(), rock.mesh.indices.size()) << rock.mesh.name;
        EXPECT_EQ(rock.lods[0].vertices.size(), rock.mesh.positions.size()) << rock.mesh.name;
        EXPECT_LT(rock.lods[kLodCount - 1].indices.size(), rock.mesh.indices.size()) << rock.mesh.name;
        for (uint32_t l = 1; l < kLodCount; ++l)
            EXPECT_LE(rock.lods[l].indices.size(), rock.lods[l - 1].indices.size()) << rock.mesh.name << " LOD " << l;
    }
    const Terrain terrain(lib.field.terrain);
    for (const gpu::GpuInstance& inst : lib.field.clumpInstances) {
        EXPECT_NEAR(inst.positionScale.y, terrain.height(inst.positionScale.x, inst.positionScale.z), 1e-5f);
        EXPECT_EQ(std::abs(inst.positionScale.w), 1.0f);
    }
    ASSERT_EQ(lib.clumps.size(), 1u);
    const LibraryClump& clump = lib.clumps[0];
    EXPECT_GT(clump.mesh.indices.size(), 0u);
    // Every vertex lies inside the bounding sphere the cull pass uses.
    for (const auto& v : clump.mesh.vertices)
        EXPECT_LE(glm::length(glm::vec3(v.positionU) - glm::vec3(0, clump.mesh.boundingRadius * 0.5f, 0)),
                  clump.mesh.boundingRadius * (1.0f + 1e-6f));
    // Motion: both levels recorded, reduced within the scene's bound, a connected graph.
    EXPECT_EQ(clump.motion.frames, 2u * 45u);
    EXPECT_LE(clump.motion.relativeErrorPerMode[clump.motion.lodModes[0]], 0.05 + 1e-6);
    // One motion block per rod: a vertex pays for its own rod's modes, far fewer than the clump's.
    EXPECT_GT(clump.motion.blocks.size(), 1u);
    EXPECT_LT(clump.motion.maxBlockRank(0), clump.motion.lodModes[0]);
    EXPECT_TRUE(clump.graph.stronglyConnected);
    EXPECT_GT(lib.atlas.width, 0u);
    // The day of sky: the preset's frames in time order, each with order-3 RGB SH and its backdrop.
    ASSERT_EQ(lib.sky.frames.size(), scene.sky.params.frames);
    EXPECT_FALSE(lib.skyFromMaps);
    EXPECT_EQ(lib.sky.frames[0].sh.size(), 27u);
    EXPECT_EQ(lib.sky.frames[0].image.size(), size_t(lib.sky.imageWidth) * lib.sky.imageHeight * 3);
    // Light: transfer of both sides of every vertex, RGB, order 3, with its displacement gradient;
    // the ground grid's mean transfer, with what modes would gain; held-out errors measured.
    const LibraryLight& light = clump.light;
    EXPECT_EQ(light.order, 3);
    EXPECT_EQ(light.vertices.vertexCount, clump.mesh.vertices.size());
    EXPECT_EQ(light.vertices.valuesPerVertex, 2u * 3u * 9u);
    EXPECT_GE(light.bakedFrames.size(), 4u);
    EXPECT_GT(light.groundResolution, 1u);
    EXPECT_EQ(light.ground.mean.size(), size_t(light.groundResolution) * light.groundResolution * 3u * 9u);
    EXPECT_GE(light.ground.relativeErrorPerMode.size(), 1u);
    EXPECT_GT(light.vertexNoise, 0.0);
    EXPECT_GT(light.vertexHeldOutError, 0.0);
    EXPECT_LT(light.vertexHeldOutError, 0.5);
    // Five levels of detail, each fewer triangles than the one before, errors growing, LOD 0 the
    // full mesh.
    EXPECT_EQ(clump.lods[0].indices.size(), clump.mesh.indices.size());
    EXPECT_LT(clump.lods[0].error.deformed.rms, 1e-6); // metres: sampling the same surface twice
    for (uint32_t l = 1; l < kLodCount; ++l) {
        EXPECT_LT(clump.lods[l].indices.size(), clump.lods[l - 1].indices.size()) << "LOD " << l;
        EXPECT_GE(clump.lods[l].error.deformed.rms, clump.lods[l - 1].error.deformed.rms) << "LOD " << l;
        EXPECT_GE(clump.lods[l].error.rest.hausdorff, clump.lods[l - 1].error.rest.hausdorff) << "LOD " << l;
    }
    // Noon is brighter than midnight (c00 of green).
    EXPECT_GT(lib.sky.frames[lib.sky.frames.size() / 2].sh[1], 100.0f * lib.sky.frames[0].sh[1]);
    // The far field's surface samples (FARS): the ci preset's 1024 per clump and rock over LOD 0's
    // whole area (the iris atlas cuts nothing out), each playing a vertex of the last LOD.
    auto checkFar = [](const FarSamples& far, const std::vector<uint32_t>& lastLod, size_t vertices, double area,
                       const std::string& name) {
        EXPECT_EQ(far.samples.size(), 1024u) << name;
        EXPECT_NEAR(far.area, area, area * 1e-4) << name;
        std::vector<bool> isFar(vertices, false);
        for (uint32_t v : lastLod)
            isFar[v] = true;
        for (const FarSample& s : far.samples)
            ASSERT_TRUE(s.vertex < vertices && isFar[s.vertex]) << name << " plays vertex " << s.vertex;
    };
    auto meshArea = [](auto position, const std::vector<uint32_t>& indices) {
        double area = 0.0;
        for (size_t t = 0; t < indices.size(); t += 3)
            area += 0.5 * glm::length(glm::cross(position(indices[t + 1]) - position(indices[t]),
                                                 position(indices[t + 2]) - position(indices[t])));
        return area;
    };
    checkFar(clump.far, clump.lods[kLodCount - 1].vertices, clump.mesh.vertices.size(),
             meshArea([&](uint32_t v) { return glm::vec3(clump.mesh.vertices[v].positionU); }, clump.mesh.indices),
             clump.name);
    for (const LibraryRock& rock : lib.field.rocks)
        checkFar(rock.far, rock.lods[kLodCount - 1].vertices, rock.mesh.positions.size(),
                 meshArea([&](uint32_t v) { return rock.mesh.positions[v]; }, rock.mesh.indices), rock.mesh.name);
}

TEST(Library, CorruptCacheIsRebuiltNotTrusted) {
    auto dir = tempPath("cache");
    std::filesystem::remove_all(dir);
    setenv("MEADOW_CACHE_DIR", dir.c_str(), 1);
    Scene scene = loadScene(MEADOW_SOURCE_DIR "/tests/data/scenes/tiny.json", "ci", std::nullopt);
    Library first = ensureLibrary(scene, true);
    auto path = cachedLibraryPath(scene);
    std::vector<uint8_t> bytes = readAll(path);
    bytes[bytes.size() - 5] ^= 0xff;
    writeAll(path, bytes);
    EXPECT_THROW(loadLibrary(path), Error);
    Library second = ensureLibrary(scene, true);
    EXPECT_EQ(second.field.clumpInstances.size(), first.field.clumpInstances.size());
    EXPECT_NO_THROW(loadLibrary(path)); // the cache was rewritten whole
    unsetenv("MEADOW_CACHE_DIR");
}
