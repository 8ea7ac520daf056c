// The SPIR-V of every shader in shaders/, compiled and validated at build time and embedded in
// the executable (cmake/Shaders.cmake generates the implementation).
#pragma once

#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

namespace meadow {

// The words of shader `name` ("cull.comp"), or an empty span if there is none.
std::span<const uint32_t> findShader(std::string_view name);
std::vector<std::string_view> shaderNames();

} // namespace meadow
