#include "core/random.h"
#include "sim/segment_distance.h"

#include <cmath>
#include <gtest/gtest.h>
#include <limits>

using namespace meadow;

namespace {

glm::vec3 randomPoint(Random& rng, float half) {
    return {rng.uniform(-half, half), rng.uniform(-half, half), rng.uniform(-half, half)};
}

} // namespace

TEST(SegmentDistance, ClosestPointsOfCrossingParallelAndDegenerateSegments) {
    float s = -1.0f, t = -1.0f;
    // Crossing at right angles, 0.3 apart in z, at their middles.
    EXPECT_NEAR(segmentDistance({-1, 0, 0}, {1, 0, 0}, {0, -1, 0.3f}, {0, 1, 0.3f}, s, t), 0.3f, 1e-6f);
    EXPECT_NEAR(s, 0.5f, 1e-6f);
    EXPECT_NEAR(t, 0.5f, 1e-6f);
    // Parallel, overlapping in x, 0.2 apart in y.
    EXPECT_NEAR(segmentDistance({0, 0, 0}, {1, 0, 0}, {0.5f, 0.2f, 0}, {2, 0.2f, 0}, s, t), 0.2f, 1e-6f);
    // End to end along one line: the nearer ends.
    EXPECT_NEAR(segmentDistance({0, 0, 0}, {1, 0, 0}, {1.5f, 0, 0}, {3, 0, 0}, s, t), 0.5f, 1e-6f);
    EXPECT_FLOAT_EQ(s, 1.0f);
    EXPECT_FLOAT_EQ(t, 0.0f);
    // A point (a flower's sphere) against a segment, and two points.
    EXPECT_NEAR(segmentDistance({0.5f, 0.4f, 0}, {0.5f, 0.4f, 0}, {0, 0, 0}, {1, 0, 0}, s, t), 0.4f, 1e-6f);
    EXPECT_NEAR(segmentDistance({0, 0, 0}, {0, 0, 0}, {0, 0.1f, 0}, {0, 0.1f, 0}, s, t), 0.1f, 1e-6f);
}

// The rod system passes over a contact candidate whose bounds are apart before measuring its
// distance, and must find the same pairs within the limit as when it measures every one: whenever
// segmentBoundsApart says apart, segmentDistance is at least the limit. Pairs are placed with their
// bounds' gap near the limit, on either side, at clump-sized coordinates (up to 2 m from the
// origin), and include parallel, axis-aligned and degenerate segments.
TEST(SegmentDistance, BoundsApartOnlyWhereTheDistanceIsAtLeastTheLimit) {
    Random rng(20261208);
    int apart = 0, notApart = 0, withinLimit = 0;
    for (int i = 0; i < 200000; ++i) {
        const glm::vec3 centre = randomPoint(rng, 2.0f);
        const int shape = i % 4;
        const glm::vec3 d1 = shape == 3 ? glm::vec3(0.0f) : randomPoint(rng, 0.05f);
        glm::vec3 d2 = shape == 1 ? d1 : randomPoint(rng, 0.05f); // 1: parallel
        if (shape == 2)
            d2 = {d2.x, 0.0f, 0.0f}; // along an axis
        const glm::vec3 p0 = centre, p1 = centre + d1;
        const float limit = rng.uniform(0.0f, 0.03f);
        // The second segment's bounds placed `gap` past the first's along a random axis.
        const int axis = int(rng.next() % 3);
        const float sign = (rng.next() & 1u) ? 1.0f : -1.0f;
        const float gap = limit + kSegmentBoundsSlack * rng.uniform(-3.0f, 3.0f);
        const glm::vec3 loA = glm::min(p0, p1), hiA = glm::max(p0, p1);
        glm::vec3 q0 = centre + randomPoint(rng, 0.04f), q1 = q0 + d2;
        const glm::vec3 loQ = glm::min(q0, q1), hiQ = glm::max(q0, q1);
        float shift = sign > 0.0f ? hiA[axis] + gap - loQ[axis] : loA[axis] - gap - hiQ[axis];
        q0[axis] += shift;
        q1[axis] += shift;
        const glm::vec3 loB = glm::min(q0, q1), hiB = glm::max(q0, q1);
        float s, t;
        const float distance = segmentDistance(p0, p1, q0, q1, s, t);
        if (segmentBoundsApart(loA, hiA, loB, hiB, limit)) {
            ++apart;
            ASSERT_GE(distance, limit) << "pair " << i << ": bounds apart, distance " << distance << " under the limit "
                                       << limit;
        } else {
            ++notApart;
            withinLimit += distance < limit;
        }
    }
    // Both answers are exercised, and among the pairs not apart many are within the limit.
    EXPECT_GT(apart, 20000);
    EXPECT_GT(notApart, 20000);
    EXPECT_GT(withinLimit, 100);
}

TEST(SegmentDistance, BoundsApartIsFalseForOverlappingBoundsAndNaN) {
    const glm::vec3 lo(0.0f), hi(1.0f);
    EXPECT_FALSE(segmentBoundsApart(lo, hi, lo + 0.5f, hi + 0.5f, 0.0f));
    // Apart by 0.2 in y: apart for a limit of 0.1, not for 0.2 (the slack) or 0.3.
    EXPECT_TRUE(segmentBoundsApart(lo, hi, glm::vec3(0.0f, 1.2f, 0.0f), glm::vec3(1.0f, 2.0f, 1.0f), 0.1f));
    EXPECT_FALSE(segmentBoundsApart(lo, hi, glm::vec3(0.0f, 1.2f, 0.0f), glm::vec3(1.0f, 2.0f, 1.0f), 0.2f));
    EXPECT_FALSE(segmentBoundsApart(lo, hi, glm::vec3(0.0f, 1.2f, 0.0f), glm::vec3(1.0f, 2.0f, 1.0f), 0.3f));
    const float nan = std::numeric_limits<float>::quiet_NaN();
    EXPECT_FALSE(segmentBoundsApart(glm::vec3(nan), glm::vec3(nan), lo, hi, 0.0f));
}
