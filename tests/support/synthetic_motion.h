// Synthetic "wind levels" for motion tests: each of r coordinates is a damped oscillator pulled
// toward a gusty target (Ornstein-Uhlenbeck processes, shared and per mode), whose mean and spread
// grow with the wind level, plus a little measurement noise. Like a simulated plant, the motion never repeats
// exactly but revisits similar states, and neighbouring levels overlap.
#pragma once

#include "core/random.h"
#include "motion/frame_distance.h"

#include <Eigen/Core>

#include <cmath>
#include <vector>

namespace meadow::test {

struct SyntheticMotion {
    Eigen::MatrixXf q; // dims x frames
    std::vector<MotionClip> clips;
};

inline float gaussian(Random& random) {
    // Box-Muller; Random::uniform is in [0, 1), so 1 - u is never 0.
    const float u = 1.0f - random.uniform(), v = random.uniform();
    return std::sqrt(-2.0f * std::log(u)) * std::cos(6.28318530718f * v);
}

inline SyntheticMotion makeSyntheticMotion(uint32_t levels, uint32_t clipsPerLevel, uint32_t framesPerClip,
                                           uint32_t dims, uint64_t seed) {
    SyntheticMotion motion;
    motion.q.resize(dims, Eigen::Index(levels) * clipsPerLevel * framesPerClip);
    Random random(seed);
    const float dt = 1.0f / 30.0f;
    const uint32_t substeps = 4, settleFrames = 60;
    uint32_t column = 0;
    for (uint32_t level = 0; level < levels; ++level)
        for (uint32_t c = 0; c < clipsPerLevel; ++c) {
            motion.clips.push_back({level, column, framesPerClip});
            // One gust shared by every mode plus a little of each mode's own, as a clump's modes
            // all feel the same wind; higher modes move less (a PCA basis's coordinates decay).
            std::vector<float> x(dims), v(dims, 0.0f), ownGust(dims, 0.0f);
            float sharedGust = 0.0f;
            const float spread = 0.15f * (1.0f + float(level));
            const float gustRate = 1.5f; // 1/s: gusts change over ~0.7 s
            auto modeMean = [&](uint32_t d) { return 0.3f * float(level) * std::pow(0.7f, float(d)); };
            for (uint32_t d = 0; d < dims; ++d)
                x[d] = modeMean(d);
            const float h = dt / float(substeps);
            const float kick = std::sqrt(2.0f * gustRate * h);
            for (uint32_t f = 0; f < settleFrames + framesPerClip; ++f) {
                for (uint32_t s = 0; s < substeps; ++s) {
                    sharedGust += -gustRate * sharedGust * h + kick * gaussian(random);
                    for (uint32_t d = 0; d < dims; ++d) {
                        ownGust[d] += -gustRate * ownGust[d] * h + kick * gaussian(random);
                        const float omega = 6.28318530718f * (0.6f + 0.13f * float(d)); // 0.6 .. 2 Hz
                        const float damping = 0.15f;
                        const float pull =
                            modeMean(d) + spread * std::pow(0.7f, float(d)) * (0.8f * sharedGust + 0.6f * ownGust[d]);
                        const float accel = -omega * omega * (x[d] - pull) - 2.0f * damping * omega * v[d];
                        v[d] += accel * h;
                        x[d] += v[d] * h;
                    }
                }
                if (f >= settleFrames)
                    for (uint32_t d = 0; d < dims; ++d)
                        motion.q(d, column + (f - settleFrames)) = x[d] + 0.002f * gaussian(random);
            }
            column += framesPerClip;
        }
    return motion;
}

} // namespace meadow::test
