// Where a scene's library is cached, and the hash of what it is built from (build_library.h).
#include "pipeline/build_library.h"

#include "core/error.h"
#include "library/library_file.h"

#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <nlohmann/json.hpp>

namespace meadow {
namespace {

// Bump when what precompute produces changes for the same inputs.
constexpr uint32_t kPrecomputeVersion = 20;

std::string hex(uint64_t v) {
    char buf[17];
    std::snprintf(buf, sizeof(buf), "%016llx", static_cast<unsigned long long>(v));
    return buf;
}

// The files a glTF asset names beside itself (external buffers and images, URL-decoded, relative
// to its folder), read from its JSON (a .glb's first chunk). Nothing when it cannot be read: the
// importer refuses such a file with a message.
std::vector<std::filesystem::path> gltfReferencedFiles(const std::filesystem::path& file) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(file, ec))
        return {};
    std::ifstream in(file, std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (bytes.size() >= 20 && bytes.compare(0, 4, "glTF") == 0) {
        uint32_t length = 0;
        std::memcpy(&length, bytes.data() + 12, 4);
        bytes = bytes.substr(20, std::min<size_t>(length, bytes.size() - 20));
    }
    const nlohmann::json doc = nlohmann::json::parse(bytes, nullptr, false);
    std::vector<std::filesystem::path> files;
    if (!doc.is_object())
        return files;
    for (const char* key : {"buffers", "images"}) {
        auto list = doc.find(key);
        if (list == doc.end() || !list->is_array())
            continue;
        for (const nlohmann::json& entry : *list) {
            if (!entry.is_object() || !entry.contains("uri") || !entry["uri"].is_string())
                continue;
            const std::string uri = entry["uri"].get<std::string>();
            if (uri.rfind("data:", 0) == 0)
                continue;
            std::string decoded;
            for (size_t i = 0; i < uri.size(); ++i) {
                if (uri[i] == '%' && i + 2 < uri.size() && std::isxdigit(static_cast<unsigned char>(uri[i + 1])) &&
                    std::isxdigit(static_cast<unsigned char>(uri[i + 2]))) {
                    decoded.push_back(static_cast<char>(std::stoi(uri.substr(i + 1, 2), nullptr, 16)));
                    i += 2;
                } else {
                    decoded.push_back(uri[i]);
                }
            }
            files.push_back(file.parent_path() / decoded);
        }
    }
    return files;
}

} // namespace

uint64_t libraryInputHash(const Scene& scene) {
    std::string key = scene.resolved.dump() + "|" + scene.preset + "|" + std::to_string(scene.seed) + "|" +
                      std::to_string(kLibraryFormatVersion) + "|" + std::to_string(kPrecomputeVersion);
    uint64_t hash = fnv1a64(key.data(), key.size());
    // Imported files are inputs too: their bytes, not only their names.
    auto hashFile = [&](const std::filesystem::path& file) {
        // Only regular files: a device such as /dev/zero would be read forever. Whatever else the
        // scene names is refused with a message by the stage that reads it.
        std::error_code ec;
        if (!std::filesystem::is_regular_file(file, ec))
            return;
        std::ifstream in(file, std::ios::binary);
        std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        hash = fnv1a64(bytes.data(), bytes.size(), hash);
    };
    if (scene.plants.source == "gltf") {
        hashFile(scene.plants.gltf);
        for (const std::filesystem::path& file : gltfReferencedFiles(scene.plants.gltf))
            hashFile(file);
    }
    for (const std::filesystem::path& map : scene.sky.maps)
        hashFile(map);
    return hash;
}

std::filesystem::path cachedLibraryPath(const Scene& scene) {
    std::filesystem::path dir;
    if (const char* env = std::getenv("MEADOW_CACHE_DIR"); env && *env)
        dir = env;
    else if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg)
        dir = std::filesystem::path(xdg) / "meadow";
    else if (const char* home = std::getenv("HOME"); home && *home)
        dir = std::filesystem::path(home) / ".cache" / "meadow";
    else
        dir = std::filesystem::temp_directory_path() / "meadow-cache";
    return dir / (scene.name + "-" + scene.preset + "-" + hex(libraryInputHash(scene)) + ".mlib");
}

Library loadCachedLibrary(const Scene& scene) {
    const std::filesystem::path path = cachedLibraryPath(scene);
    uint64_t hash = 0;
    if (!peekLibraryInputHash(path, hash))
        throw Error("no library of " + scene.path.string() + " (preset " + scene.preset + ", seed " +
                    std::to_string(scene.seed) + ") at " + path.string() + ": build it with `meadow precompute " +
                    scene.path.string() + " --preset " + scene.preset +
                    "`, or set MEADOW_CACHE_DIR to the folder that holds it");
    if (hash != libraryInputHash(scene))
        throw Error("library " + path.string() + " was built from other inputs than " + scene.path.string() +
                    " (preset " + scene.preset + "): build it again with `meadow precompute`");
    return loadLibrary(path);
}

} // namespace meadow
