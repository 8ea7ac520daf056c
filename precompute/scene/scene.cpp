#include "scene/scene.h"

#include "core/error.h"

#include <charconv>
#include <cmath>
#include <fstream>
#include <set>

namespace meadow {
namespace {

using nlohmann::json;

// Deeper than any valid scene (which nests four levels): refused before anything recurses over it.
constexpr size_t kMaxNesting = 64;
constexpr size_t kMaxNameLength = 64; // the name goes into the library's file name

// How deeply `doc` nests arrays and objects, counted without recursion.
size_t nestingDepth(const json& doc) {
    size_t deepest = 0;
    std::vector<std::pair<const json*, size_t>> pending{{&doc, 1}};
    while (!pending.empty()) {
        auto [value, depth] = pending.back();
        pending.pop_back();
        if (!value->is_structured())
            continue;
        deepest = std::max(deepest, depth);
        if (deepest > kMaxNesting)
            break;
        for (const json& child : *value)
            pending.emplace_back(&child, depth + 1);
    }
    return deepest;
}

// A value as quoted in a message: scalars as JSON (long strings cut short), arrays and objects by
// their size, so that a huge or deeply nested value cannot flood the message.
std::string describe(const json& v) {
    if (v.is_array())
        return "an array of " + std::to_string(v.size());
    if (v.is_object())
        return "an object of " + std::to_string(v.size()) + " keys";
    std::string text = v.dump(-1, ' ', false, json::error_handler_t::replace);
    if (text.size() > 40)
        text = text.substr(0, 40) + "...";
    return text;
}

class Checker {
  public:
    explicit Checker(std::string file) : file_(std::move(file)) {}

    [[noreturn]] void fail(const std::string& key, const std::string& what) const {
        throw Error("scene " + file_ + ": " + key + " " + what);
    }

    void onlyKeys(const json& object, const std::string& where, const std::set<std::string>& allowed) const {
        if (!object.is_object())
            fail(where.empty() ? "the top level" : where, "must be an object");
        for (auto it = object.begin(); it != object.end(); ++it)
            if (!allowed.count(it.key()))
                fail(where.empty() ? it.key() : where + "." + it.key(), "is not a known key");
    }

    const json& require(const json& object, const std::string& where, const std::string& key) const {
        auto it = object.find(key);
        if (it == object.end())
            fail(where.empty() ? key : where + "." + key, "is missing");
        return *it;
    }

    float number(const json& v, const std::string& key, float lo, float hi) const {
        if (!v.is_number())
            fail(key, "must be a number (got " + describe(v) + ")");
        double d = v.get<double>();
        if (!(d >= lo && d <= hi))
            fail(key, "must be between " + fmt(lo) + " and " + fmt(hi) + " (got " + describe(v) + ")");
        return static_cast<float>(d);
    }

    uint32_t count(const json& v, const std::string& key, uint32_t lo, uint32_t hi) const {
        if (!v.is_number_integer())
            fail(key, "must be an integer (got " + describe(v) + ")");
        int64_t i = v.get<int64_t>();
        if (i < lo || i > hi)
            fail(key,
                 "must be between " + std::to_string(lo) + " and " + std::to_string(hi) + " (got " + describe(v) + ")");
        return static_cast<uint32_t>(i);
    }

    glm::vec3 vec3(const json& v, const std::string& key) const {
        if (!v.is_array() || v.size() != 3)
            fail(key, "must be an array of three numbers (got " + describe(v) + ")");
        return {number(v[0], key + "[0]", -1e6f, 1e6f), number(v[1], key + "[1]", -1e6f, 1e6f),
                number(v[2], key + "[2]", -1e6f, 1e6f)};
    }

