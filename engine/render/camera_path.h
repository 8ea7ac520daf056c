// A recorded camera path: keyframes of (time, eye, target), played back by `meadow view`,
// `meadow render --camera-path` and `meadow bench --camera-path`, so that one flight drives all
// three. Between keyframes eye and target follow Catmull-Rom splines in time (Hermite cubics with
// finite-difference tangents, which stay valid for unevenly spaced keys): the path passes
// through every keyframe with a continuous velocity, and a camera moving at constant velocity is
// reproduced exactly.
//
// File format (JSON):
//   { "version": 1,
//     "comment": "optional free text",
//     "keyframes": [ { "time": 0.0, "eye": [x, y, z], "target": [x, y, z] }, ... ] }
// Times are seconds, strictly increasing; positions are world metres (y up). A keyframe's target
// must differ from its eye and must not look straight up or down.
#pragma once

#include <filesystem>
#include <glm/glm.hpp>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace meadow {

struct CameraKeyframe {
    double time = 0.0; // seconds from the start of the path
    glm::vec3 eye{0.0f};
    glm::vec3 target{0.0f, 0.0f, 1.0f};
};

struct CameraPath {
    std::vector<CameraKeyframe> keyframes;

    double startTime() const { return keyframes.empty() ? 0.0 : keyframes.front().time; }
    double endTime() const { return keyframes.empty() ? 0.0 : keyframes.back().time; }
    double duration() const { return endTime() - startTime(); }
};

struct CameraPose {
    glm::vec3 eye{0.0f};
    glm::vec3 target{0.0f, 0.0f, 1.0f};
};

// Throws meadow::Error, starting with `where` (a file name), naming the keyframe and what is
// wrong: no keyframes, a time that is not after the one before, a non-finite number, a target
// at the eye, a view straight up or down, an unknown field.
void validateCameraPath(const CameraPath& path, const std::string& where);

// The path at `time` (seconds, same clock as the keyframes): clamped to the first and last
// keyframe outside them. Precondition: the path passed validateCameraPath.
CameraPose sampleCameraPath(const CameraPath& path, double time);

// JSON in the format above. parseCameraPath validates; `where` names the source in errors.
nlohmann::ordered_json cameraPathToJson(const CameraPath& path);
CameraPath parseCameraPath(const nlohmann::json& json, const std::string& where);

// Reads and validates a path file; errors name the file and the problem.
CameraPath loadCameraPath(const std::filesystem::path& file);
// Writes the file whole or not at all (a temporary beside it, renamed into place). Validates first.
void saveCameraPath(const std::filesystem::path& file, const CameraPath& path);

} // namespace meadow
