#include "library/sky_day.h"

#include <cassert>
#include <cmath>

namespace meadow::sky {

SkyBlend skyBlendAt(const SkyDay& day, double hours) {
    assert(!day.frames.empty() && std::isfinite(hours));
    const uint32_t count = uint32_t(day.frames.size());
    double t = std::fmod(hours, 24.0);
    if (t < 0.0)
        t += 24.0;
    const double position = t * double(count) / 24.0; // in frames
    double whole = std::floor(position);
    double weight = position - whole;
    // Snap to a frame within 1e-9 h, so a frame's own time returns it exactly.
    const double tolerance = 1e-9 * double(count) / 24.0;
    if (weight < tolerance) {
        weight = 0.0;
    } else if (1.0 - weight < tolerance) {
        whole += 1.0;
        weight = 0.0;
    }
    SkyBlend blend;
    blend.first = uint32_t(whole) % count;
    blend.second = (blend.first + 1) % count;
    blend.weight = weight;
    return blend;
}

std::vector<float> blendSh(const SkyDay& day, const SkyBlend& blend) {
    const std::vector<float>& a = day.frames[blend.first].sh;
    const std::vector<float>& b = day.frames[blend.second].sh;
    assert(a.size() == b.size());
    std::vector<float> out(a.size());
    for (size_t i = 0; i < a.size(); ++i)
        out[i] = float((1.0 - blend.weight) * double(a[i]) + blend.weight * double(b[i]));
    return out;
}

std::vector<float> shAt(const SkyDay& day, double hours) {
    return blendSh(day, skyBlendAt(day, hours));
}

} // namespace meadow::sky
