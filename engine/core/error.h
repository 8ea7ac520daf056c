// meadow's error type: every error reported to a user is a meadow::Error whose message says
// what went wrong and where (file, flag, Vulkan call). main() prints it on stderr and exits
// non-zero. Programmer errors assert instead.
#pragma once

#include <stdexcept>
#include <string>

namespace meadow {

class Error : public std::runtime_error {
  public:
    explicit Error(const std::string& message) : std::runtime_error(message) {}
};

} // namespace meadow
