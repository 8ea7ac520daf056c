#include "render/camera_path.h"

#include "core/error.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <unistd.h>

namespace meadow {
namespace {

constexpr int kFormatVersion = 1;
// |direction.y| above this is within about 0.8 degrees of vertical: lookAt with +y up degenerates.
constexpr float kMaxVerticalCosine = 0.9999f;

std::string keyframeWhere(const std::string& where, size_t index) {
    return where + ": keyframe " + std::to_string(index);
}

bool finite(const glm::vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

double readNumber(const nlohmann::json& object, const char* name, const std::string& where) {
    auto it = object.find(name);
    if (it == object.end())
        throw Error(where + ": '" + name + "' is missing");
    if (!it->is_number())
        throw Error(where + ": '" + name + "' is not a number (" + it->dump() + ")");
    double value = it->get<double>();
    if (!std::isfinite(value))
        throw Error(where + ": '" + name + "' is not a finite number");
    return value;
}

glm::vec3 readVec3(const nlohmann::json& object, const char* name, const std::string& where) {
    auto it = object.find(name);
    if (it == object.end())
        throw Error(where + ": '" + name + "' is missing");
    if (!it->is_array() || it->size() != 3)
        throw Error(where + ": '" + name + "' is not an array of three numbers (" + it->dump() + ")");
    glm::vec3 v;
    for (int i = 0; i < 3; ++i) {
        const nlohmann::json& c = (*it)[size_t(i)];
        if (!c.is_number())
            throw Error(where + ": '" + name + "' is not an array of three numbers (" + it->dump() + ")");
        v[i] = float(c.get<double>());
    }
    if (!finite(v))
        throw Error(where + ": '" + name + "' holds a number too large for a float (" + it->dump() + ")");
    return v;
}

// Hermite cubic on [t0, t1] through p0, p1 with velocities m0, m1.
glm::vec3 hermite(const glm::vec3& p0, const glm::vec3& m0, const glm::vec3& p1, const glm::vec3& m1, double t0,
                  double t1, double t) {
    const double h = t1 - t0;
    const double s = (t - t0) / h;
    const double s2 = s * s, s3 = s2 * s;
    const double h00 = 2.0 * s3 - 3.0 * s2 + 1.0;
    const double h10 = s3 - 2.0 * s2 + s;
    const double h01 = -2.0 * s3 + 3.0 * s2;
    const double h11 = s3 - s2;
    glm::dvec3 r =
        h00 * glm::dvec3(p0) + (h10 * h) * glm::dvec3(m0) + h01 * glm::dvec3(p1) + (h11 * h) * glm::dvec3(m1);
    return glm::vec3(r);
}

// Catmull-Rom velocity at key i for non-uniform times: the finite difference across its
// neighbours; one-sided at the ends.
template <typename Get> glm::vec3 tangent(const std::vector<CameraKeyframe>& k, size_t i, Get get) {
    const size_t n = k.size();
    const size_t lo = i == 0 ? 0 : i - 1;
    const size_t hi = i + 1 == n ? n - 1 : i + 1;
    return glm::vec3((glm::dvec3(get(k[hi])) - glm::dvec3(get(k[lo]))) / (k[hi].time - k[lo].time));
}

// A float as the shortest decimal that reads back as the same float, so saved files stay
// readable ("0.1", not "0.10000000149011612") and load back bit for bit.
double shortestDecimal(float value) {
    char text[32];
    auto result = std::to_chars(text, text + sizeof(text), value);
    *result.ptr = '\0';
    return std::strtod(text, nullptr);
}

nlohmann::ordered_json vec3Json(const glm::vec3& v) {
    return {shortestDecimal(v.x), shortestDecimal(v.y), shortestDecimal(v.z)};
}

} // namespace

void validateCameraPath(const CameraPath& path, const std::string& where) {
    if (path.keyframes.empty())
        throw Error(where + ": the path has no keyframes");
    for (size_t i = 0; i < path.keyframes.size(); ++i) {
        const CameraKeyframe& k = path.keyframes[i];
        const std::string at = keyframeWhere(where, i);
        if (!std::isfinite(k.time))
            throw Error(at + ": 'time' is not a finite number");
        if (i > 0 && !(k.time > path.keyframes[i - 1].time)) {
            std::ostringstream s;
            s << at << ": 'time' " << k.time << " is not after the previous keyframe's " << path.keyframes[i - 1].time
              << " (times must increase)";
            throw Error(s.str());
        }
        if (!finite(k.eye) || !finite(k.target))
            throw Error(at + ": eye and target must be finite");
        glm::vec3 d = k.target - k.eye;
        float length = glm::length(d);
        if (length < 1e-3f)
            throw Error(at + ": the target must differ from the eye");
        if (std::abs(d.y) / length > kMaxVerticalCosine)
            throw Error(at + ": the camera looks straight up or down (the view's up is +y)");
    }
}

CameraPose sampleCameraPath(const CameraPath& path, double time) {
    const std::vector<CameraKeyframe>& k = path.keyframes;
    if (k.size() == 1 || !(time > k.front().time))
        return {k.front().eye, k.front().target};
    if (time >= k.back().time)
        return {k.back().eye, k.back().target};
    // The segment [k[i].time, k[i+1].time) holding `time`.
    size_t i = size_t(std::upper_bound(k.begin(), k.end(), time,
                                       [](double t, const CameraKeyframe& key) { return t < key.time; }) -
                      k.begin()) -
               1;
    auto eye = [](const CameraKeyframe& key) { return key.eye; };
    auto target = [](const CameraKeyframe& key) { return key.target; };
    CameraPose pose;
    pose.eye =
        hermite(k[i].eye, tangent(k, i, eye), k[i + 1].eye, tangent(k, i + 1, eye), k[i].time, k[i + 1].time, time);
    pose.target = hermite(k[i].target, tangent(k, i, target), k[i + 1].target, tangent(k, i + 1, target), k[i].time,
                          k[i + 1].time, time);
    // Eye and target are splined apart, so between keys the target can pass close to the eye
    // (a fast turn in place). Keep a direction then: the nearer key's.
    glm::vec3 d = pose.target - pose.eye;
    float length = glm::length(d);
    if (length < 1e-3f || std::abs(d.y) > kMaxVerticalCosine * length) {
        const CameraKeyframe& nearest = (time - k[i].time) < (k[i + 1].time - time) ? k[i] : k[i + 1];
        pose.target = pose.eye + (nearest.target - nearest.eye);
    }
    return pose;
}

nlohmann::ordered_json cameraPathToJson(const CameraPath& path) {
    nlohmann::ordered_json keys = nlohmann::ordered_json::array();
    for (const CameraKeyframe& k : path.keyframes)
        keys.push_back({{"time", k.time}, {"eye", vec3Json(k.eye)}, {"target", vec3Json(k.target)}});
    return {{"version", kFormatVersion}, {"keyframes", keys}};
}

CameraPath parseCameraPath(const nlohmann::json& json, const std::string& where) {
    if (!json.is_object())
        throw Error(where + ": a camera path is a JSON object with 'keyframes'");
    for (auto it = json.begin(); it != json.end(); ++it)
        if (it.key() != "version" && it.key() != "keyframes" && it.key() != "comment")
            throw Error(where + ": unknown field '" + it.key() + "' (fields: version, comment, keyframes)");
    if (json.contains("version")) {
        const nlohmann::json& v = json["version"];
        if (!v.is_number_integer() || v.get<int64_t>() != kFormatVersion)
            throw Error(where + ": unsupported version " + v.dump() + " (this meadow reads version " +
                        std::to_string(kFormatVersion) + ")");
    }
    auto keys = json.find("keyframes");
    if (keys == json.end())
        throw Error(where + ": 'keyframes' is missing");
    if (!keys->is_array())
        throw Error(where + ": 'keyframes' is not an array");
    CameraPath path;
    for (size_t i = 0; i < keys->size(); ++i) {
        const nlohmann::json& k = (*keys)[i];
        const std::string at = keyframeWhere(where, i);
        if (!k.is_object())
            throw Error(at + ": not an object with time, eye and target");
        for (auto it = k.begin(); it != k.end(); ++it)
            if (it.key() != "time" && it.key() != "eye" && it.key() != "target")
                throw Error(at + ": unknown field '" + it.key() + "' (fields: time, eye, target)");
        CameraKeyframe key;
        key.time = readNumber(k, "time", at);
        key.eye = readVec3(k, "eye", at);
        key.target = readVec3(k, "target", at);
        path.keyframes.push_back(key);
    }
    validateCameraPath(path, where);
    return path;
}

CameraPath loadCameraPath(const std::filesystem::path& file) {
    const std::string where = "camera path " + file.string();
    std::error_code ec;
    if (!std::filesystem::exists(file, ec))
        throw Error(where + ": no such file");
    if (std::filesystem::is_directory(file, ec))
        throw Error(where + ": is a folder, not a file");
    std::ifstream in(file);
    if (!in)
        throw Error(where + ": cannot open");
    nlohmann::json json;
    try {
        json = nlohmann::json::parse(in);
    } catch (const nlohmann::json::parse_error& e) {
        throw Error(where + ": invalid JSON (" + e.what() + ")");
    }
    return parseCameraPath(json, where);
}

void saveCameraPath(const std::filesystem::path& file, const CameraPath& path) {
    const std::string where = "camera path " + file.string();
    validateCameraPath(path, where);
    std::filesystem::path tmp = file;
    tmp.replace_filename("." + file.filename().string() + ".partial-" + std::to_string(getpid()));
    {
        std::ofstream out(tmp);
        if (!out)
            throw Error("cannot write " + where + " (cannot create " + tmp.string() + ")");
        // One keyframe per line: diffs of recorded paths stay readable.
        const nlohmann::ordered_json json = cameraPathToJson(path);
        out << "{\n  \"version\": " << json["version"].dump() << ",\n  \"keyframes\": [\n";
        const nlohmann::ordered_json& keys = json["keyframes"];
        for (size_t i = 0; i < keys.size(); ++i)
            out << "    " << keys[i].dump() << (i + 1 < keys.size() ? ",\n" : "\n");
        out << "  ]\n}\n";
        out.close();
        if (!out) {
            std::error_code ec;
            std::filesystem::remove(tmp, ec);
            throw Error("cannot write " + where);
        }
    }
    std::error_code ec;
    std::filesystem::rename(tmp, file, ec);
    if (ec) {
        std::filesystem::remove(tmp, ec);
        throw Error("cannot write " + where + ": " + ec.message());
    }
}

} // namespace meadow
