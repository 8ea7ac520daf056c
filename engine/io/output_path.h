// Output files: whether one can be written where the command line asks, checked before any work.
#pragma once

#include <filesystem>

namespace meadow {

// Throws meadow::Error, naming the path, when a file cannot be created there (missing or
// unwritable folder, or a folder at the path). Checked before any rendering starts.
void checkOutputWritable(const std::filesystem::path& path);

} // namespace meadow
