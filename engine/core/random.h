// Counter-based random numbers (SplitMix64, Steele et al. 2014): the same stream on every
// machine and compiler, unlike std:: distributions, so a scene and seed always give the same
// library.
#pragma once

#include <cstdint>

namespace meadow {

inline uint64_t splitMix64(uint64_t x) {
    x += 0x9e3779b97f4a7c15ull;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
    return x ^ (x >> 31);
}

class Random {
  public:
    explicit Random(uint64_t seed) : state_(seed) {}
    uint64_t next() { return splitMix64(state_++); }
    // Uniform in [0, 1), 24 bits: exactly representable as a float.
    float uniform() { return static_cast<float>(next() >> 40) * (1.0f / 16777216.0f); }
    float uniform(float lo, float hi) { return lo + (hi - lo) * uniform(); }

  private:
    uint64_t state_;
};

} // namespace meadow
