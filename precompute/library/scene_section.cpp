#include "library/sections.h"

#include "core/error.h"

#include <nlohmann/json.hpp>

namespace meadow {

LibraryScene parseLibraryScene(std::string json, const std::string& where) {
    nlohmann::json scene;
    try {
        scene = nlohmann::json::parse(json);
    } catch (const nlohmann::json::exception& e) {
        throw Error(where + " is not valid JSON: " + e.what());
    }
    if (!scene.is_object() || !scene.contains("name") || !scene["name"].is_string() || !scene.contains("seed") ||
        !scene["seed"].is_number_unsigned() ||
        (scene.contains("field") && (!scene["field"].is_object() || (scene["field"].contains("yawJitter") &&
                                                                     !scene["field"]["yawJitter"].is_number()))))
        throw Error(where + " is not a resolved scene (an object with a name, a seed and a field)");
    LibraryScene out;
    out.name = scene["name"].get<std::string>();
    out.seed = scene["seed"].get<uint64_t>();
    if (scene.contains("field") && scene["field"].contains("yawJitter"))
        out.yawJitter = scene["field"]["yawJitter"].get<float>();
    out.json = std::move(json);
    return out;
}

void writeSceneSection(ByteWriter& w, const Library& library) {
    w.bytes(library.scene.json.data(), library.scene.json.size());
}

void readSceneSection(ByteReader& r, const std::string& where, Library& library) {
    std::string text(r.remaining(), '\0');
    r.bytes(text.data(), text.size());
    library.scene = parseLibraryScene(std::move(text), where);
}

} // namespace meadow