  private:
    // A bound as written in the code: the shortest decimal that reads back as the same float
    // (0.002, not the double 0.0020000000949949026), with ".0" on whole numbers.
    // Small fractions stay decimal too (0.0005, not 5e-04).
    static std::string fmt(float f) {
        char text[32];
        const bool fraction = std::abs(f) >= 1e-4f && std::abs(f) < 1.0f;
        auto [end, ec] = fraction ? std::to_chars(text, text + sizeof(text), f, std::chars_format::fixed)
                                  : std::to_chars(text, text + sizeof(text), f);
        std::string out(text, ec == std::errc() ? end : text);
        if (out.find_first_of(".en") == std::string::npos)
            out += ".0";
        return out;
    }
    std::string file_;
};

void checkPreset(const std::string& preset) {
    bool knownPreset = false;
    for (const char* name : kPresetNames)
        knownPreset |= preset == name;
    if (!knownPreset)
        throw Error("unknown preset '" + preset + "' (use ci or full)");
}

// The file as JSON, its nesting and top-level keys checked.
json readSceneJson(const std::filesystem::path& path, const Checker& check) {
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec))
        throw Error("scene " + path.string() + ": is a folder, not a scene file");
    std::ifstream in(path);
    if (!in)
        throw Error("scene " + path.string() + ": cannot open");
    json doc;
    try {
        doc = json::parse(in);
    } catch (const json::exception& e) { // parse errors, and numbers too large for a double
        // The parser quotes what it last read, which may be bytes that are not text.
        std::string what = e.what();
        for (char& c : what)
            if (static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) >= 0x7f)
                c = '?';
        throw Error("scene " + path.string() + ": invalid JSON: " + what);
    }
    if (nestingDepth(doc) > kMaxNesting)
        check.fail("the top level", "nests arrays and objects more than " + std::to_string(kMaxNesting) + " deep");
    check.onlyKeys(doc, "",
                   {"name", "description", "seed", "presets", "field", "camera", "timeOfDay", "plants", "wind",
                    "motion", "sky", "light", "lod"});
    return doc;
}

// The base description with the preset's overrides merged over it, and without "presets".
json resolvePreset(const json& doc, const std::string& preset, const Checker& check) {
    json resolved = doc;
    resolved.erase("presets");
    if (doc.contains("presets")) {
        const json& presets = doc["presets"];
        check.onlyKeys(presets, "presets", {"ci", "full"});
        if (presets.contains(preset)) {
            if (!presets[preset].is_object())
                check.fail("presets." + preset, "must be an object");
            if (presets[preset].contains("presets"))
                check.fail("presets." + preset + ".presets", "is not allowed");
            resolved.merge_patch(presets[preset]);
        }
    }
    return resolved;
}

// The name (it goes into file names) and the description.
std::string readName(const json& resolved, const Checker& check) {
    const json& name = check.require(resolved, "", "name");
    if (!name.is_string() || name.get<std::string>().empty())
        check.fail("name", "must be a non-empty string");
    std::string text = name.get<std::string>();
    if (text.size() > kMaxNameLength)
        check.fail("name", "must be at most " + std::to_string(kMaxNameLength) + " characters long (got " +
                               std::to_string(text.size()) + ")");
    for (char c : text)
        if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_'))
            check.fail("name", "may hold only letters, digits, '-' and '_' (got \"" + text + "\")");
    if (resolved.contains("description") && !resolved["description"].is_string())
        check.fail("description", "must be a string");
    return text;
}

// The seed given on the command line, else the scene's.
uint64_t readSeed(const json& resolved, std::optional<uint64_t> seed, const Checker& check) {
    if (seed)
        return *seed;
    const json& s = check.require(resolved, "", "seed");
    if (!s.is_number_unsigned())
        check.fail("seed", "must be a non-negative integer (got " + describe(s) + ")");
    return s.get<uint64_t>();
}

