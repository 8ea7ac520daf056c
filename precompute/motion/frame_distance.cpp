#include "motion/frame_distance.h"

#include "core/error.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <string>

namespace meadow {

std::vector<uint32_t> clipOfFrames(const std::vector<MotionClip>& clips, uint32_t frameCount) {
    std::vector<uint32_t> clipOf(frameCount, kNoClip);
    for (size_t c = 0; c < clips.size(); ++c) {
        const MotionClip& clip = clips[c];
        const std::string name = "motion clip " + std::to_string(c);
        if (clip.frameCount == 0)
            throw Error(name + " is empty");
        if (clip.level >= 255)
            throw Error(name + ": wind level " + std::to_string(clip.level) + " is out of range (at most 254)");
        if (uint64_t(clip.firstFrame) + clip.frameCount > frameCount)
            throw Error(name + ": frames [" + std::to_string(clip.firstFrame) + ", " +
                        std::to_string(uint64_t(clip.firstFrame) + clip.frameCount) + ") exceed the " +
                        std::to_string(frameCount) + " frames of q");
        for (uint32_t f = clip.firstFrame; f < clip.firstFrame + clip.frameCount; ++f) {
            if (clipOf[f] != kNoClip)
                throw Error(name + " overlaps motion clip " + std::to_string(clipOf[f]) + " at frame " +
                            std::to_string(f));
            clipOf[f] = uint32_t(c);
        }
    }
    return clipOf;
}

Eigen::MatrixXf motionFeatures(const Eigen::MatrixXf& q, const std::vector<MotionClip>& clips, float frameRate,
                               float velocityWeightSeconds) {
    const Eigen::Index r = q.rows();
    Eigen::MatrixXf features = Eigen::MatrixXf::Zero(2 * r, q.cols());
    features.topRows(r) = q;
    const float velocityScale = velocityWeightSeconds * frameRate;
    for (const MotionClip& clip : clips) {
        const Eigen::Index first = clip.firstFrame, last = clip.firstFrame + clip.frameCount - 1;
        for (Eigen::Index f = first; f <= last; ++f) {
            const Eigen::Index a = std::max(first, f - 1), b = std::min(last, f + 1);
            if (b == a)
                continue; // a one-frame clip has no velocity
            // (q_b - q_a) / ((b - a) / frameRate) seconds, times the weight in seconds.
            features.col(f).bottomRows(r) = (q.col(b) - q.col(a)) * (velocityScale / float(b - a));
        }
    }
    return features;
}

std::vector<float> pairwiseSquaredDistances(const Eigen::MatrixXf& features) {
    const size_t frames = size_t(features.cols());
    const Eigen::Index dims = features.rows();
    std::vector<float> d(frames * frames, 0.0f);
    // Direct differences rather than |a|^2 + |b|^2 - 2ab: no cancellation, an exact zero diagonal,
    // and at 2r <= 80 dimensions the O(F^2 r) loop costs milliseconds. Each row's entries with
    // b > a are written only by that row's task, mirrored into column a, so no two tasks touch
    // the same entry.
    tbb::parallel_for(tbb::blocked_range<size_t>(0, frames, 16), [&](const tbb::blocked_range<size_t>& rows) {
        for (size_t a = rows.begin(); a != rows.end(); ++a) {
            const float* fa = features.col(Eigen::Index(a)).data();
            for (size_t b = a + 1; b < frames; ++b) {
                const float* fb = features.col(Eigen::Index(b)).data();
                float sum = 0.0f;
                for (Eigen::Index c = 0; c < dims; ++c) {
                    const float diff = fa[c] - fb[c];
                    sum += diff * diff;
                }
                d[a * frames + b] = sum;
                d[b * frames + a] = sum;
            }
        }
    });
    return d;
}

std::vector<float> transitionDistances(const std::vector<float>& frameDistances, const std::vector<MotionClip>& clips,
                                       const std::vector<uint32_t>& clipOfFrame, uint32_t window) {
    const size_t frames = clipOfFrame.size();
    const int64_t half = int64_t(window / 2);
    const int64_t taps = 2 * half;
    // Binomial weights, as Schödl et al. 2000 (section 3.2) filter their distance matrix.
    std::vector<float> weight(size_t(taps), 1.0f);
    for (int64_t k = 0; k < taps; ++k) {
        double binomial = 1.0;
        for (int64_t m = 0; m < k; ++m)
            binomial = binomial * double(taps - 1 - m) / double(m + 1);
        weight[size_t(k)] = float(binomial);
    }
    float totalWeight = 0.0f;
    for (float w : weight)
        totalWeight += w;

    std::vector<float> result(frames * frames, std::numeric_limits<float>::infinity());
    tbb::parallel_for(tbb::blocked_range<size_t>(0, frames, 16), [&](const tbb::blocked_range<size_t>& rows) {
        for (size_t i = rows.begin(); i != rows.end(); ++i) {
            if (clipOfFrame[i] == kNoClip)
                continue;
            const MotionClip& from = clips[clipOfFrame[i]];
            const int64_t fromBegin = from.firstFrame, fromEnd = int64_t(from.firstFrame) + from.frameCount;
            for (size_t j = 0; j < frames; ++j) {
                if (clipOfFrame[j] == kNoClip)
                    continue;
                const MotionClip& to = clips[clipOfFrame[j]];
                const int64_t toBegin = to.firstFrame, toEnd = int64_t(to.firstFrame) + to.frameCount;
                const int64_t successor = int64_t(i) + 1;
                if (clipOfFrame[j] == clipOfFrame[i] && std::abs(int64_t(j) - successor) <= int64_t(window))
                    continue;
                float sum = 0.0f, used = 0.0f;
                for (int64_t k = -half; k < half; ++k) {
                    const int64_t a = successor + k, b = int64_t(j) + k;
                    if (a < fromBegin || a >= fromEnd || b < toBegin || b >= toEnd)
                        continue;
                    const float w = weight[size_t(k + half)];
                    sum += w * frameDistances[size_t(a) * frames + size_t(b)];
                    used += w;
                }
                if (used > 0.0f && 2.0f * used >= totalWeight)
                    result[i * frames + j] = sum / used;
            }
        }
    });
    return result;
}

} // namespace meadow
