#include "fixtures.h"

#include "plants/iris.h"

#include <atomic>
#include <cstdio>
#include <map>
#include <mutex>

namespace meadow::bench {
namespace {

std::atomic<int> failures{0};

} // namespace

void fail(benchmark::State& state, const std::string& message) {
    ++failures;
    state.SkipWithError(message.c_str());
}

int failureCount() {
    return failures.load();
}

const PlantClump& irisClump(const std::string& preset) {
    static std::mutex mutex;
    static std::map<std::string, PlantClump> clumps;
    std::lock_guard<std::mutex> lock(mutex);
    auto it = clumps.find(preset);
    if (it == clumps.end())
        it = clumps.emplace(preset, std::move(makeIrisClumps(kSceneSeed, 1, irisParamsForPreset(preset))[0])).first;
    return it->second;
}

std::string describeClump(const std::string& preset) {
    const PlantClump& clump = irisClump(preset);
    size_t nodes = 0;
    for (const Rod& rod : clump.rods)
        nodes += rod.restNodes.size();
    char text[160];
    std::snprintf(text, sizeof text, "%s clump: %zu vertices, %zu triangles, %zu rods, %zu nodes", preset.c_str(),
                  clump.mesh.vertexCount(), clump.mesh.triangleCount(), clump.rods.size(), nodes);
    return text;
}

} // namespace meadow::bench
