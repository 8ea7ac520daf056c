#include "io/output_path.h"

#include "core/error.h"

#include <unistd.h>

namespace meadow {

void checkOutputWritable(const std::filesystem::path& path) {
    std::filesystem::path dir = path.parent_path();
    if (dir.empty())
        dir = ".";
    std::error_code ec;
    if (!std::filesystem::is_directory(dir, ec))
        throw Error("cannot write " + path.string() + ": folder " + dir.string() + " does not exist");
    if (std::filesystem::is_directory(path, ec))
        throw Error("cannot write " + path.string() + ": it is a folder");
    if (access(dir.c_str(), W_OK) != 0)
        throw Error("cannot write " + path.string() + ": folder " + dir.string() + " is not writable");
}

} // namespace meadow
