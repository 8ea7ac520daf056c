// The tone mapper's curve, shared by tonemap.comp and far_resolve.comp (which resolves the far
// field and tone maps in one pass): linear HDR radiance times the exposure -> display-referred
// sRGB-encoded values, with the ACES fit of Narkowicz (2015). The values are written to a UNORM
// image already sRGB-encoded, so that PNG output and a UNORM swapchain both show them as they are.
#ifndef MEADOW_TONEMAP_H
#define MEADOW_TONEMAP_H

vec3 acesFilm(vec3 x) {
    return clamp((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0);
}

// The sRGB curve (IEC 61966-2-1). Above its linear toe, 1.055 c^(1/2.4) - 0.055 is fitted (minimax
// over [0.0031308, 1]) by c and its square, fourth and eighth roots, within 0.012 of one 8-bit step
// of the exact curve. lavapipe builds pow from a log2 and an exp2 polynomial; the three square roots
// take about 1 ms less of the 1280x720 resolve pass there (docs/BENCHMARKS.md, 2026-12-02).
vec3 linearToSrgb(vec3 c) {
    vec3 s1 = sqrt(c), s2 = sqrt(s1), s3 = sqrt(s2);
    vec3 curve = -0.01756284 * c + 0.64236502 * s1 + 0.71211112 * s2 - 0.33687021 * s3;
    return mix(c * 12.92, curve, greaterThan(c, vec3(0.0031308)));
}

vec4 tonemapRadiance(vec3 radiance, float exposure) {
    return vec4(linearToSrgb(acesFilm(radiance * exposure)), 1.0);
}

#endif
