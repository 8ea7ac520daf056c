// Appearance that follows deformation (James & Fatahalian 2003, "Precomputing interactive dynamic
// deformable scenes"): light transfer is baked on a sample of the motion frames, reduced by PCA
// to a small appearance basis, T(f) ≈ T̄ + B a(f), and every motion frame gets appearance
// coordinates a(f). Frames between two baked frames of the same clip take the linear
// interpolation of their coordinates: the frames are 1/30 s apart and the baked ones a fraction
// of a sway period, so the pose, and with it the light, changes smoothly in between.
#pragma once

#include "motion/frame_distance.h"

#include <Eigen/Core>

#include <cstdint>
#include <vector>

namespace meadow {

// The frames to bake: of each clip `perClip` (>= 2) frames evenly spread from its first to its
// last frame inclusive (fewer if the clip is shorter), ascending, without repeats. Throws
// meadow::Error if perClip < 2.
std::vector<uint32_t> appearanceBakeFrames(const std::vector<MotionClip>& clips, uint32_t perClip);

struct AppearanceModel {
    Eigen::VectorXf mean;   // n: the mean transfer over the baked frames
    Eigen::MatrixXf basis;  // n x r, orthonormal columns
    Eigen::MatrixXf coords; // r x F: every motion frame's coordinates
    std::vector<uint32_t> bakedFrames;
    // [k] = ||T - (T̄ + B_k B_kᵀ (T - T̄))||_F / ||T||_F over the baked frames, k = 0 .. modes the
    // PCA found: the error relative to the transfer itself (not to its variation), which is what
    // the picture shows.
    std::vector<double> relativeErrorPerMode;
};

// baked: n x S, column s the transfer of frame bakedFrames[s]; frames: the motion frames in all.
// Keeps the fewest modes (at most maxModes) whose relative error is <= maxRelativeError.
// Deterministic. Throws meadow::Error on inconsistent or non-finite input.
AppearanceModel reduceAppearance(const Eigen::MatrixXf& baked, const std::vector<uint32_t>& bakedFrames,
                                 const std::vector<MotionClip>& clips, uint32_t frames, double maxRelativeError,
                                 uint32_t maxModes);

// T̄ + B a(frame).
Eigen::VectorXf reconstructAppearance(const AppearanceModel& model, uint32_t frame);

} // namespace meadow
