#include "library/sections.h"

#include "core/error.h"
#include "library/sh.h"

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

void writeRockSection(ByteWriter& w, const Library& library) {
    w.u32(uint32_t(library.field.rocks.size()));
    for (const LibraryRock& rock : library.field.rocks) {
        w.string(rock.mesh.name);
        w.f32(rock.mesh.size);
        writeVec3s(w, rock.mesh.positions);
        writeVec3s(w, rock.mesh.normals);
        std::vector<float> uvs;
        for (const glm::vec2& uv : rock.mesh.uvs)
            uvs.insert(uvs.end(), {uv.x, uv.y});
        w.f32s(uvs);
        w.u32s(rock.mesh.indices);
        for (const RockLod& lod : rock.lods) {
            w.u32s(lod.vertices);
            w.u32s(lod.indices);
        }
        w.u32(uint32_t(rock.order));
        w.f16s(rock.transfer);
        w.u32(rock.groundResolution);
        w.f32(rock.groundSize);
        w.f16s(rock.groundTransfer);
    }
    writeInstances(w, library.field.rockInstances);
}

void readRockSection(ByteReader& r, const std::string& where, Library& library) {
    LibraryField& field = library.field;
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
        for (uint32_t l = 0; l < kLodCount; ++l) {
            RockLod& lod = rock.lods[l];
            lod.vertices = r.u32s();
            lod.indices = r.u32s();
            const std::string which = what + ": LOD " + std::to_string(l);
            if (lod.vertices.empty() || lod.indices.empty() || lod.indices.size() % 3 != 0)
                throw Error(which + " is empty or not a triangle list");
            for (uint32_t v : lod.vertices)
                if (v >= vertices)
                    throw Error(which + " names vertex " + std::to_string(v) + " of " + std::to_string(vertices));
            for (uint32_t i : lod.indices)
                if (i >= lod.vertices.size())
                    throw Error(which + " has a triangle index out of range");
        }
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

} // namespace meadow
