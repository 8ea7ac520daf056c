#include "library.h"

#include "core/error.h"
#include "core/library_file.h"
#include "random.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace meadow {
namespace {

// Bump when what precompute produces changes for the same inputs.
constexpr uint32_t kPrecomputeVersion = 1;

std::string hex(uint64_t v) {
    char buf[17];
    std::snprintf(buf, sizeof(buf), "%016llx", static_cast<unsigned long long>(v));
    return buf;
}

} // namespace

uint64_t libraryInputHash(const Scene& scene) {
    std::string key = scene.resolved.dump() + "|" + scene.preset + "|" + std::to_string(scene.seed) + "|" +
                      std::to_string(kLibraryFormatVersion) + "|" + std::to_string(kPrecomputeVersion);
    return fnv1a64(key.data(), key.size());
}

std::vector<gpu::GpuInstance> placeTestField(const Scene& scene, float meshRadius) {
    const TestFieldParams& p = scene.testField;
    Random rng(scene.seed ^ 0x7465737466696c64ull); // "testfild"
    std::vector<gpu::GpuInstance> out;
    out.reserve(size_t(p.countX) * p.countZ);
    float originX = -0.5f * p.spacing * static_cast<float>(p.countX - 1);
    float originZ = -0.5f * p.spacing * static_cast<float>(p.countZ - 1);
    for (uint32_t z = 0; z < p.countZ; ++z) {
        for (uint32_t x = 0; x < p.countX; ++x) {
            gpu::GpuInstance inst{};
            float jx = rng.uniform(-p.jitter, p.jitter) * p.spacing;
            float jz = rng.uniform(-p.jitter, p.jitter) * p.spacing;
            float scale = rng.uniform(p.scaleMin, p.scaleMax);
            float yaw = rng.uniform(0.0f, 6.2831853f);
            float hue = rng.uniform();
            inst.positionScale =
                glm::vec4(originX + p.spacing * float(x) + jx, 0.0f, originZ + p.spacing * float(z) + jz, scale);
            inst.boundsTint = glm::vec4(meshRadius, yaw, hue, 0.0f);
            out.push_back(inst);
        }
    }
    return out;
}

void buildLibrary(const Scene& scene, const std::filesystem::path& path, bool quiet) {
    auto start = std::chrono::steady_clock::now();
    if (!quiet)
        std::fprintf(stderr, "meadow: precompute %s (preset %s, seed %llu)\n", scene.name.c_str(), scene.preset.c_str(),
                     static_cast<unsigned long long>(scene.seed));
    LibraryFile file;
    file.inputHash = libraryInputHash(scene);
    std::string sceneText = scene.resolved.dump(2);
    file.sections["SCNE"] = std::vector<uint8_t>(sceneText.begin(), sceneText.end());

    if (!quiet)
        std::fprintf(stderr, "meadow: [1/2] stand-in plant mesh\n");
    Mesh mesh = makeTuftMesh();
    {
        ByteWriter w;
        w.u32(static_cast<uint32_t>(mesh.vertices.size()));
        w.u32(static_cast<uint32_t>(mesh.indices.size()));
        w.f32(mesh.boundingRadius);
        for (const gpu::GpuVertex& v : mesh.vertices)
            for (int i = 0; i < 4; ++i)
                w.f32(v.positionU[i]);
        for (const gpu::GpuVertex& v : mesh.vertices)
            for (int i = 0; i < 4; ++i)
                w.f32(v.normalV[i]);
        for (uint32_t index : mesh.indices)
            w.u32(index);
        file.sections["TMSH"] = w.take();
    }

    if (!quiet)
        std::fprintf(stderr, "meadow: [2/2] test field: %u x %u instances\n", scene.testField.countX,
                     scene.testField.countZ);
    std::vector<gpu::GpuInstance> field = placeTestField(scene, mesh.boundingRadius);
    ByteWriter w;
    w.u32(static_cast<uint32_t>(field.size()));
    for (const gpu::GpuInstance& inst : field) {
        for (int i = 0; i < 4; ++i)
            w.f32(inst.positionScale[i]);
        for (int i = 0; i < 4; ++i)
            w.f32(inst.boundsTint[i]);
    }
    file.sections["TFLD"] = w.take();

    std::error_code ec;
    if (!path.parent_path().empty())
        std::filesystem::create_directories(path.parent_path(), ec);
    writeLibraryFile(path, file);
    if (!quiet) {
        double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        std::fprintf(stderr, "meadow: wrote %s in %.2f s\n", path.string().c_str(), seconds);
    }
}

