// A test process's own folder under the system's temporary directory, for the files its tests
// write: made when the process first asks for it, and removed with everything in it when the
// process exits, so that test runs leave nothing behind in /tmp.
#pragma once

#include <filesystem>
#include <string>
#include <system_error>
#include <unistd.h>

namespace meadow::test {

class ScratchDir {
  public:
    // PREFIX-<process id> under the temporary directory.
    explicit ScratchDir(const std::string& prefix)
        : path_(std::filesystem::temp_directory_path() / (prefix + "-" + std::to_string(getpid()))) {
        std::filesystem::create_directories(path_);
    }
    ~ScratchDir() {
        std::error_code ignored; // a test that removed it already is fine
        std::filesystem::remove_all(path_, ignored);
    }
    ScratchDir(const ScratchDir&) = delete;
    ScratchDir& operator=(const ScratchDir&) = delete;

    const std::filesystem::path& path() const { return path_; }

  private:
    std::filesystem::path path_;
};

} // namespace meadow::test
