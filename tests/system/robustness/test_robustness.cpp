// Robustness (issue 10) in-process: a stale or corrupt library cache is rebuilt, never trusted,
// and the rebuild gives the same bytes; loader checks that the command-line corpus cannot reach
// easily; the memory check's arithmetic. The bad-input corpus itself runs through the command
// line (corpus.cmake), the fuzzers in tests/system/fuzz.
#include "core/error.h"
#include "library/library_file.h"
#include "library/motion_basis.h"
#include "pipeline/build_library.h"
#include "plants/gltf_import.h"
#include "vk/memory_budget.h"

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace meadow {
namespace {

const std::filesystem::path kCorpus = std::filesystem::path(MEADOW_SOURCE_DIR) / "tests/system/robustness";

std::filesystem::path tempDir(const std::string& name) {
    std::filesystem::path dir = std::filesystem::temp_directory_path() / "meadow-robustness" / name;
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    return dir;
}

std::vector<uint8_t> readAll(const std::filesystem::path& p) {
    std::ifstream in(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void writeAll(const std::filesystem::path& p, const std::vector<uint8_t>& bytes) {
    std::ofstream(p, std::ios::binary)
        .write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
}

// MEADOW_CACHE_DIR pointed at a fresh folder for one test, restored afterwards.
class ScopedCache {
  public:
    explicit ScopedCache(const std::string& name) : dir_(tempDir(name)) {
        if (const char* old = std::getenv("MEADOW_CACHE_DIR"))
            old_ = old;
        setenv("MEADOW_CACHE_DIR", dir_.c_str(), 1);
    }
    ~ScopedCache() {
        if (old_.empty())
            unsetenv("MEADOW_CACHE_DIR");
        else
            setenv("MEADOW_CACHE_DIR", old_.c_str(), 1);
    }
    const std::filesystem::path& dir() const { return dir_; }

  private:
    std::filesystem::path dir_;
    std::string old_;
};

// Each way a cached library can be unusable: the file at the cache path after `spoil`.
struct Spoiled {
    const char* name;
    void (*spoil)(const std::filesystem::path& path, const std::vector<uint8_t>& good,
                  const std::vector<uint8_t>& other);
};

const Spoiled kSpoiled[] = {
    {"a flipped bit in a section",
     [](auto& path, auto& good, auto&) {
         std::vector<uint8_t> bytes = good;
         bytes[bytes.size() / 2] ^= 0x04;
         writeAll(path, bytes);
     }},
    {"truncated to its header",
     [](auto& path, auto& good, auto&) { writeAll(path, std::vector<uint8_t>(good.begin(), good.begin() + 40)); }},
    {"an older format version",
     [](auto& path, auto& good, auto&) {
         std::vector<uint8_t> bytes = good;
         bytes[8] = uint8_t(kLibraryFormatVersion - 1); // little-endian u32 after the magic
         writeAll(path, bytes);
     }},
    {"another scene's library under this name", [](auto& path, auto&, auto& other) { writeAll(path, other); }},
    {"the right header over garbage",
     [](auto& path, auto& good, auto&) {
         std::vector<uint8_t> bytes(good.begin(), good.begin() + 32); // magic, version, count, input hash
         bytes.resize(good.size(), 0xa5);
         writeAll(path, bytes);
     }},
    {"empty", [](auto& path, auto&, auto&) { writeAll(path, {}); }},
};

TEST(Robustness, UnusableCacheIsRebuiltToTheSameBytes) {
    ScopedCache cache("cache");
    const std::filesystem::path micro = kCorpus / "micro.json";
    const Scene scene = loadScene(micro, "ci", std::nullopt);
    // Another scene's library: the same file in the other preset (its inputs, so its bytes, differ).
    const Scene otherScene = loadScene(micro, "full", std::nullopt);
    const std::filesystem::path path = cachedLibraryPath(scene);
    const Library first = ensureLibrary(scene, true);
    const std::vector<uint8_t> good = readAll(path);
    ensureLibrary(otherScene, true);
    const std::vector<uint8_t> other = readAll(cachedLibraryPath(otherScene));
    ASSERT_FALSE(good.empty());
    ASSERT_NE(good, other); // so that a library kept instead of rebuilt shows below

    for (const Spoiled& s : kSpoiled) {
        SCOPED_TRACE(s.name);
        s.spoil(path, good, other);
        ASSERT_NE(readAll(path), good);
        const Library rebuilt = ensureLibrary(scene, true);
        // Rebuilt whole, not patched or trusted: the same bytes as the first build (determinism).
        EXPECT_EQ(readAll(path), good);
        EXPECT_EQ(rebuilt.inputHash, first.inputHash);
        EXPECT_EQ(rebuilt.field.clumpInstances.size(), first.field.clumpInstances.size());
    }
    // Nothing but the two libraries is left in the cache (no partial files).
    size_t files = 0;
    for (const auto& entry : std::filesystem::directory_iterator(cache.dir())) {
        EXPECT_EQ(entry.path().extension(), ".mlib") << entry.path();
        ++files;
    }
    EXPECT_EQ(files, 2u);
}

TEST(Robustness, LibraryBytesAreTheSameForTheSameSceneAndSeed) {
    const std::filesystem::path dir = tempDir("determinism");
    const Scene scene = loadScene(kCorpus / "micro.json", "ci", std::nullopt);
    buildLibrary(scene, dir / "a.mlib", true);
    buildLibrary(scene, dir / "b.mlib", true);
    EXPECT_EQ(readAll(dir / "a.mlib"), readAll(dir / "b.mlib"));
    // The control: other inputs give other bytes (the comparison is not vacuous).
    buildLibrary(loadScene(kCorpus / "micro.json", "full", std::nullopt), dir / "c.mlib", true);
    EXPECT_NE(readAll(dir / "a.mlib"), readAll(dir / "c.mlib"));
}

// Motion blocks whose ranks sum past 2^32: with 32-bit sums they wrapped around to match the
// stored mode count while the second block's coordinates lay 4 billion values past each frame's.
TEST(Robustness, MotionBlocksWhoseRanksOverflowAreRefused) {
    MotionBasis basis;
    basis.frames = 1;
    basis.lodModes.fill(1);
    MotionBlock huge, small;
    huge.coordOffset = 0;
    huge.ranks.fill(0xffffffffu);
    small.coordOffset = 0xffffffffu;
    small.ranks.fill(2u);
    basis.blocks = {huge, small};
    basis.vertexBlock = {1};
    basis.basis.assign(6, 0.0f);
    basis.coords.assign(1, 0.0f);
    basis.relativeErrorPerMode.assign(2, 0.0);
    try {
        basis.finish("test basis");
        FAIL() << "a basis whose blocks need 2^32 + 1 modes was accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("LOD 0 counts 1 motion modes, its blocks 4294967297"), std::string::npos)
            << e.what();
    }
    // The same basis with honest ranks is fine: the check is not refusing everything.
    basis.blocks = {small};
    basis.blocks[0].coordOffset = 0;
    basis.vertexBlock = {0};
    basis.lodModes.fill(2);
    basis.coords.assign(2, 0.0f);
    basis.relativeErrorPerMode.assign(3, 0.0);
    EXPECT_NO_THROW(basis.finish("test basis"));
}

// A node that flattens the plant along z has no inverse transpose: its normals used to come out
// as NaN and the plant was refused as "not finite"; they now fall back to +y.
TEST(Robustness, FlatteningTransformGivesFiniteNormals) {
    nlohmann::json doc = nlohmann::json::parse(std::ifstream(kCorpus / "gltf/valid_plant.gltf"));
    doc["nodes"][0]["scale"] = {1.0, 1.0, 0.0};
    const std::filesystem::path file = tempDir("flat") / "flat.gltf";
    std::ofstream(file) << doc.dump();
    const PlantClump plant = importGltfPlant(file);
    ASSERT_EQ(plant.mesh.normals.size(), 10u);
    for (const glm::vec3& n : plant.mesh.normals) {
        EXPECT_TRUE(std::isfinite(n.x) && std::isfinite(n.y) && std::isfinite(n.z));
        EXPECT_NEAR(glm::length(n), 1.0f, 1e-5f); // unit length up to float rounding
    }
}

// The memory check's arithmetic and message (the device figures come from tests/system/robustness/
// test_memory_budget_device.cpp on lavapipe).
TEST(MemoryBudget, MessageSaysWhatIsNeededAndWhatThereIs) {
    DeviceMemoryFigures figures;
    figures.deviceName = "test GPU";
    figures.heapIndex = 1;
    figures.heapBytes = 8ull << 30;
    figures.availableBytes = 6ull << 30;
    figures.fromBudget = true;
    EXPECT_NO_THROW(checkMemoryFits(6ull << 30, figures, "the field"));
    try {
        checkMemoryFits((6ull << 30) + 1, figures, "the field");
        FAIL() << "one byte more than available was accepted";
    } catch (const Error& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find("the field needs 6144.0 MiB of GPU memory; the device has 8192.0 MiB (test GPU, heap 1, "
                               "6144.0 MiB of it available to meadow now"),
                  std::string::npos)
            << message;
    }
    figures.fromBudget = false;
    try {
        checkMemoryFits(100ull << 30, figures, "a field of 50000000 clumps");
        FAIL();
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("a field of 50000000 clumps needs 102400.0 MiB of GPU memory; the device "
                                             "has 8192.0 MiB"),
                  std::string::npos)
            << e.what();
        EXPECT_NE(std::string(e.what()).find("90% of the heap"), std::string::npos) << e.what();
    }
}

} // namespace
} // namespace meadow
