// The tone mapper's curve, shared by tonemap.comp and far_resolve.comp (which resolves the far
// field and tone maps in one pass): linear HDR radiance times the exposure -> display-referred
// sRGB-encoded values, with the ACES fit of Narkowicz (2015). The values are written to a UNORM
// image already sRGB-encoded, so that PNG output and a UNORM swapchain both show them as they are.
#ifndef MEADOW_TONEMAP_H
#define MEADOW_TONEMAP_H

vec3 acesFilm(vec3 x) {
    return clamp((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0);
}

vec3 linearToSrgb(vec3 c) {
    return mix(c * 12.92, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, greaterThan(c, vec3(0.0031308)));
}

vec4 tonemapRadiance(vec3 radiance, float exposure) {
    return vec4(linearToSrgb(acesFilm(radiance * exposure)), 1.0);
}

#endif
