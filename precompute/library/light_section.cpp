#include "library/sections.h"

#include "core/error.h"
#include "library/sh.h"

#include <cmath>
#include <functional>

namespace meadow {
namespace {

// transfer/transfer.h's layouts: two sides of a vertex, three colour channels.
constexpr uint32_t kTransferSides = 2;
constexpr uint32_t kTransferChannels = 3;

void writeAppearance(ByteWriter& w, const GroundAppearance& m) {
    w.f32s(m.mean);
    w.u32s(m.bakedFrames);
    w.f32s(std::vector<float>(m.relativeErrorPerMode.begin(), m.relativeErrorPerMode.end()));
}

GroundAppearance readAppearance(ByteReader& r, size_t values, uint32_t frames,
                                const std::function<Error(const std::string&)>& fail) {
    GroundAppearance m;
    std::vector<float> mean = r.f32s();
    m.bakedFrames = r.u32s();
    std::vector<float> errors = r.f32s();
    if (mean.size() != values || errors.empty())
        throw fail("an appearance model has the wrong size");
    for (const std::vector<float>* v : {&mean, &errors})
        for (float x : *v)
            if (!std::isfinite(x))
                throw fail("an appearance model holds a non-finite value");
    for (uint32_t f : m.bakedFrames)
        if (f >= frames)
            throw fail("an appearance model names baked frame " + std::to_string(f) + " of " + std::to_string(frames));
    m.mean = std::move(mean);
    m.relativeErrorPerMode.assign(errors.begin(), errors.end());
    return m;
}

void writeLight(ByteWriter& w, const LibraryLight& light) {
    w.u32(uint32_t(light.order));
    w.u32s(light.bakedFrames);
    w.u32(light.vertices.valuesPerVertex);
    // Half floats, as the appearance basis: the bake's noise is far above their 0.05 %.
    w.f16s(light.vertices.coefficients);
    w.u32(light.groundResolution);
    w.f32(light.groundSize);
    if (light.groundResolution > 0)
        writeAppearance(w, light.ground);
    for (double figure : {light.vertexNoise, light.groundNoise, light.vertexHeldOutError, light.vertexMeanOnlyError,
                          light.groundHeldOutError, light.vertexIrradianceNoise, light.groundIrradianceNoise})
        w.f32(float(figure));
}

LibraryLight readLight(ByteReader& r, const LibraryClump& clump, const std::string& where) {
    auto fail = [&](const std::string& what) { return Error(where + ": clump " + clump.name + ": " + what); };
    LibraryLight light;
    light.order = int(r.u32());
    if (light.order < 1 || light.order > sh::kMaxOrder)
        throw fail("SH order " + std::to_string(light.order) + " is out of range");
    const uint32_t coefficients = uint32_t(sh::coefficientCount(light.order));
    light.bakedFrames = r.u32s();
    for (uint32_t f : light.bakedFrames)
        if (f >= clump.motion.frames)
            throw fail("baked frame " + std::to_string(f) + " is beyond the " + std::to_string(clump.motion.frames) +
                       " motion frames");
    VertexAppearance& v = light.vertices;
    v.vertexCount = uint32_t(clump.mesh.vertices.size());
    v.valuesPerVertex = r.u32();
    if (v.valuesPerVertex != kTransferSides * kTransferChannels * coefficients)
        throw fail("vertex transfer has " + std::to_string(v.valuesPerVertex) + " values per vertex");
    v.coefficients = r.f16s();
    if (v.coefficients.size() != size_t(v.vertexCount) * v.valuesPerVertex * 4)
        throw fail("vertex transfer has the wrong size");
    for (float x : v.coefficients)
        if (!std::isfinite(x))
            throw fail("vertex transfer holds a non-finite value");
    light.groundResolution = r.u32();
    light.groundSize = r.f32();
    if (light.groundResolution > 256 || !(light.groundSize >= 0.0f && light.groundSize < 1000.0f))
        throw fail("the ground grid is " + std::to_string(light.groundResolution) + " points wide");
    if (light.groundResolution > 0)
        light.ground = readAppearance(
            r, size_t(light.groundResolution) * light.groundResolution * kTransferChannels * coefficients,
            clump.motion.frames, fail);
    for (double* figure :
         {&light.vertexNoise, &light.groundNoise, &light.vertexHeldOutError, &light.vertexMeanOnlyError,
          &light.groundHeldOutError, &light.vertexIrradianceNoise, &light.groundIrradianceNoise})
        *figure = r.f32();
    return light;
}

} // namespace

void writeLightSection(ByteWriter& w, const Library& library) {
    w.u32(uint32_t(library.clumps.size()));
    for (const LibraryClump& clump : library.clumps)
        writeLight(w, clump.light);
}

void readLightSection(ByteReader& r, const std::string& where, Library& library) {
    if (r.u32() != library.clumps.size())
        throw Error(where + " does not hold one entry per clump");
    for (LibraryClump& clump : library.clumps)
        clump.light = readLight(r, clump, where);
    r.expectEnd();
}

} // namespace meadow