void readField(const json& resolved, FieldSpec& f, const Checker& check) {
    const json& field = check.require(resolved, "", "field");
    check.onlyKeys(field, "field",
                   {"tilesX", "tilesY", "tileSize", "cellSize", "margin", "yawJitter", "rocksPerTile", "rockVariants",
                    "sweptFrames", "tiling", "terrain"});
    f.tilesX = check.count(check.require(field, "field", "tilesX"), "field.tilesX", 1, 1024);
    f.tilesY = check.count(check.require(field, "field", "tilesY"), "field.tilesY", 1, 1024);
    f.tileSize = check.number(field.value("tileSize", json(f.tileSize)), "field.tileSize", 0.5f, 1000.0f);
    f.cellSize = check.number(field.value("cellSize", json(f.cellSize)), "field.cellSize", 0.002f, 1.0f);
    f.margin = check.number(field.value("margin", json(f.margin)), "field.margin", 0.0f, 1.0f);
    f.yawJitter = check.number(field.value("yawJitter", json(f.yawJitter)), "field.yawJitter", 0.0f, 3.14159f);
    f.rocksPerTile = check.count(field.value("rocksPerTile", json(f.rocksPerTile)), "field.rocksPerTile", 0, 1000);
    f.rockVariants = check.count(field.value("rockVariants", json(f.rockVariants)), "field.rockVariants", 1, 16);
    f.sweptFrames = check.count(field.value("sweptFrames", json(f.sweptFrames)), "field.sweptFrames", 2, 100000);
    const json& tiling = field.value("tiling", json(f.tiling));
    if (!tiling.is_string() || (tiling != "scanline" && tiling != "hash"))
        check.fail("field.tiling", "must be \"scanline\" or \"hash\" (got " + describe(tiling) + ")");
    f.tiling = tiling.get<std::string>();
    if (field.contains("terrain")) {
        const json& terrain = field["terrain"];
        check.onlyKeys(terrain, "field.terrain", {"amplitude", "wavelength"});
        f.terrainAmplitude =
            check.number(terrain.value("amplitude", json(f.terrainAmplitude)), "field.terrain.amplitude", 0.0f, 100.0f);
        f.terrainWavelength = check.number(terrain.value("wavelength", json(f.terrainWavelength)),
                                           "field.terrain.wavelength", 1.0f, 10000.0f);
    }
}

void readCamera(const json& cam, SceneCamera& camera, const Checker& check) {
    check.onlyKeys(cam, "camera", {"eye", "target", "fovYDegrees"});
    camera.eye = check.vec3(check.require(cam, "camera", "eye"), "camera.eye");
    camera.target = check.vec3(check.require(cam, "camera", "target"), "camera.target");
    camera.fovYDegrees = check.number(cam.value("fovYDegrees", json(55.0)), "camera.fovYDegrees", 5.0f, 150.0f);
    if (glm::length(camera.target - camera.eye) < 1e-3f)
        check.fail("camera.target", "must differ from camera.eye");
}

// Plants: iris clumps, or one clump from a glTF file next to the scene.
void readPlants(const json& plants, const std::filesystem::path& path, PlantsParams& spec, const Checker& check) {
    check.onlyKeys(plants, "plants", {"source", "clumps", "gltf", "stemDiameter"});
    const json& source = plants.value("source", json("iris"));
    if (!source.is_string() || (source != "iris" && source != "gltf"))
        check.fail("plants.source", "must be \"iris\" or \"gltf\" (got " + describe(source) + ")");
    spec.source = source.get<std::string>();
    spec.clumps = check.count(plants.value("clumps", json(4)), "plants.clumps", 1, 16);
    if (spec.source == "gltf") {
        const json& file = check.require(plants, "plants", "gltf");
        if (!file.is_string() || file.get<std::string>().empty())
            check.fail("plants.gltf", "must be a file name");
        spec.gltf = path.parent_path() / file.get<std::string>();
        spec.clumps = 1;
    }
    if (plants.contains("stemDiameter")) {
        if (spec.source != "gltf")
            check.fail("plants.stemDiameter",
                       "applies only to plants.source \"gltf\" (the irises' stems are part of the iris model)");
        spec.stemDiameter = check.number(plants["stemDiameter"], "plants.stemDiameter", 0.0005f, 0.5f);
    }
}

