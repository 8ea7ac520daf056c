// The distance between two segments, and a cheap test that they lie farther apart than a limit:
// the rod system's contacts (rod_system.cpp).
#pragma once

#include <algorithm>
#include <glm/glm.hpp>

namespace meadow {

// Closest points of segments [p0, p1] and [q0, q1] (Ericson, Real-Time Collision Detection 5.1.9).
inline float segmentDistance(glm::vec3 p0, glm::vec3 p1, glm::vec3 q0, glm::vec3 q1, float& s, float& t) {
    glm::vec3 d1 = p1 - p0, d2 = q1 - q0, r = p0 - q0;
    float a = glm::dot(d1, d1), e = glm::dot(d2, d2), f = glm::dot(d2, r);
    const float eps = 1e-12f;
    if (a <= eps && e <= eps) {
        s = t = 0.0f;
    } else if (a <= eps) {
        s = 0.0f;
        t = std::clamp(f / e, 0.0f, 1.0f);
    } else {
        float c = glm::dot(d1, r);
        if (e <= eps) {
            t = 0.0f;
            s = std::clamp(-c / a, 0.0f, 1.0f);
        } else {
            float b = glm::dot(d1, d2), denom = a * e - b * b;
            s = denom > eps ? std::clamp((b * f - c * e) / denom, 0.0f, 1.0f) : 0.0f;
            t = (b * s + f) / e;
            if (t < 0.0f) {
                t = 0.0f;
                s = std::clamp(-c / a, 0.0f, 1.0f);
            } else if (t > 1.0f) {
                t = 1.0f;
                s = std::clamp((b - c) / a, 0.0f, 1.0f);
            }
        }
    }
    return glm::length((p0 + d1 * s) - (q0 + d2 * t));
}

// Whether segments with bounds [loA, hiA] and [loB, hiB] (their end points' component-wise minimum
// and maximum) certainly lie farther apart than `limit`, so that segmentDistance of any two
// segments within those bounds is at least `limit`: the bounds are separated along some axis by
// more than `limit` plus kSegmentBoundsSlack. No two points of the segments are nearer than that
// gap, and the slack (0.1 mm) is far more than the rounding of segmentDistance for coordinates of
// a few metres (a few ulps, under 1 um), so a caller that passes over such pairs finds the same
// pairs within the limit as one that measures every distance. False where a bound is NaN.
inline constexpr float kSegmentBoundsSlack = 1e-4f;
inline bool segmentBoundsApart(glm::vec3 loA, glm::vec3 hiA, glm::vec3 loB, glm::vec3 hiB, float limit) {
    const glm::vec3 gap = glm::max(loA - hiB, loB - hiA);
    return std::max(gap.x, std::max(gap.y, gap.z)) > limit + kSegmentBoundsSlack;
}

} // namespace meadow
