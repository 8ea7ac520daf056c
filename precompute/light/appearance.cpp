#include "light/appearance.h"

#include "core/error.h"
#include "motion/pca.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace meadow {

std::vector<uint32_t> appearanceBakeFrames(const std::vector<MotionClip>& clips, uint32_t perClip) {
    if (perClip < 2)
        throw Error("appearance: at least 2 baked frames per clip are needed (got " + std::to_string(perClip) + ")");
    std::vector<uint32_t> frames;
    for (const MotionClip& clip : clips) {
        if (clip.frameCount == 0)
            continue;
        const uint32_t last = clip.frameCount - 1;
        const uint32_t count = std::min(perClip, clip.frameCount);
        for (uint32_t i = 0; i < count; ++i) {
            // Rounded evenly spaced offsets; count <= frameCount makes them distinct.
            const uint32_t offset =
                count == 1 ? 0 : uint32_t((uint64_t(i) * last * 2 + (count - 1)) / (2 * (count - 1)));
            frames.push_back(clip.firstFrame + offset);
        }
    }
    std::sort(frames.begin(), frames.end());
    frames.erase(std::unique(frames.begin(), frames.end()), frames.end());
    return frames;
}

AppearanceModel reduceAppearance(const Eigen::MatrixXf& baked, const std::vector<uint32_t>& bakedFrames,
                                 const std::vector<MotionClip>& clips, uint32_t frames, double maxRelativeError,
                                 uint32_t maxModes) {
    if (baked.cols() == 0 || size_t(baked.cols()) != bakedFrames.size())
        throw Error("appearance: " + std::to_string(baked.cols()) + " baked transfers for " +
                    std::to_string(bakedFrames.size()) + " baked frames");
    if (!baked.allFinite())
        throw Error("appearance: a baked transfer holds NaN or infinite values");
    if (!std::is_sorted(bakedFrames.begin(), bakedFrames.end()) ||
        std::adjacent_find(bakedFrames.begin(), bakedFrames.end()) != bakedFrames.end())
        throw Error("appearance: the baked frames must ascend without repeats");
    const std::vector<uint32_t> clipOf = clipOfFrames(clips, frames);
    for (uint32_t f : bakedFrames)
        if (f >= frames || clipOf[f] == kNoClip)
            throw Error("appearance: baked frame " + std::to_string(f) + " lies in no clip");
    for (const MotionClip& clip : clips) {
        const bool first = std::binary_search(bakedFrames.begin(), bakedFrames.end(), clip.firstFrame);
        const bool last =
            std::binary_search(bakedFrames.begin(), bakedFrames.end(), clip.firstFrame + clip.frameCount - 1);
        if (!first || !last)
            throw Error("appearance: the clip of frames " + std::to_string(clip.firstFrame) + " .. " +
                        std::to_string(clip.firstFrame + clip.frameCount - 1) +
                        " must have its first and last frames baked");
    }

    const PcaResult pca = computePca(baked, std::max<uint32_t>(1, maxModes));
    AppearanceModel model;
    model.mean = pca.mean;
    model.bakedFrames = bakedFrames;
    const double total = baked.cast<double>().squaredNorm();
    const double centred = (baked.cast<double>().colwise() - pca.mean.cast<double>()).squaredNorm();
    const double scale = total > 0.0 ? std::sqrt(centred / total) : 0.0;
    for (double e : pca.relativeErrorPerRank)
        model.relativeErrorPerMode.push_back(e * scale);
    uint32_t rank = uint32_t(pca.basis.cols());
    for (uint32_t k = 0; k < model.relativeErrorPerMode.size(); ++k)
        if (model.relativeErrorPerMode[k] <= maxRelativeError) {
            rank = std::min(rank, k);
            break;
        }
    model.basis = pca.basis.leftCols(rank);

    // Coordinates of every frame: the baked ones exact, the others interpolated within their clip.
    model.coords = Eigen::MatrixXf::Zero(rank, frames);
    for (const MotionClip& clip : clips) {
        auto it = std::lower_bound(bakedFrames.begin(), bakedFrames.end(), clip.firstFrame);
        for (uint32_t f = clip.firstFrame; f < clip.firstFrame + clip.frameCount; ++f) {
            while (*it < f)
                ++it; // the clip's last frame is baked, so this stops inside the clip
            const size_t hi = size_t(it - bakedFrames.begin());
            if (*it == f) {
                model.coords.col(f) = pca.coords.col(Eigen::Index(hi)).head(rank);
                continue;
            }
            const size_t lo = hi - 1; // the clip's first frame is baked and < f
            const float t = float(f - bakedFrames[lo]) / float(bakedFrames[hi] - bakedFrames[lo]);
            model.coords.col(f) = (1.0f - t) * pca.coords.col(Eigen::Index(lo)).head(rank) +
                                  t * pca.coords.col(Eigen::Index(hi)).head(rank);
        }
    }
    return model;
}

Eigen::VectorXf reconstructAppearance(const AppearanceModel& model, uint32_t frame) {
    return model.mean + model.basis * model.coords.col(Eigen::Index(frame));
}

} // namespace meadow
