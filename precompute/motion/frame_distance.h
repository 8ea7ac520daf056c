// Frame-to-frame distances for finding motion-graph transitions (Schödl et al. 2000, section 3;
// Kovar et al. 2002, section 3.1). Internal to meadow_motion; exposed for tests and tools.
#pragma once

#include <Eigen/Core>

#include <cstdint>
#include <limits>
#include <vector>

namespace meadow {

// Consecutive frames (columns of q) of one wind level's simulation.
struct MotionClip {
    uint32_t level = 0;
    uint32_t firstFrame = 0;
    uint32_t frameCount = 0;
};

inline constexpr uint32_t kNoClip = std::numeric_limits<uint32_t>::max();

// Which clip each frame belongs to (kNoClip where none). Throws meadow::Error if a clip leaves
// [0, frameCount), is empty, overlaps another, or names a level >= 255.
std::vector<uint32_t> clipOfFrames(const std::vector<MotionClip>& clips, uint32_t frameCount);

// Per-frame features [q; velocityWeightSeconds * dq/dt] (2r x F). The velocity is a central
// difference inside the clip (one-sided at its ends), so a match also agrees in direction of
// motion: Schödl et al. preserve dynamics with a window, Kovar et al. compare velocities too.
Eigen::MatrixXf motionFeatures(const Eigen::MatrixXf& q, const std::vector<MotionClip>& clips, float frameRate,
                               float velocityWeightSeconds);

// Row-major F x F matrix of squared feature distances d(a, b), symmetric, exact zero diagonal.
// Each entry is summed in the same order whatever the thread count.
std::vector<float> pairwiseSquaredDistances(const Eigen::MatrixXf& features);

// Transition distances D(i -> j) (row-major F x F, +inf where no transition may be considered):
// the binomially weighted window sum over k in [-window/2, window/2) of d(i + 1 + k, j + k),
// i.e. how well j and its neighbours stand in for i's natural successor and its neighbours.
// Terms whose frames leave their clip are dropped and the sum renormalised, provided at least half
// of the window's weight remains: that lets a clip's last frame (no i + 1) still find
// transitions by its past. Pairs in one clip with |j - (i + 1)| <= window are excluded: such a
// jump skips or repeats a few frames of the same motion, which reads as a stutter, not variety.
std::vector<float> transitionDistances(const std::vector<float>& frameDistances, const std::vector<MotionClip>& clips,
                                       const std::vector<uint32_t>& clipOfFrame, uint32_t window);

} // namespace meadow
