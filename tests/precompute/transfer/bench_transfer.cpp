// meadow_transfer_bench: what the PRT bake costs per frame of a procedural iris clump
// (docs/ARCHITECTURE.md, Light transfer; the precompute budget in docs/BENCHMARKS.md). Not a test:
// it asserts nothing and is run by hand.
//
//   meadow_transfer_bench [--mesh ci|full] [--rays N] [--bounces B] [--frames F] [--ground-rays N]
//                         [--ground-resolution R] [--threads T]
//
// Each frame sways the clump (a bend growing with height, as the wind does) so the Embree scene is
// rebuilt every frame, as in the real bake. Prints one line per frame and a summary: seconds per
// frame (median), vertex rays per second of the ray-casting stage and of the whole frame.
#include "plants/iris.h"
#include "transfer/transfer.h"

#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

using namespace meadow;

namespace {

[[noreturn]] void usage(const char* message) {
    std::fprintf(stderr,
                 "meadow_transfer_bench: %s\nusage: meadow_transfer_bench [--mesh ci|full] [--rays N] [--bounces B] "
                 "[--frames F] [--ground-rays N] [--ground-resolution R] [--threads T]\n",
                 message);
    std::exit(2);
}

uint32_t parseCount(const char* text, const char* flag) {
    char* end = nullptr;
    const unsigned long value = std::strtoul(text, &end, 10);
    if (!end || *end != '\0' || value > 1u << 20)
        usage((std::string(flag) + " takes a whole number").c_str());
    return uint32_t(value);
}

} // namespace

int main(int argc, char** argv) {
    std::string meshPreset = "full";
    transfer::BakeSettings settings = transfer::bakeSettingsForPreset("full");
    uint32_t frames = 5, threads = 0;
    for (int i = 1; i < argc; ++i) {
        const std::string flag = argv[i];
        if (i + 1 >= argc)
            usage(("missing value after " + flag).c_str());
        const char* value = argv[++i];
        if (flag == "--mesh")
            meshPreset = value;
        else if (flag == "--rays")
            settings.raysPerVertex = parseCount(value, "--rays");
        else if (flag == "--bounces")
            settings.bounces = parseCount(value, "--bounces");
        else if (flag == "--frames")
            frames = std::max(1u, parseCount(value, "--frames"));
        else if (flag == "--ground-rays")
            settings.groundRaysPerPoint = parseCount(value, "--ground-rays");
        else if (flag == "--ground-resolution")
            settings.groundGridResolution = parseCount(value, "--ground-resolution");
        else if (flag == "--threads")
            threads = parseCount(value, "--threads");
        else
            usage(("unknown option " + flag).c_str());
    }
    std::unique_ptr<tbb::global_control> limit;
    if (threads > 0)
        limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, threads);

    try {
        const PlantClump clump = makeIrisClumps(20040807, 1, irisParamsForPreset(meshPreset)).front();
        const PlantMesh& mesh = clump.mesh;
        const std::vector<glm::vec3> albedo(mesh.vertexCount(), glm::vec3(0.12f, 0.3f, 0.1f));
        const std::vector<float> translucency = transfer::translucencyForParts(mesh.parts, settings);
        transfer::TransferBaker baker(mesh.indices, albedo, translucency, settings);
        std::printf(
            "iris clump (%s mesh): %zu vertices, %zu triangles; %u rays/vertex, %u bounces, ground %u^2 x %u rays\n",
            meshPreset.c_str(), mesh.vertexCount(), mesh.triangleCount(), settings.raysPerVertex, settings.bounces,
            settings.groundGridResolution, settings.groundRaysPerPoint);

        std::vector<double> seconds, castRate, frameRate;
        std::vector<glm::vec3> positions(mesh.vertexCount());
        for (uint32_t f = 0; f < frames; ++f) {
            const float sway = 0.15f * std::sin(0.7f * float(f));
            for (size_t v = 0; v < positions.size(); ++v) {
                const glm::vec3 p = mesh.positions[v];
                positions[v] = p + glm::vec3(sway * p.y * p.y, 0.0f, 0.5f * sway * p.y * p.y);
            }
            const transfer::ClumpTransfer result = baker.bake(positions, mesh.normals);
            const transfer::BakeStats& s = result.stats;
            const double rays = double(s.vertexRays + s.groundRays);
            std::printf("frame %u: %.3f s (build %.4f, vertex rays %.3f, bounces %.3f, ground %.3f); "
                        "%.2f Mrays/s casting, %.2f Mrays/s whole frame\n",
                        f, s.totalSeconds, s.buildSeconds, s.castSeconds, s.bounceSeconds, s.groundSeconds,
                        double(s.vertexRays) / s.castSeconds * 1e-6, rays / s.totalSeconds * 1e-6);
            seconds.push_back(s.totalSeconds);
            castRate.push_back(double(s.vertexRays) / s.castSeconds);
            frameRate.push_back(rays / s.totalSeconds);
        }
        auto median = [](std::vector<double> v) {
            std::sort(v.begin(), v.end());
            return v[v.size() / 2];
        };
        std::printf("median: %.3f s per frame, %.2f Mrays/s casting, %.2f Mrays/s whole frame\n", median(seconds),
                    median(castRate) * 1e-6, median(frameRate) * 1e-6);
    } catch (const std::exception& error) {
        std::fprintf(stderr, "meadow_transfer_bench: %s\n", error.what());
        return 1;
    }
    return 0;
}
