#include "render/reference_motion.h"

#include "core/error.h"

#include <cstddef>
#include <string>

namespace meadow {

glm::vec3 clumpVertexDisplacement(const std::vector<float>& motionData, const glm::uvec4& motion,
                                  const gpu::GpuDrawInstance& inst, const char* reference) {
    auto at = [&](size_t index, const char* what) {
        if (index >= motionData.size())
            throw Error(std::string(reference) + ": " + what + " index " + std::to_string(index) + " is outside its " +
                        std::to_string(motionData.size()) + " entries");
        return motionData[index];
    };
    const uint32_t rank = motion.w & 0xffffu;
    const uint32_t q0 = inst.offsets.x + motion.y, q1 = inst.offsets.y + motion.y;
    const bool blending = inst.pose.z > 0.0f;
    glm::vec3 d(0.0f);
    for (uint32_t k = 0; k < rank; ++k) {
        const uint32_t row = 4u * (motion.x + k);
        float q = at(q0 + k, "motion coordinate");
        if (blending)
            q = glm::mix(q, at(q1 + k, "motion coordinate"), inst.pose.z);
        d += glm::vec3(at(row, "motion row"), at(row + 1u, "motion row"), at(row + 2u, "motion row")) * q;
    }
    return d;
}

} // namespace meadow
