// CPU reference of the near raster (shaders/near_vertices.comp.glsl and near_raster.comp.glsl), for
// tests: what the visibility buffer holds after its two passes, from the same inputs they read.
// Its per-triangle arithmetic is near_raster.h's, shared with the shaders; the rest (motion, light,
// projection, interpolation) is the shaders', line by line, in glm.
#pragma once

#include "draw_instance.h"
#include "gpu_types.h"
#include "library/mesh.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

namespace meadow {

// Everything the near raster reads, as the GPU held it for one frame.
struct NearRasterInputs {
    gpu::GpuFrame frame{};
    glm::vec4 mirrorNormal{0.0f, 0.0f, 1.0f, 0.0f}; // the vertex pass's push constant
    std::vector<glm::uvec4> nearList;               // (entry, bucket, first vertex, 0), the dispatch's count of them
    std::vector<gpu::GpuDrawInstance> drawInstances;
    std::vector<gpu::GpuClump> clumps;
    std::vector<glm::uvec4> nearMeshes; // per bucket (first LOD vertex, vertices, first index, indices)
    std::vector<uint32_t> indices;
    std::vector<gpu::GpuLodVertex> lodVertices;
    std::vector<float> motionData;
    std::vector<glm::uvec4> vertexLight;
    RgbaImage atlas; // only a uniform atlas is modelled (every texel the same), as the tests' is
};

// The visibility buffer (far_splat.h's words; gpu::kFarEmpty in both halves where nothing was drawn),
// row-major over frame.lodScreen.zw pixels. The LOD debug view's colours are not modelled: throws
// meadow::Error for a frame in it, for an atlas whose texels differ, and for inputs that index
// outside their arrays.
std::vector<uint64_t> nearRasterReference(const NearRasterInputs& inputs);

} // namespace meadow
