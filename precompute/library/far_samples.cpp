#include "library/far_samples.h"

#include <algorithm>
#include <cmath>

namespace meadow {
namespace {

// +1 for x >= 0 (GLSL's sign() gives 0 at 0, which would fold the seam onto the origin).
glm::vec2 signNotZero(glm::vec2 v) {
    return {v.x >= 0.0f ? 1.0f : -1.0f, v.y >= 0.0f ? 1.0f : -1.0f};
}

uint32_t packSnorm16(float v) {
    const float r = std::round(std::clamp(v, -1.0f, 1.0f) * 32767.0f);
    return uint32_t(uint16_t(int16_t(r)));
}

float unpackSnorm16(uint32_t bits) {
    return std::clamp(float(int16_t(uint16_t(bits))) / 32767.0f, -1.0f, 1.0f);
}

} // namespace

uint32_t packOctahedral(glm::vec3 n) {
    const float sum = std::abs(n.x) + std::abs(n.y) + std::abs(n.z);
    if (!(sum > 0.0f) || !std::isfinite(sum))
        return 0; // +z
    glm::vec2 p = glm::vec2(n.x, n.y) / sum;
    if (n.z < 0.0f)
        p = (1.0f - glm::abs(glm::vec2(p.y, p.x))) * signNotZero(p);
    return packSnorm16(p.x) | (packSnorm16(p.y) << 16);
}

glm::vec3 unpackOctahedral(uint32_t packed) {
    glm::vec3 n(unpackSnorm16(packed & 0xffffu), unpackSnorm16(packed >> 16), 0.0f);
    n.z = 1.0f - std::abs(n.x) - std::abs(n.y);
    if (n.z < 0.0f) {
        const glm::vec2 folded = (1.0f - glm::abs(glm::vec2(n.y, n.x))) * signNotZero(glm::vec2(n));
        n.x = folded.x;
        n.y = folded.y;
    }
    return glm::normalize(n);
}

} // namespace meadow
