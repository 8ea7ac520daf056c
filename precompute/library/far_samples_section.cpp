#include "core/error.h"
#include "library/sections.h"

#include <cmath>
#include <vector>

namespace meadow {
namespace {

// Per clump or rock: f32 area, the gain table (kFarGainSizes x kFarGainElevations f32), u32 count,
// then count x {f32 x, y, z; u32 normal, albedo, vertex, lightVertex, visibility}.
void writeFarSamplesOf(ByteWriter& w, const FarSamples& far) {
    w.f32(far.area);
    for (float g : far.gain)
        w.f32(g);
    w.u32(uint32_t(far.samples.size()));
    for (const FarSample& s : far.samples) {
        w.f32(s.position.x);
        w.f32(s.position.y);
        w.f32(s.position.z);
        w.u32(s.normal);
        w.u32(s.albedo);
        w.u32(s.vertex);
        w.u32(s.lightVertex);
        w.u32(s.visibility);
    }
}

// `fail` names the clump or rock; `vertices` is its mesh's vertex count, `lastLod` the vertices
// its last LOD keeps (the only ones a sample may play: the run time looks their rows up there).
template <typename Fail>
FarSamples readFarSamplesOf(ByteReader& r, size_t vertices, const std::vector<uint32_t>& lastLod, const Fail& fail) {
    std::vector<bool> kept(vertices, false);
    for (uint32_t v : lastLod)
        if (v < vertices)
            kept[v] = true;
    FarSamples far;
    far.area = r.f32();
    if (!std::isfinite(far.area) || far.area < 0.0f)
        throw fail("its far-field samples cover a non-finite or negative area");
    for (float& g : far.gain) {
        g = r.f32();
        if (!std::isfinite(g) || !(g > 0.0f))
            throw fail("its far-field coverage gain " + std::to_string(g) + " is not a positive finite number");
    }
    const uint32_t count = r.u32();
    if (size_t(count) * kFarSampleBytes > r.remaining())
        throw fail(std::to_string(count) + " far-field samples do not fit in the section");
    far.samples.resize(count);
    for (uint32_t i = 0; i < count; ++i) {
        FarSample& s = far.samples[i];
        s.position.x = r.f32();
        s.position.y = r.f32();
        s.position.z = r.f32();
        s.normal = r.u32();
        s.albedo = r.u32();
        s.vertex = r.u32();
        s.lightVertex = r.u32();
        s.visibility = r.u32();
        if ((s.visibility & ~gpu::kFarAllVisible) != 0u)
            throw fail("far-field sample " + std::to_string(i) + " has visibility bits " +
                       std::to_string(s.visibility) + " outside the " + std::to_string(gpu::kFarVisibilityTopBit + 1u) +
                       " views");
        if (s.lightVertex >= vertices)
            throw fail("far-field sample " + std::to_string(i) + " is lit by vertex " + std::to_string(s.lightVertex) +
                       " of " + std::to_string(vertices));
        if (!std::isfinite(s.position.x) || !std::isfinite(s.position.y) || !std::isfinite(s.position.z))
            throw fail("far-field sample " + std::to_string(i) + " has a non-finite position");
        if (s.vertex >= vertices)
            throw fail("far-field sample " + std::to_string(i) + " names vertex " + std::to_string(s.vertex) + " of " +
                       std::to_string(vertices));
        if (!kept[s.vertex])
            throw fail("far-field sample " + std::to_string(i) + " plays vertex " + std::to_string(s.vertex) +
                       ", which the last LOD does not keep");
    }
    return far;
}

} // namespace

void writeFarSamplesSection(ByteWriter& w, const Library& library) {
    w.u32(uint32_t(library.clumps.size()));
    for (const LibraryClump& clump : library.clumps)
        writeFarSamplesOf(w, clump.far);
    w.u32(uint32_t(library.field.rocks.size()));
    for (const LibraryRock& rock : library.field.rocks)
        writeFarSamplesOf(w, rock.far);
}

void readFarSamplesSection(ByteReader& r, const std::string& where, Library& library) {
    if (r.u32() != library.clumps.size())
        throw Error(where + " does not hold one entry per clump");
    for (LibraryClump& clump : library.clumps) {
        auto fail = [&](const std::string& what) { return Error(where + ": clump " + clump.name + ": " + what); };
        clump.far = readFarSamplesOf(r, clump.mesh.vertices.size(), clump.lods[kLodCount - 1].vertices, fail);
    }
    if (r.u32() != library.field.rocks.size())
        throw Error(where + " does not hold one entry per rock");
    for (LibraryRock& rock : library.field.rocks) {
        auto fail = [&](const std::string& what) { return Error(where + ": " + rock.mesh.name + ": " + what); };
        rock.far = readFarSamplesOf(r, rock.mesh.positions.size(), rock.lods[kLodCount - 1].vertices, fail);
    }
    r.expectEnd();
}

} // namespace meadow
