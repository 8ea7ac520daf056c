// Rod dynamics (precompute/sim): a whole iris clump stepped as simulateClumpLevel steps it
// (sim/clump_sim.cpp): RodSystem::step at dt = 1/600 s, two-way coupled to a real WindSolver, with
// the contact candidate refresh it makes every fifth substep. One iteration is one such group,
// five substeps and one refresh (1/120 s of simulated time); the refresh alone is benchmarked too.
#include "fixtures.h"

#include "sim/clump_sim.h"

#include <cmath>
#include <map>
#include <memory>
#include <mutex>
#include <stdexcept>

namespace meadow::bench {
namespace {

// clump_sim.cpp's cadence: candidates every 5 substeps with a 1.5 cm margin.
constexpr uint32_t kSubstepsPerCandidateUpdate = 5;
constexpr float kCandidateMargin = 0.015f;
constexpr float kWindSpeed = 4.0f; // m/s, the default scene's third level (0.7, 2, 4, 7)

// A clump settled into the wind: the state the timed loops step on in place. The air is not
// stepped while timing (its field stays at the settled one; the rods' forces accumulate in it as
// they do between two air steps), so the rods sway towards a steady bend and every substep
// costs what one in the recording does.
struct RodCase {
    ClumpSimSettings settings;
    std::unique_ptr<WindSolver> air;
    std::unique_ptr<RodSystem> rods;
    AirCoupling coupling;
    float dt = 0.0f;
    uint32_t nodes = 0;
};

bool finite(const RodSystem& rods) {
    for (const glm::vec3& p : rods.positions())
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
            return false;
    return true;
}

RodCase& rodCase(const std::string& preset) {
    static std::mutex mutex;
    static std::map<std::string, std::unique_ptr<RodCase>> cases;
    std::lock_guard<std::mutex> lock(mutex);
    std::unique_ptr<RodCase>& slot = cases[preset];
    if (slot)
        return *slot;
    const PlantClump& clump = irisClump(preset);
    auto c = std::make_unique<RodCase>();
    WindLevelParams level;
    level.direction = glm::normalize(glm::vec3(1.0f, 0.0f, 0.25f)); // irises.json
    level.meanSpeed = kWindSpeed;
    level.turbulence = 0.3f;
    level.seed = 31;
    c->air = std::make_unique<WindSolver>(c->settings.grid, level);
    c->rods = std::make_unique<RodSystem>(clump.rods, c->settings.material);
    c->nodes = uint32_t(c->rods->positions().size());
    WindSolver& air = *c->air;
    c->coupling.velocityAt = [&air](glm::vec3 p) { return air.velocityAt(p); };
    c->coupling.addForce = [&air](glm::vec3 p, glm::vec3 f) { air.addForce(p, f); };
    // Settle for half a second (15 frames x 20 substeps, the air stepped once per frame) so that
    // contacts and drag are those of a clump bent by the wind, not of the rest pose.
    const float frameDt = 1.0f / c->settings.frameRate;
    c->dt = frameDt / float(c->settings.substeps);
    for (uint32_t frame = 0; frame < 15; ++frame) {
        for (uint32_t s = 0; s < c->settings.substeps; ++s) {
            if (s % kSubstepsPerCandidateUpdate == 0)
                c->rods->updateContactCandidates(kCandidateMargin);
            c->rods->step(c->dt, c->coupling, 1.0f / float(c->settings.substeps));
        }
        air.step(frameDt);
    }
    if (!finite(*c->rods))
        throw std::runtime_error("the settling simulation diverged");
    slot = std::move(c);
    return *slot;
}

void rodStep(benchmark::State& state, const std::string& preset) {
    // The case is the benchmark's own state, stepped in place iteration after iteration.
    RodCase* c = setupOrFail(state, [&]() -> RodCase& { return rodCase(preset); });
    if (!c)
        return;
    RodSystem& rods = *c->rods;
    const float airWeight = 1.0f / float(c->settings.substeps);
    for (auto _ : state) {
        rods.updateContactCandidates(kCandidateMargin);
        for (uint32_t s = 0; s < kSubstepsPerCandidateUpdate; ++s)
            rods.step(c->dt, c->coupling, airWeight);
        benchmark::DoNotOptimize(rods.positions().data());
        benchmark::ClobberMemory();
    }
    if (!finite(rods))
        return fail(state, "rod positions are not finite after stepping");
    const double substeps = double(state.iterations()) * kSubstepsPerCandidateUpdate;
    state.SetItemsProcessed(int64_t(substeps) * c->nodes);
    state.counters["rods/s"] = benchmark::Counter(substeps * rods.rodCount(), benchmark::Counter::kIsRate);
    state.counters["pairs"] = double(rods.contactCandidateCount());
    state.SetLabel(describeClump(preset) + "; items = nodes x substeps; 5 substeps + 1 refresh per iteration");
}

void rodContactCandidates(benchmark::State& state, const std::string& preset) {
    RodCase* c = setupOrFail(state, [&]() -> RodCase& { return rodCase(preset); });
    if (!c)
        return;
    RodSystem& rods = *c->rods; // rebuilds only the candidate list
    for (auto _ : state) {
        rods.updateContactCandidates(kCandidateMargin);
        benchmark::ClobberMemory();
    }
    state.SetItemsProcessed(int64_t(state.iterations()) * rods.rodCount());
    state.counters["pairs"] = double(rods.contactCandidateCount());
    state.SetLabel(describeClump(preset) + "; items = rods; every capsule pair tested");
}

} // namespace

void registerRodBenchmarks() {
    for (const char* preset : kPresets) {
        const std::string p = preset;
        benchmark::RegisterBenchmark(("rod_step/" + p).c_str(), [p](benchmark::State& s) { rodStep(s, p); });
        benchmark::RegisterBenchmark(("rod_contact_candidates/" + p).c_str(),
                                     [p](benchmark::State& s) { rodContactCandidates(s, p); });
    }
}

} // namespace meadow::bench