void readWind(const json& wind, WindParams& spec, const Checker& check) {
    check.onlyKeys(wind, "wind", {"direction", "levels", "turbulence", "gustPeriod"});
    if (wind.contains("direction")) {
        glm::vec3 d = check.vec3(wind["direction"], "wind.direction");
        d.y = 0.0f;
        if (glm::length(d) < 1e-3f)
            check.fail("wind.direction", "must have a horizontal component");
        spec.direction = glm::normalize(d);
    }
    if (wind.contains("levels")) {
        const json& levels = wind["levels"];
        if (!levels.is_array() || levels.size() < 2 || levels.size() > 8)
            check.fail("wind.levels", "must be an array of 2 to 8 speeds, calm first");
        spec.levelSpeeds.clear();
        for (size_t i = 0; i < levels.size(); ++i) {
            float speed = check.number(levels[i], "wind.levels[" + std::to_string(i) + "]", 0.0f, 30.0f);
            if (i > 0 && speed <= spec.levelSpeeds.back())
                check.fail("wind.levels", "must increase from calm to strong");
            spec.levelSpeeds.push_back(speed);
        }
    }
    spec.turbulence = check.number(wind.value("turbulence", json(0.3)), "wind.turbulence", 0.0f, 1.0f);
    spec.gustPeriod = check.number(wind.value("gustPeriod", json(4.0)), "wind.gustPeriod", 0.2f, 60.0f);
}

void readMotion(const json& motion, MotionParams& m, const Checker& check) {
    check.onlyKeys(motion, "motion", {"frameRate", "substeps", "settleSeconds", "recordSeconds", "lod0MaxError"});
    m.frameRate = check.number(motion.value("frameRate", json(30.0)), "motion.frameRate", 10.0f, 120.0f);
    m.substeps = check.count(motion.value("substeps", json(20)), "motion.substeps", 4, 200);
    m.settleSeconds = check.number(motion.value("settleSeconds", json(2.0)), "motion.settleSeconds", 0.0f, 60.0f);
    m.recordSeconds = check.number(motion.value("recordSeconds", json(20.0)), "motion.recordSeconds", 0.5f, 300.0f);
    m.lod0MaxError = check.number(motion.value("lod0MaxError", json(0.01)), "motion.lod0MaxError", 1e-4f, 0.5f);
}

// The sky's overrides of the preset's parameters, and panoramas (next to the scene) to use instead
// of the daylight model.
void readSky(const json& skyJson, const std::filesystem::path& path, SkySource& source, const Checker& check) {
    check.onlyKeys(
        skyJson, "sky",
        {"latitude", "dayOfYear", "turbidity", "groundAlbedo", "nightLuminance", "frames", "imageWidth", "maps"});
    sky::SkyParams& p = source.params;
    p.latitudeDegrees = check.number(skyJson.value("latitude", json(p.latitudeDegrees)), "sky.latitude", -90, 90);
    p.dayOfYear = check.number(skyJson.value("dayOfYear", json(p.dayOfYear)), "sky.dayOfYear", 1, 366);
    p.daylight.turbidity =
        check.number(skyJson.value("turbidity", json(p.daylight.turbidity)), "sky.turbidity", 1.7f, 10.0f);
    p.daylight.groundAlbedo =
        check.number(skyJson.value("groundAlbedo", json(p.daylight.groundAlbedo)), "sky.groundAlbedo", 0, 1);
    p.daylight.nightLuminance =
        check.number(skyJson.value("nightLuminance", json(p.daylight.nightLuminance)), "sky.nightLuminance", 0, 1000);
    p.frames = check.count(skyJson.value("frames", json(p.frames)), "sky.frames", 1, 4096);
    p.imageWidth = check.count(skyJson.value("imageWidth", json(p.imageWidth)), "sky.imageWidth", 4, 1024);
    if (p.imageWidth % 2 != 0)
        check.fail("sky.imageWidth", "must be even (the backdrop is a 2:1 panorama)");
    p.imageHeight = p.imageWidth / 2;
    if (skyJson.contains("maps")) {
        const json& maps = skyJson["maps"];
        if (!maps.is_array() || maps.empty() || maps.size() > 1024)
            check.fail("sky.maps", "must be an array of 1 to 1024 panorama file names");
        for (size_t i = 0; i < maps.size(); ++i) {
            if (!maps[i].is_string() || maps[i].get<std::string>().empty())
                check.fail("sky.maps[" + std::to_string(i) + "]", "must be a file name");
            source.maps.push_back(path.parent_path() / maps[i].get<std::string>());
        }
    }
}

