#include "library/sections.h"

#include "core/error.h"

#include <cmath>

namespace meadow {
namespace {

void writeLods(ByteWriter& w, const std::array<ClumpLod, kLodCount>& lods) {
    for (const ClumpLod& lod : lods) {
        w.u32s(lod.vertices);
        w.u32s(lod.indices);
        const LodError& e = lod.error;
        for (const SurfaceDistance* d : {&e.rest, &e.deformed, &e.light, &e.motion}) {
            w.f32(float(d->hausdorff));
            w.f32(float(d->rms));
        }
        w.u32(e.fullSamples);
        w.u32(e.lodSamples);
    }
}

void readLods(ByteReader& r, LibraryClump& clump, const std::string& where) {
    auto fail = [&](const std::string& what) { return Error(where + ": clump " + clump.name + ": " + what); };
    const size_t meshVertices = clump.mesh.vertices.size();
    for (uint32_t l = 0; l < kLodCount; ++l) {
        ClumpLod& lod = clump.lods[l];
        lod.vertices = r.u32s();
        lod.indices = r.u32s();
        LodError& e = lod.error;
        for (SurfaceDistance* d : {&e.rest, &e.deformed, &e.light, &e.motion}) {
            d->hausdorff = r.f32();
            d->rms = r.f32();
            if (!std::isfinite(d->hausdorff) || !std::isfinite(d->rms))
                throw fail("LOD " + std::to_string(l) + " has a non-finite error");
        }
        e.fullSamples = r.u32();
        e.lodSamples = r.u32();
        if (lod.vertices.empty() || lod.indices.empty() || lod.indices.size() % 3 != 0)
            throw fail("LOD " + std::to_string(l) + " is empty or not a triangle list");
        for (uint32_t v : lod.vertices)
            if (v >= meshVertices)
                throw fail("LOD " + std::to_string(l) + " names vertex " + std::to_string(v) + " of " +
                           std::to_string(meshVertices));
        for (uint32_t i : lod.indices)
            if (i >= lod.vertices.size())
                throw fail("LOD " + std::to_string(l) + " has a triangle index out of range");
    }
}

} // namespace

void writeLodSection(ByteWriter& w, const Library& library) {
    w.u32(uint32_t(library.clumps.size()));
    for (const LibraryClump& clump : library.clumps)
        writeLods(w, clump.lods);
}

void readLodSection(ByteReader& r, const std::string& where, Library& library) {
    if (r.u32() != library.clumps.size())
        throw Error(where + " does not hold one entry per clump");
    for (LibraryClump& clump : library.clumps)
        readLods(r, clump, where);
    r.expectEnd();
}

} // namespace meadow
