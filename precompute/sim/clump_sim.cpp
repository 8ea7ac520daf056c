#include "sim/clump_sim.h"

#include "core/error.h"

#include <algorithm>
#include <cmath>

namespace meadow {
namespace {
constexpr uint32_t kSubstepsPerCandidateUpdate = 5;
} // namespace

LevelSimulation simulateClumpLevel(const PlantClump& clump, const WindLevelSpec& wind, uint32_t level,
                                   const ClumpSimSettings& settings, uint64_t seed) {
    WindLevelParams airParams;
    airParams.direction = glm::normalize(glm::vec3(settings.windDirection.x, 0.0f, settings.windDirection.z));
    airParams.meanSpeed = wind.meanSpeed;
    airParams.turbulence = wind.turbulence;
    airParams.gustPeriod = settings.gustPeriod;
    airParams.seed = seed;
    WindSolver air(settings.grid, airParams);
    RodSystem rods(clump.rods, settings.material);

    const float frameDt = 1.0f / settings.frameRate;
    const float dt = frameDt / float(settings.substeps);
    const uint32_t settleFrames = uint32_t(std::lround(settings.settleSeconds * settings.frameRate));
    const uint32_t recordFrames =
        std::max<uint32_t>(2, uint32_t(std::lround(settings.recordSeconds * settings.frameRate)));

    // The wind ramps from still air over the first half of the settling time, so the clump bends
    // into it instead of being struck by a wall of air.
    float ramp = 1.0f;
    AirCoupling coupling;
    coupling.velocityAt = [&](glm::vec3 p) { return ramp * air.velocityAt(p); };
    if (settings.twoWayCoupling)
        coupling.addForce = [&](glm::vec3 p, glm::vec3 f) { air.addForce(p, ramp * f); };

    LevelSimulation out;
    out.level = level;
    out.frames = recordFrames;
    out.nodesPerFrame = uint32_t(rods.positions().size());
    out.nodeFrames.reserve(size_t(recordFrames) * out.nodesPerFrame);
    double energySum[2] = {0.0, 0.0};
    for (uint32_t frame = 0; frame < settleFrames + recordFrames; ++frame) {
        float t = float(frame) * frameDt;
        ramp = settleFrames > 0 ? std::clamp(t / (0.5f * settings.settleSeconds), 0.0f, 1.0f) : 1.0f;
        for (uint32_t s = 0; s < settings.substeps; ++s) {
            // Candidate pairs are refreshed every few substeps with a margin that covers the
            // motion in between (1.5 cm in 1/120 s: relative speeds below 1.8 m/s); testing
            // fewer pairs is most of the simulation's speed.
            if (s % kSubstepsPerCandidateUpdate == 0)
                rods.updateContactCandidates(0.015f);
            rods.step(dt, coupling, 1.0f / float(settings.substeps));
        }
        air.step(frameDt);
        for (const glm::vec3& p : rods.positions())
            if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
                throw Error("clump " + clump.name + ", wind level " + std::to_string(level) +
                            ": the rod simulation diverged after " + std::to_string(t) + " s");
        if (frame < settleFrames) {
            rods.takeMaxPenetration();
            continue;
        }
        uint32_t recorded = frame - settleFrames;
        out.nodeFrames.insert(out.nodeFrames.end(), rods.positions().begin(), rods.positions().end());
        out.maxPenetration = std::max(out.maxPenetration, rods.takeMaxPenetration());
        double energy = rods.kineticEnergy();
        out.maxKineticEnergy = std::max(out.maxKineticEnergy, energy);
        energySum[recorded < recordFrames / 2 ? 0 : 1] += energy;
        out.maxAirDivergence = std::max(out.maxAirDivergence, air.maxDivergence());
    }
    out.firstHalfKineticEnergy = energySum[0] / double(recordFrames / 2);
    out.secondHalfKineticEnergy = energySum[1] / double(recordFrames - recordFrames / 2);
    out.contactCandidates = rods.contactCandidateCount();
    return out;
}

} // namespace meadow
