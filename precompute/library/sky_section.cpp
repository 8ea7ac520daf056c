#include "library/sections.h"

#include "core/error.h"
#include "library/sh.h"

#include <cmath>

namespace meadow {
namespace {

void writeVec3(ByteWriter& w, const glm::vec3& v) {
    w.f32(v.x);
    w.f32(v.y);
    w.f32(v.z);
}

glm::vec3 readVec3(ByteReader& r) {
    glm::vec3 v;
    v.x = r.f32();
    v.y = r.f32();
    v.z = r.f32();
    return v;
}

void writeSky(ByteWriter& w, const sky::SkyDay& day, bool fromMaps) {
    w.u32(uint32_t(day.shOrder));
    w.u32(day.imageWidth);
    w.u32(day.imageHeight);
    w.u32(fromMaps ? 1 : 0);
    w.u32(uint32_t(day.frames.size()));
    for (const sky::SkyFrame& f : day.frames) {
        w.f32(float(f.hours));
        writeVec3(w, f.sunDirection);
        writeVec3(w, f.sunRadiance);
        writeVec3(w, f.sunIrradiance);
        w.f32s(f.sh);
        w.f32s(f.image);
    }
}

sky::SkyDay readSky(ByteReader& r, const std::string& where, bool& fromMaps) {
    auto fail = [&](const std::string& what) { return Error(where + ": " + what); };
    sky::SkyDay day;
    day.shOrder = int(r.u32());
    day.imageWidth = r.u32();
    day.imageHeight = r.u32();
    const uint32_t source = r.u32();
    const uint32_t frames = r.u32();
    if (day.shOrder < 1 || day.shOrder > sh::kMaxOrder)
        throw fail("SH order " + std::to_string(day.shOrder) + " is out of range");
    if (day.imageWidth == 0 || day.imageWidth > 4096 || day.imageWidth != 2 * day.imageHeight)
        throw fail("the backdrop image is " + std::to_string(day.imageWidth) + " x " + std::to_string(day.imageHeight));
    if (source > 1 || frames == 0 || frames > 4096)
        throw fail("holds " + std::to_string(frames) + " frames of source " + std::to_string(source));
    fromMaps = source == 1;
    const size_t shValues = size_t(sh::coefficientCount(day.shOrder)) * 3;
    const size_t imageValues = size_t(day.imageWidth) * day.imageHeight * 3;
    double previous = -1.0;
    for (uint32_t i = 0; i < frames; ++i) {
        sky::SkyFrame f;
        f.hours = r.f32();
        f.sunDirection = readVec3(r);
        f.sunRadiance = readVec3(r);
        f.sunIrradiance = readVec3(r);
        f.sh = r.f32s(shValues);
        f.image = r.f32s(imageValues);
        if (f.sh.size() != shValues || f.image.size() != imageValues)
            throw fail("frame " + std::to_string(i) + " has the wrong size");
        bool finite = std::isfinite(f.hours);
        for (int c = 0; c < 3; ++c)
            finite = finite && std::isfinite(f.sunDirection[c]) && std::isfinite(f.sunRadiance[c]) &&
                     std::isfinite(f.sunIrradiance[c]);
        for (float v : f.sh)
            finite = finite && std::isfinite(v);
        for (float v : f.image)
            finite = finite && std::isfinite(v) && v >= 0.0f;
        if (!finite)
            throw fail("frame " + std::to_string(i) + " holds a non-finite or negative value");
        if (!(f.hours > previous && f.hours < 24.0))
            throw fail("frame " + std::to_string(i) + " is not in time order within the day");
        previous = f.hours;
        day.frames.push_back(std::move(f));
    }
    r.expectEnd();
    return day;
}

} // namespace

void writeSkySection(ByteWriter& w, const Library& library) {
    writeSky(w, library.sky, library.skyFromMaps);
}

void readSkySection(ByteReader& r, const std::string& where, Library& library) {
    library.sky = readSky(r, where, library.skyFromMaps);
}

} // namespace meadow
