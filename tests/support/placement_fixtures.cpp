#include "placement_fixtures.h"

#include "core/error.h"
#include "plants/iris.h"
#include "plants/rock.h"

#include <algorithm>
#include <cmath>
#include <gtest/gtest.h>

namespace meadow::test {
namespace {

glm::vec3 rotate(const glm::vec3& v, const glm::vec3& axis, float angle) {
    const float c = std::cos(angle), s = std::sin(angle);
    return v * c + glm::cross(axis, v) * s + axis * (glm::dot(axis, v) * (1.0f - c));
}

} // namespace

std::vector<std::vector<glm::vec3>> leanFrames(const PlantMesh& mesh, glm::vec2 wind, float maxAngle) {
    const glm::vec3 downwind = glm::normalize(glm::vec3(wind.x, 0.0f, wind.y));
    const glm::vec3 across = glm::cross(glm::vec3(0.0f, 1.0f, 0.0f), downwind); // turns +y toward downwind
    float height = 0.0f;
    for (const glm::vec3& p : mesh.positions)
        height = std::max(height, p.y);
    std::vector<std::vector<glm::vec3>> frames;
    for (float lean : {-0.2f, 0.0f, 0.35f, 0.7f, 1.0f})
        for (float sway : {0.0f, 0.15f, -0.15f}) {
            std::vector<glm::vec3>& frame = frames.emplace_back();
            for (const glm::vec3& p : mesh.positions) {
                const float along = std::max(p.y, 0.0f) / height;
                frame.push_back(rotate(rotate(p, across, maxAngle * lean * along), downwind, maxAngle * sway * along));
            }
        }
    return frames;
}

const std::vector<SweptVolume>& irisVolumes() {
    static const std::vector<SweptVolume> volumes = [] {
        std::vector<SweptVolume> out;
        for (const PlantClump& clump : makeIrisClumps(kPlantSeed, 4, irisParamsForPreset("ci")))
            out.push_back(voxelizeSweptSurface(clump.mesh.indices, leanFrames(clump.mesh, kWind, 0.35f),
                                               {kCellSize, kMargin, false}));
        return out;
    }();
    return volumes;
}

const std::vector<SweptVolume>& rockVolumes() {
    static const std::vector<SweptVolume> volumes = [] {
        std::vector<SweptVolume> out;
        for (const RockMesh& rock : makeRocks(kPlantSeed, 4, rockParamsForPreset("ci"))) {
            const std::vector<std::vector<glm::vec3>> frames{rock.positions};
            out.push_back(voxelizeSweptSurface(rock.indices, frames, {kCellSize, kMargin, true}));
        }
        return out;
    }();
    return volumes;
}

TileFillParams defaultFillParams() {
    TileFillParams params;
    params.windDirection = kWind;
    params.seed = 7;
    return params;
}

const WangTileFill& defaultFill() {
    static const WangTileFill fill = fillWangTiles(irisVolumes(), rockVolumes(), defaultFillParams());
    return fill;
}

void expectError(const std::function<void()>& call, const std::string& fragment) {
    try {
        call();
        ADD_FAILURE() << "no error; expected one mentioning '" << fragment << "'";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
    }
}

} // namespace meadow::test