Library loadLibrary(const std::filesystem::path& path) {
    LibraryFile file = readLibraryFile(path);
    const std::string where = "library " + path.string();
    Library lib;
    lib.formatVersion = file.formatVersion;
    lib.inputHash = file.inputHash;
    lib.fileBytes = file.fileBytes;
    for (const auto& [tag, bytes] : file.sections)
        lib.sections.push_back(tag);

    auto section = [&](const char* tag) -> const std::vector<uint8_t>& {
        auto it = file.sections.find(tag);
        if (it == file.sections.end())
            throw Error(where + ": section '" + tag + "' is missing");
        return it->second;
    };
    const std::vector<uint8_t>& sceneBytes = section("SCNE");
    try {
        lib.scene = nlohmann::json::parse(sceneBytes.begin(), sceneBytes.end());
    } catch (const nlohmann::json::exception& e) {
        throw Error(where + ": section 'SCNE' is not valid JSON: " + e.what());
    }

    {
        ByteReader m(section("TMSH"), where + ": section 'TMSH'");
        uint32_t vertexCount = m.u32(), indexCount = m.u32();
        lib.testMesh.boundingRadius = m.f32();
        if (uint64_t(vertexCount) * 32 + uint64_t(indexCount) * 4 != m.remaining() || indexCount % 3 != 0 ||
            !(lib.testMesh.boundingRadius > 0.0f))
            throw Error(where + ": section 'TMSH' is inconsistent");
        lib.testMesh.vertices.resize(vertexCount);
        for (gpu::GpuVertex& v : lib.testMesh.vertices)
            for (int i = 0; i < 4; ++i)
                v.positionU[i] = m.f32();
        for (gpu::GpuVertex& v : lib.testMesh.vertices)
            for (int i = 0; i < 4; ++i)
                v.normalV[i] = m.f32();
        lib.testMesh.indices.resize(indexCount);
        for (uint32_t& index : lib.testMesh.indices) {
            index = m.u32();
            if (index >= vertexCount)
                throw Error(where + ": section 'TMSH' has an index out of range");
        }
        m.expectEnd();
    }

    ByteReader r(section("TFLD"), where + ": section 'TFLD'");
    uint32_t count = r.u32();
    if (uint64_t(count) * 32 != r.remaining())
        throw Error(where + ": section 'TFLD' holds " + std::to_string(r.remaining()) + " bytes for " +
                    std::to_string(count) + " instances");
    lib.testField.resize(count);
    for (gpu::GpuInstance& inst : lib.testField) {
        for (int i = 0; i < 4; ++i)
            inst.positionScale[i] = r.f32();
        for (int i = 0; i < 4; ++i)
            inst.boundsTint[i] = r.f32();
        for (int i = 0; i < 4; ++i)
            if (!std::isfinite(inst.positionScale[i]) || !std::isfinite(inst.boundsTint[i]))
                throw Error(where + ": section 'TFLD' holds a non-finite value");
    }
    r.expectEnd();
    return lib;
}

std::filesystem::path cachedLibraryPath(const Scene& scene) {
    std::filesystem::path dir;
    if (const char* env = std::getenv("MEADOW_CACHE_DIR"); env && *env)
        dir = env;
    else if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg)
        dir = std::filesystem::path(xdg) / "meadow";
    else if (const char* home = std::getenv("HOME"); home && *home)
        dir = std::filesystem::path(home) / ".cache" / "meadow";
    else
        dir = std::filesystem::temp_directory_path() / "meadow-cache";
    return dir / (scene.name + "-" + scene.preset + "-" + hex(libraryInputHash(scene)) + ".mlib");
}

Library ensureLibrary(const Scene& scene, bool quiet) {
    std::filesystem::path path = cachedLibraryPath(scene);
    uint64_t hash = 0;
    if (peekLibraryInputHash(path, hash) && hash == libraryInputHash(scene)) {
        try {
            return loadLibrary(path);
        } catch (const Error& e) {
            std::fprintf(stderr, "meadow: cached library is unusable, rebuilding: %s\n", e.what());
        }
    } else if (std::filesystem::exists(path)) {
        std::fprintf(stderr, "meadow: cached library %s is stale or corrupt, rebuilding\n", path.string().c_str());
    }
    std::error_code ec;
    std::filesystem::create_directories(path.parent_path(), ec);
    if (ec)
        throw Error("cannot create the library cache folder " + path.parent_path().string() + ": " + ec.message() +
                    " (set MEADOW_CACHE_DIR)");
    buildLibrary(scene, path, quiet);
    return loadLibrary(path);
}

} // namespace meadow
