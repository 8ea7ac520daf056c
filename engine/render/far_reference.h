// CPU reference of the far field's splat pass (shaders/far_splat.comp.glsl), for tests: what the
// visibility buffer holds after the pass, from the same inputs the pass reads. Its per-sample
// arithmetic is far_splat.h's and lod_select.h's, shared with the shader; the rest (motion,
// light, projection) is the shader's, line by line, in glm.
#pragma once

#include "draw_instance.h"
#include "gpu_types.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

namespace meadow {

// Everything the splat pass reads, as the GPU held it for one frame.
struct FarSplatInputs {
    gpu::GpuFrame frame{};
    glm::vec4 mirrorNormal{0.0f, 0.0f, 1.0f, 0.0f}; // the pass's push constant
    std::vector<glm::uvec2> farList;                // (visible-list entry, samples), the dispatch's count of them
    std::vector<gpu::GpuDrawInstance> drawInstances;
    std::vector<gpu::GpuClump> clumps;
    std::vector<gpu::GpuFarSample> farSamples;
    std::vector<gpu::GpuFarMotion> farMotion;
    std::vector<float> motionData;
    std::vector<glm::uvec4> vertexLight;
};

// The visibility buffer (far_splat.h's words; gpu::kFarEmpty in both halves where no sample won),
// row-major over frame.lodScreen.zw pixels, before the resolve pass tests it against the meshes'
// depth (gpu::farWordShows). The LOD debug view's colours are not modelled: throws
// meadow::Error for a frame in it, and for inputs that index outside their arrays.
std::vector<uint64_t> farSplatReference(const FarSplatInputs& inputs);

} // namespace meadow
