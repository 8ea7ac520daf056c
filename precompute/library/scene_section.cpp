#include "library/sections.h"

#include "core/error.h"

namespace meadow {

void writeSceneSection(ByteWriter& w, const Library& library) {
    const std::string text = library.scene.dump(2);
    w.bytes(text.data(), text.size());
}

void readSceneSection(ByteReader& r, const std::string& where, Library& library) {
    std::vector<uint8_t> bytes(r.remaining());
    r.bytes(bytes.data(), bytes.size());
    try {
        library.scene = nlohmann::json::parse(bytes.begin(), bytes.end());
    } catch (const nlohmann::json::exception& e) {
        throw Error(where + " is not valid JSON: " + e.what());
    }
    // The resolved scene as precompute wrote it; what readers of `scene` rely on is checked here.
    const nlohmann::json& scene = library.scene;
    if (!scene.is_object() || !scene.contains("name") || !scene["name"].is_string() || !scene.contains("seed") ||
        !scene["seed"].is_number_unsigned() ||
        (scene.contains("field") && (!scene["field"].is_object() || (scene["field"].contains("yawJitter") &&
                                                                     !scene["field"]["yawJitter"].is_number()))))
        throw Error(where + " is not a resolved scene (an object with a name, a seed and a field)");
}

} // namespace meadow
