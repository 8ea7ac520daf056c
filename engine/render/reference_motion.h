// What the CPU references of the compute passes that move clump vertices share: a vertex's
// displacement for an instance's motion-graph state, shaders/shared/clump_motion.glsl's sum in glm
// (near_reference.cpp for near_vertices.comp, far_reference.cpp for far_splat.comp).
#pragma once

#include "draw_instance.h"
#include "gpu_types.h"

#include <glm/glm.hpp>

#include <vector>

namespace meadow {

// d = sum over the vertex's modes k of U_k q_k, the coordinates blended across a motion-graph jump:
// `motion` is its GpuLodVertex::motion, `motionData` the packed rows (4 floats each) and
// coordinates. Throws meadow::Error, naming `reference`, for a row or coordinate outside motionData.
glm::vec3 clumpVertexDisplacement(const std::vector<float>& motionData, const glm::uvec4& motion,
                                  const gpu::GpuDrawInstance& inst, const char* reference);

} // namespace meadow
