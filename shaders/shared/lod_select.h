// The choice of level of detail (docs/ARCHITECTURE.md, Levels of detail), one function body
// compiled as C++ (tests, the CPU-driven path) and as GLSL (the cull pass), like motion_step.h.
//
// An instance's size on screen, r (its bounding sphere's projected radius, in pixels), picks a
// continuous LOD coordinate x in [0, kLodSelectCount - 1]: x = i on LOD i's plateau, and across
// the band around each switch radius x slides linearly from i to i + 1, during which the instance
// is drawn in both LODs with complementary dither masks (a crossfade), so no LOD ever pops in.
//   - Switch radii are jittered per instance (scaled by 1 + jitter (u - 1/2), u from the
//     instance's hash), so the crossfades of a field do not form a visible ring.
//   - Hysteresis: inside a band, x stays at the instance's previous x while the new one differs
//     by less than `hysteresis`, so a camera hovering at a switch distance does not make the
//     dither masks shimmer; on a plateau x is exact, so nothing stays half-faded.
// The caller keeps x per instance from frame to frame (GpuLodState).
#ifndef MEADOW_LOD_SELECT_H
#define MEADOW_LOD_SELECT_H

#ifdef __cplusplus
#include <cmath>
#include <cstdint>
namespace meadow::gpu {
using uint = std::uint32_t;
#define MEADOW_LOD_CONST inline constexpr uint
#define MEADOW_LOD_FN inline
using std::abs;
using std::floor;
using std::max;
using std::min;
inline float clamp(float x, float lo, float hi) {
    return x < lo ? lo : (x > hi ? hi : x);
}
#else
#define MEADOW_LOD_CONST const uint
#define MEADOW_LOD_FN
#endif

MEADOW_LOD_CONST kLodSelectCount = 5; // LODs 0 .. 4
MEADOW_LOD_CONST kLodFar = 5;         // the far field's LOD index (lod, fadeLod), past the meshes'

// Values in registers only (never in a buffer: the frame carries them as GpuFrame::lodSwitchRadius
// and lodBand), so only C++ and GLSL need to agree on the members.
struct GpuLodParams {
    float switchRadius[4]; // px: below switchRadius[i] LOD i + 1 replaces LOD i; descending
    float band;            // half-width of each crossfade band, relative to its radius (0 .. 0.5)
    float jitter;          // relative spread of the switch radii between instances (0 .. 0.5)
    float hysteresis;      // in LOD coordinate units (0 .. 0.5)
    // px: below farRadius the far field (surface-sample splats, far_splat.h) replaces the last
    // mesh LOD drawn, with the same jitter, band and hysteresis; 0: no far field. The mesh LODs
    // whose switch band the far field's band does not lie wholly below are never drawn: a far
    // radius above LOD 4's switch makes LOD 3 hand over to the far field directly
    // (lodMeshLevels).
    float farRadius;
};

struct GpuLodChoice {
    uint lod;     // drawn with weight 1 - fade
    uint fadeLod; // drawn with weight fade (lod + 1 while crossfading, else lod)
    float fade;   // 0 .. 1
    float x;      // the coordinate to keep for the next frame
};

// The per-instance random number u in [0, 1) that jitters the switch radii: a PCG hash of the
// instance index (Jarzynski & Olano 2020), 24 bits so the float is exact.
MEADOW_LOD_FN float lodInstanceRandom(uint instance) {
    uint state = instance * 747796405u + 2891336453u;
    uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return float(((word >> 22u) ^ word) >> 8u) * (1.0f / 16777216.0f);
}

// The visible list's entry for an instance: its index, with the top bit set when the entry
// draws the instance's fadeLod (the second draw of a crossfade).
MEADOW_LOD_CONST kLodFadeEntryBit = 0x80000000u;
// Set on an instance the far field takes that is drawn as a LOD 0 mesh instead (kFrameFarAsLod0): the
// LOD view shows it in the far field's colour.
MEADOW_LOD_CONST kLodFarMeshEntryBit = 0x40000000u;
MEADOW_LOD_CONST kLodEntryIndexMask = 0x3fffffffu;

// How many mesh LODs are drawn (LODs 0 .. m - 1): all five without a far field; with one, those
// whose switch band to the next lies wholly above the far field's band (the jitter scales both
// alike, so this is the same for every instance). The far field follows LOD m - 1.
MEADOW_LOD_FN uint lodMeshLevels(GpuLodParams p) {
    uint m = kLodSelectCount;
    if (p.farRadius > 0.0f)
        for (m = 1u; m < kLodSelectCount; ++m)
            if (!(p.farRadius * (1.0f + p.band) < p.switchRadius[m - 1u] * (1.0f - p.band)))
                break;
    return m;
}

// The continuous coordinate of a screen radius r for an instance whose random number is u in
// [0, 1). Non-increasing in r. In [0, kLodSelectCount - 1], or [0, lodMeshLevels] with a far
// field: the coordinate counts the switches crossed, so with LOD 4 skipped the far field is 4.
MEADOW_LOD_FN float lodCoordinate(GpuLodParams p, float r, float u) {
    float scale = 1.0f + p.jitter * (u - 0.5f);
    float x = 0.0f;
    uint levels = lodMeshLevels(p);
    for (uint i = 0u; i + 1u < levels; ++i) {
        float t = p.switchRadius[i] * scale;
        // 0 above the band, 1 below it, linear across it.
        x += clamp((t * (1.0f + p.band) - r) / (2.0f * p.band * t), 0.0f, 1.0f);
    }
    if (p.farRadius > 0.0f) {
        float t = p.farRadius * scale;
        x += clamp((t * (1.0f + p.band) - r) / (2.0f * p.band * t), 0.0f, 1.0f);
    }
    return x;
}

// The LOD a whole coordinate step stands for: the step past the last mesh LOD is the far field.
MEADOW_LOD_FN uint lodAtStep(uint step, uint levels) {
    return step >= levels ? kLodFar : step;
}

MEADOW_LOD_FN GpuLodChoice lodSelect(GpuLodParams p, float r, float u, float previousX) {
    float target = lodCoordinate(p, r, u);
    float x = target;
    bool plateau = target == floor(target);
    if (!plateau && abs(target - previousX) < p.hysteresis)
        x = previousX;
    GpuLodChoice c;
    uint levels = lodMeshLevels(p), step = uint(floor(x));
    c.x = x;
    c.lod = lodAtStep(step, levels);
    c.fade = x - floor(x);
    c.fadeLod = c.fade > 0.0f ? lodAtStep(step + 1u, levels) : c.lod;
    return c;
}

// A 4 x 4 ordered dither (Bayer 1973): a pixel's index, 16 distinct values 0..15 over each 4 x 4
// block, and its threshold (index + 1/2) / 16 in (0, 1). A crossfading instance draws `lod` where
// threshold >= fade and `fadeLod` where threshold < fade: the two masks are complementary, so every
// pixel is covered by exactly one of them.
MEADOW_LOD_FN uint lodDitherIndex(uint px, uint py) {
    uint x = px & 3u, y = py & 3u;
    uint xy = x ^ y;
    // Bit-interleaved Bayer index.
    return ((xy & 1u) << 3u) | ((x & 1u) << 2u) | ((xy & 2u) << 0u) | ((x & 2u) >> 1u);
}

MEADOW_LOD_FN float lodDitherThreshold(uint px, uint py) {
    return (float(lodDitherIndex(px, py)) + 0.5f) / 16.0f;
}

MEADOW_LOD_FN bool lodDitherKeeps(bool isFadeLod, float fade, uint px, uint py) {
    float t = lodDitherThreshold(px, py);
    return isFadeLod ? t < fade : t >= fade;
}

// The same test with the fade as a whole level, 0 to 16: how many of the 16 thresholds lie below
// it. lodDitherKeepsLevel(isFadeLod, lodDitherLevel(fade), px, py) equals lodDitherKeeps(isFadeLod,
// fade, px, py) for every fade, so the vertex stage can pass the level in a few bits of a flat
// integer (instance.vert: lavapipe sets up every varying slot of every triangle on one thread).
MEADOW_LOD_FN uint lodDitherLevel(float fade) {
    uint level = 0u;
    for (uint i = 0u; i < 16u; ++i)
        level += (float(i) + 0.5f) / 16.0f < fade ? 1u : 0u;
    return level;
}

MEADOW_LOD_FN bool lodDitherKeepsLevel(bool isFadeLod, uint level, uint px, uint py) {
    uint i = lodDitherIndex(px, py);
    return isFadeLod ? i < level : i >= level;
}

#ifdef __cplusplus
static_assert(sizeof(GpuLodParams) == 32, "GpuLodParams must stay 8 packed floats");
} // namespace meadow::gpu
#endif
#undef MEADOW_LOD_CONST
#undef MEADOW_LOD_FN
#endif
