// What the fuzz targets share: the input written to a file of this process's own (the loaders read
// paths, as meadow does), and the rule that a bad input may end only in a meadow::Error. Any other
// exception escapes the target and aborts: libFuzzer reports it as a crash, and so does the replay.
#pragma once

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

namespace meadow::fuzz {

// A folder of this process (fuzzing with -jobs runs several), empty but for what the targets write:
// relative references from the input (glTF buffers, sky maps) find nothing there.
inline const std::filesystem::path& scratchFolder() {
    static const std::filesystem::path folder = [] {
        std::filesystem::path f = std::filesystem::temp_directory_path() / ("meadow-fuzz-" + std::to_string(getpid()));
        std::filesystem::create_directories(f);
        return f;
    }();
    return folder;
}

inline std::filesystem::path writeInput(const std::string& name, const uint8_t* data, size_t size) {
    const std::filesystem::path path = scratchFolder() / name;
    std::ofstream(path, std::ios::binary | std::ios::trunc)
        .write(reinterpret_cast<const char*>(data), std::streamsize(size));
    return path;
}

} // namespace meadow::fuzz