// The light's overrides of the preset's bake settings.
void readLight(const json& light, LightParams& l, const Checker& check) {
    check.onlyKeys(light, "light",
                   {"raysPerVertex", "bounces", "framesPerLevel", "appearanceMaxError", "maxAppearanceModes",
                    "groundGridSize", "groundGridResolution", "groundRaysPerPoint"});
    l.bake.raysPerVertex =
        check.count(light.value("raysPerVertex", json(l.bake.raysPerVertex)), "light.raysPerVertex", 8, 65536);
    l.bake.bounces = check.count(light.value("bounces", json(l.bake.bounces)), "light.bounces", 0, 16);
    l.framesPerLevel =
        check.count(light.value("framesPerLevel", json(l.framesPerLevel)), "light.framesPerLevel", 2, 1000);
    l.appearanceMaxError = check.number(light.value("appearanceMaxError", json(l.appearanceMaxError)),
                                        "light.appearanceMaxError", 0.0f, 1.0f);
    l.maxAppearanceModes =
        check.count(light.value("maxAppearanceModes", json(l.maxAppearanceModes)), "light.maxAppearanceModes", 1, 256);
    l.bake.groundGridSize =
        check.number(light.value("groundGridSize", json(l.bake.groundGridSize)), "light.groundGridSize", 0.05f, 100.0f);
    l.bake.groundGridResolution = check.count(light.value("groundGridResolution", json(l.bake.groundGridResolution)),
                                              "light.groundGridResolution", 2, 256);
    l.bake.groundRaysPerPoint = check.count(light.value("groundRaysPerPoint", json(l.bake.groundRaysPerPoint)),
                                            "light.groundRaysPerPoint", 8, 65536);
}

// The triangle fractions of the LODs: 1 for LOD 0, then non-increasing.
void readLod(const json& lod, LodParams& spec, const Checker& check) {
    check.onlyKeys(lod, "lod", {"triangleFractions"});
    if (lod.contains("triangleFractions")) {
        const json& f = lod["triangleFractions"];
        if (!f.is_array() || f.size() != spec.triangleFractions.size())
            check.fail("lod.triangleFractions", "must be an array of 5 fractions of the full mesh");
        for (size_t i = 0; i < f.size(); ++i) {
            const std::string key = "lod.triangleFractions[" + std::to_string(i) + "]";
            spec.triangleFractions[i] = check.number(f[i], key, 1e-4f, 1.0f);
            if (i == 0 && spec.triangleFractions[0] != 1.0f)
                check.fail(key, "must be 1: LOD 0 is the full mesh");
            if (i > 0 && spec.triangleFractions[i] > spec.triangleFractions[i - 1])
                check.fail(key, "must not exceed the fraction before it");
        }
    }
}

} // namespace

Scene loadScene(const std::filesystem::path& path, const std::string& preset, std::optional<uint64_t> seed) {
    Checker check(path.string());
    checkPreset(preset);
    const json doc = readSceneJson(path, check);
    json resolved = resolvePreset(doc, preset, check);

    Scene scene;
    scene.path = path;
    scene.preset = preset;
    scene.name = readName(resolved, check);
    scene.seed = readSeed(resolved, seed, check);
    resolved["seed"] = scene.seed;
    readField(resolved, scene.field, check);
    if (resolved.contains("camera"))
        readCamera(resolved["camera"], scene.camera, check);
    if (resolved.contains("timeOfDay"))
        scene.timeOfDay = check.number(resolved["timeOfDay"], "timeOfDay", 0.0f, 24.0f);
    if (resolved.contains("plants"))
        readPlants(resolved["plants"], path, scene.plants, check);
    if (resolved.contains("wind"))
        readWind(resolved["wind"], scene.wind, check);
    if (resolved.contains("motion"))
        readMotion(resolved["motion"], scene.motion, check);

    scene.sky.params = sky::skyParamsForPreset(preset);
    if (resolved.contains("sky"))
        readSky(resolved["sky"], path, scene.sky, check);
    scene.light.bake = transfer::bakeSettingsForPreset(preset);
    if (preset == "ci")
        scene.light.framesPerLevel = 8;
    if (resolved.contains("light"))
        readLight(resolved["light"], scene.light, check);
    if (resolved.contains("lod"))
        readLod(resolved["lod"], scene.lod, check);
    if (preset == "ci")
        scene.far.samplesPerClump = 1024;

    scene.resolved = std::move(resolved);
    return scene;
}

} // namespace meadow
