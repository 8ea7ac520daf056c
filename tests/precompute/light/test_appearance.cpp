// Low-rank appearance over motion: which frames are baked, the error per mode, and coordinates of
// every frame interpolated within its clip.
#include "light/appearance.h"

#include "core/error.h"
#include "core/random.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>

using namespace meadow;

namespace {

const std::vector<MotionClip> kClips = {{0, 0, 10}, {1, 10, 5}, {2, 15, 1}};

// Transfer vectors of n values whose variation is two fixed directions with coordinates given
// per frame by `a`.
Eigen::MatrixXf transfers(const std::vector<uint32_t>& frames, Eigen::Index n,
                          const std::function<float(uint32_t, int)>& a, Eigen::VectorXf* meanOut = nullptr,
                          Eigen::MatrixXf* directionsOut = nullptr) {
    Random random(3);
    Eigen::VectorXf base(n);
    Eigen::MatrixXf directions(n, 2);
    for (Eigen::Index i = 0; i < n; ++i) {
        base(i) = 1.0f + random.uniform();
        directions(i, 0) = random.uniform(-0.1f, 0.1f);
        directions(i, 1) = random.uniform(-0.02f, 0.02f);
    }
    Eigen::MatrixXf out(n, Eigen::Index(frames.size()));
    for (size_t s = 0; s < frames.size(); ++s)
        out.col(Eigen::Index(s)) = base + directions.col(0) * a(frames[s], 0) + directions.col(1) * a(frames[s], 1);
    if (meanOut)
        *meanOut = base;
    if (directionsOut)
        *directionsOut = directions;
    return out;
}

} // namespace

TEST(Appearance, BakeFramesCoverEveryClipFromFirstToLast) {
    EXPECT_EQ(appearanceBakeFrames(kClips, 2), (std::vector<uint32_t>{0, 9, 10, 14, 15}));
    EXPECT_EQ(appearanceBakeFrames(kClips, 4), (std::vector<uint32_t>{0, 3, 6, 9, 10, 11, 13, 14, 15}));
    // More than a clip holds: every frame of it, once.
    EXPECT_EQ(appearanceBakeFrames({{0, 0, 3}}, 10), (std::vector<uint32_t>{0, 1, 2}));
    EXPECT_THROW(appearanceBakeFrames(kClips, 1), Error);
}

TEST(Appearance, PiecewiseLinearMotionIsReproducedAtEveryFrame) {
    // Coordinates linear in time inside each clip: interpolating between the clip's first and
    // last baked frames is then exact, at every frame, with two modes.
    auto a = [](uint32_t f, int k) { return k == 0 ? float(f % 10) - 3.0f : (f < 10 ? 0.5f * float(f) : -float(f)); };
    std::vector<uint32_t> baked = appearanceBakeFrames(kClips, 3);
    std::vector<uint32_t> all(16);
    for (uint32_t f = 0; f < 16; ++f)
        all[f] = f;
    const Eigen::MatrixXf truth = transfers(all, 200, a);
    const AppearanceModel model = reduceAppearance(transfers(baked, 200, a), baked, kClips, 16, 1e-6, 8);
    EXPECT_EQ(model.basis.cols(), 2);
    EXPECT_EQ(model.coords.cols(), 16);
    for (uint32_t f = 0; f < 16; ++f) {
        // Tolerance: float rounding of values of order 1.
        const float err = (reconstructAppearance(model, f) - truth.col(f)).cwiseAbs().maxCoeff();
        EXPECT_LE(err, 1e-5f) << "frame " << f;
    }
}

TEST(Appearance, ErrorIsRelativeToTheTransferAndPicksTheRank) {
    auto a = [](uint32_t f, int k) { return std::sin(0.7f * float(f) + float(k)) * (k == 0 ? 3.0f : 1.0f); };
    std::vector<uint32_t> baked = appearanceBakeFrames(kClips, 5);
    const Eigen::MatrixXf t = transfers(baked, 300, a);
    const AppearanceModel full = reduceAppearance(t, baked, kClips, 16, 0.0, 8);
    ASSERT_EQ(full.basis.cols(), 2);
    // Explicitly, for 0, 1 and 2 modes. Tolerance: float data of order 1.
    for (Eigen::Index k = 0; k <= 2; ++k) {
        const Eigen::MatrixXd centred = t.cast<double>().colwise() - full.mean.cast<double>();
        const Eigen::MatrixXd bk = full.basis.leftCols(k).cast<double>();
        const double err = (centred - bk * (bk.transpose() * centred)).norm() / t.cast<double>().norm();
        EXPECT_NEAR(full.relativeErrorPerMode[size_t(k)], err, 1e-6) << k;
    }
    // A bound between the one-mode and zero-mode errors keeps one mode.
    const double bound = 0.5 * (full.relativeErrorPerMode[0] + full.relativeErrorPerMode[1]);
    EXPECT_EQ(reduceAppearance(t, baked, kClips, 16, bound, 8).basis.cols(), 1);
    EXPECT_EQ(reduceAppearance(t, baked, kClips, 16, 0.0, 1).basis.cols(), 1); // maxModes caps it
}

TEST(Appearance, RejectsInconsistentInput) {
    auto a = [](uint32_t f, int) { return float(f); };
    std::vector<uint32_t> baked = appearanceBakeFrames(kClips, 2);
    const Eigen::MatrixXf t = transfers(baked, 10, a);
    EXPECT_THROW(reduceAppearance(t.leftCols(3), baked, kClips, 16, 0.01, 4), Error); // sizes differ
    std::vector<uint32_t> noLast = {0, 8, 10, 14, 15};                                // clip 0 ends at 9
    EXPECT_THROW(reduceAppearance(t, noLast, kClips, 16, 0.01, 4), Error);
    std::vector<uint32_t> outside = {0, 9, 10, 14, 16};
    EXPECT_THROW(reduceAppearance(t, outside, kClips, 16, 0.01, 4), Error);
    Eigen::MatrixXf nan = t;
    nan(1, 1) = std::nanf("");
    EXPECT_THROW(reduceAppearance(nan, baked, kClips, 16, 0.01, 4), Error);
}
