// Four floats in one SSE register (GCC/Clang vector extension, baseline SSE2): the wind solver
// blends the three components of a vector sample at once. Each lane is an ordinary IEEE float
// operation, so results equal the scalar code's bit for bit.
#pragma once

#include <cstring>
#include <glm/glm.hpp>

namespace meadow {

using Float4 = float __attribute__((vector_size(16)));

inline Float4 load4(const glm::vec4& v) {
    Float4 r;
    std::memcpy(&r, &v, sizeof r);
    return r;
}

} // namespace meadow
