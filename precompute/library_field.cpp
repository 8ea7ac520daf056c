#include "library_field.h"

#include "core/error.h"
#include "light/sh.h"

#include <cmath>

namespace meadow {
namespace {

void writeVec3s(ByteWriter& w, const std::vector<glm::vec3>& v) {
    std::vector<float> flat;
    flat.reserve(v.size() * 3);
    for (const glm::vec3& x : v)
        flat.insert(flat.end(), {x.x, x.y, x.z});
    w.f32s(flat);
}

template <int N> std::vector<glm::vec<N, float>> readVecs(ByteReader& r, const std::string& what) {
    std::vector<float> flat = r.f32s();
    if (flat.size() % N != 0)
        throw Error(what + " is not a whole number of vectors");
    std::vector<glm::vec<N, float>> v(flat.size() / N);
    for (size_t i = 0; i < v.size(); ++i)
        for (int c = 0; c < N; ++c) {
            v[i][c] = flat[i * N + size_t(c)];
            if (!std::isfinite(v[i][c]))
                throw Error(what + " holds a non-finite value");
        }
    return v;
}

bool allFinite(const std::vector<float>& v) {
    for (float x : v)
        if (!std::isfinite(x))
            return false;
    return true;
}

} // namespace

void writeInstances(ByteWriter& w, const std::vector<gpu::GpuInstance>& instances) {
    w.u32(uint32_t(instances.size()));
    for (const gpu::GpuInstance& inst : instances) {
        for (int i = 0; i < 4; ++i)
            w.f32(inst.positionScale[i]);
        w.f32(inst.yaw);
        w.f32(inst.boundingRadius);
        w.f32(inst.tint);
        w.u32(inst.mesh);
    }
}

std::vector<gpu::GpuInstance> readInstances(ByteReader& r, const std::string& where, uint32_t meshCount) {
    const uint32_t count = r.u32();
    if (uint64_t(count) * 32 > r.remaining())
        throw Error(where + " holds " + std::to_string(r.remaining()) + " bytes for " + std::to_string(count) +
                    " instances");
    std::vector<gpu::GpuInstance> instances(count);
    for (gpu::GpuInstance& inst : instances) {
        for (int i = 0; i < 4; ++i)
            inst.positionScale[i] = r.f32();
        inst.yaw = r.f32();
        inst.boundingRadius = r.f32();
        inst.tint = r.f32();
        inst.mesh = r.u32();
        bool finite = std::isfinite(inst.yaw) && std::isfinite(inst.boundingRadius) && std::isfinite(inst.tint);
        for (int i = 0; i < 4; ++i)
            finite = finite && std::isfinite(inst.positionScale[i]);
        if (!finite)
            throw Error(where + " holds a non-finite value");
        if (std::abs(inst.positionScale.w) != 1.0f)
            throw Error(where + " holds an instance of scale " + std::to_string(inst.positionScale.w) +
                        " (only 1 or -1)");
        if (inst.mesh >= meshCount)
            throw Error(where + " names mesh " + std::to_string(inst.mesh) + " of " + std::to_string(meshCount));
    }
    return instances;
}

void writeRocks(ByteWriter& w, const std::vector<LibraryRock>& rocks, const std::vector<gpu::GpuInstance>& instances) {
    w.u32(uint32_t(rocks.size()));
    for (const LibraryRock& rock : rocks) {
        w.string(rock.mesh.name);
        w.f32(rock.mesh.size);
        writeVec3s(w, rock.mesh.positions);
        writeVec3s(w, rock.mesh.normals);
        std::vector<float> uvs;
        for (const glm::vec2& uv : rock.mesh.uvs)
            uvs.insert(uvs.end(), {uv.x, uv.y});
        w.f32s(uvs);
        w.u32s(rock.mesh.indices);
        w.u32(uint32_t(rock.order));
        w.f16s(rock.transfer);
        w.u32(rock.groundResolution);
        w.f32(rock.groundSize);
        w.f16s(rock.groundTransfer);
    }
    writeInstances(w, instances);
}

void readRocks(ByteReader& r, const std::string& where, LibraryField& field) {
    const uint32_t count = r.u32();
    if (count > 64)
        throw Error(where + " holds " + std::to_string(count) + " rocks");
    for (uint32_t i = 0; i < count; ++i) {
        LibraryRock rock;
        rock.mesh.name = r.string();
        const std::string what = where + ": " + rock.mesh.name;
        rock.mesh.size = r.f32();
        rock.mesh.positions = readVecs<3>(r, what + " positions");
        rock.mesh.normals = readVecs<3>(r, what + " normals");
        rock.mesh.uvs = readVecs<2>(r, what + " uvs");
        rock.mesh.indices = r.u32s();
        const size_t vertices = rock.mesh.positions.size();
        if (vertices == 0 || rock.mesh.normals.size() != vertices || rock.mesh.uvs.size() != vertices ||
            rock.mesh.indices.empty() || rock.mesh.indices.size() % 3 != 0 || !std::isfinite(rock.mesh.size))
            throw Error(what + ": inconsistent mesh");
        for (uint32_t index : rock.mesh.indices)
            if (index >= vertices)
                throw Error(what + ": a triangle index is out of range");
        rock.order = int(r.u32());
        if (rock.order < 1 || rock.order > sh::kMaxOrder)
            throw Error(what + ": SH order " + std::to_string(rock.order) + " is out of range");
        const size_t coefficients = size_t(sh::coefficientCount(rock.order));
        rock.transfer = r.f16s();
        rock.groundResolution = r.u32();
        rock.groundSize = r.f32();
        rock.groundTransfer = r.f16s();
        if (rock.transfer.size() != vertices * 2 * 3 * coefficients || rock.groundResolution > 256 ||
            rock.groundTransfer.size() != size_t(rock.groundResolution) * rock.groundResolution * 3 * coefficients ||
            !allFinite(rock.transfer) || !allFinite(rock.groundTransfer) || !std::isfinite(rock.groundSize))
            throw Error(what + ": its light transfer has the wrong size or a non-finite value");
        field.rocks.push_back(std::move(rock));
    }
    field.rockInstances = readInstances(r, where + " instances", count);
    r.expectEnd();
}

void writePlacement(ByteWriter& w, const TerrainParams& terrain, glm::vec2 windDirection, const PlacementStats& s) {
    w.f32(windDirection.x);
    w.f32(windDirection.y);
    w.f32(terrain.amplitude);
    w.f32(terrain.wavelength);
    w.u32(terrain.octaves);
    w.u64(terrain.seed);
    w.u32(s.tiles);
    w.u32s(s.clumpsPerTile);
    w.u32s(s.rocksPerTile);
    w.f32(float(s.densityVsPoissonDisc));
    w.u32(s.overlapViolations);
    w.u32(s.tilesX);
    w.u32(s.tilesY);
    w.f32(s.tileSize);
    w.u32(s.overlaps3dFound);
    w.u32(s.clumpsRemoved3d);
    w.u32(s.rocksRemoved3d);
    w.u32(s.overlapViolations3d);
    w.f32s(s.sweptFootprintRadius);
}

void readPlacement(ByteReader& r, const std::string& where, LibraryField& field) {
    field.windDirection.x = r.f32();
    field.windDirection.y = r.f32();
    TerrainParams& t = field.terrain;
    t.amplitude = r.f32();
    t.wavelength = r.f32();
    t.octaves = r.u32();
    t.seed = r.u64();
    PlacementStats& s = field.stats;
    s.tiles = r.u32();
    s.clumpsPerTile = r.u32s(1024);
    s.rocksPerTile = r.u32s(1024);
    s.densityVsPoissonDisc = r.f32();
    s.overlapViolations = r.u32();
    s.tilesX = r.u32();
    s.tilesY = r.u32();
    s.tileSize = r.f32();
    s.overlaps3dFound = r.u32();
    s.clumpsRemoved3d = r.u32();
    s.rocksRemoved3d = r.u32();
    s.overlapViolations3d = r.u32();
    s.sweptFootprintRadius = r.f32s(64);
    r.expectEnd();
    try {
        Terrain check(t); // validates the parameters
    } catch (const Error& e) {
        throw Error(where + ": " + e.what());
    }
    if (s.clumpsPerTile.size() != s.tiles || s.rocksPerTile.size() != s.tiles || !(s.tileSize > 0.0f) ||
        !std::isfinite(s.tileSize) || !std::isfinite(s.densityVsPoissonDisc) ||
        !(std::abs(glm::length(field.windDirection) - 1.0f) < 1e-3f))
        throw Error(where + ": inconsistent tile figures");
}

} // namespace meadow
