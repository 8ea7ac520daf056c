#include "library/sections.h"

#include "core/error.h"

#include <cmath>

namespace meadow {

void writeInstances(ByteWriter& w, const std::vector<gpu::GpuInstance>& instances) {
    w.u32(uint32_t(instances.size()));
    for (const gpu::GpuInstance& inst : instances) {
        for (int i = 0; i < 4; ++i)
            w.f32(inst.positionScale[i]);
        w.f32(inst.yaw);
        w.f32(inst.boundingRadius);
        w.u32(inst.mesh);
    }
}

std::vector<gpu::GpuInstance> readInstances(ByteReader& r, const std::string& where, uint32_t meshCount) {
    const uint32_t count = r.u32();
    if (uint64_t(count) * 28 > r.remaining())
        throw Error(where + " holds " + std::to_string(r.remaining()) + " bytes for " + std::to_string(count) +
                    " instances");
    std::vector<gpu::GpuInstance> instances(count);
    for (gpu::GpuInstance& inst : instances) {
        for (int i = 0; i < 4; ++i)
            inst.positionScale[i] = r.f32();
        inst.yaw = r.f32();
        inst.boundingRadius = r.f32();
        inst.mesh = r.u32();
        bool finite = std::isfinite(inst.yaw) && std::isfinite(inst.boundingRadius);
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

void writeInstanceSection(ByteWriter& w, const Library& library) {
    writeInstances(w, library.field.clumpInstances);
}

void readInstanceSection(ByteReader& r, const std::string& where, Library& library) {
    library.field.clumpInstances = readInstances(r, where, uint32_t(library.clumps.size()));
    r.expectEnd();
}

} // namespace meadow
