#version 460
// Far field, splat pass: far instances drawn as surface samples (issue 18; far_splat.h). Each
// workgroup takes kFarInstancesPerGroup entries of the cull pass's far list at a time (indirect
// dispatch, then every gl_NumWorkGroups-th set), gl_WorkGroupSize.x / kFarInstancesPerGroup threads
// striding over `count` of each one's clump's shuffled samples, a run from the instance's own start
// (farSampleStart). Each sample moves with the last-LOD vertex it follows (x̄ + U q at that LOD's
// modes, blended across graph jumps, as instance.vert; its first two rows in one texel,
// GpuFarMotion) and takes the light of its triangle's nearest vertex to first order in that
// displacement, projects to a square of `side` pixels, and is kept (while the instance crossfades
// from LOD 4) where the dither gives the pixel to the far field. The nearest sample of a pixel
// wins by a 64-bit atomicMin of (depth key, RGB9E5 radiance), which is order independent;
// far_resolve.comp writes the winners that are nearer than the meshes' depth (far_splat.h's
// farWordShows: the same picture as testing each sample, with no depth fetch in the loop below).
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_EXT_shader_atomic_int64 : require
#include "common.glsl"
#include "lod_select.h"
#include "draw_instance.h"
#include "far_splat.h"

// The width is the device's (gpu_types.h): specialization constant 0.
layout(local_size_x = kFarGroupSize, local_size_x_id = 0) in;
// Whether the frame shows the LOD view (a debug view): as in near_raster.comp.
layout(constant_id = 1) const bool kLodView = false;

MEADOW_FRAME_BLOCK(0, 0)
layout(set = 0, binding = 1, std430) readonly buffer FarList { uvec2 farList[]; };
layout(set = 0, binding = 2, std430) readonly buffer FarDispatch { GpuFarDispatch farDispatch; };
layout(set = 0, binding = 3, std430) readonly buffer DrawInstances { GpuDrawInstance drawInstances[]; };
layout(set = 0, binding = 4, std430) readonly buffer Clumps { GpuClump clumps[]; };
// What each sample reads is fetched from texel buffers, the same bytes as the storage buffers the
// meshes read: llvmpipe loads a storage buffer lane by lane, each component behind its own branch,
// and a texel buffer with one gather per texel (docs/BENCHMARKS.md).
layout(set = 0, binding = 5) uniform usamplerBuffer farSamples; // GpuFarSample: 2 texels each
layout(set = 0, binding = 6) uniform samplerBuffer motionData;
layout(set = 0, binding = 7) uniform usamplerBuffer vertexLight;
layout(set = 0, binding = 8, std430) buffer Visibility { uint64_t visibility[]; };
// For each instance's bounding sphere (the cull pass's): the coin's bound below.
layout(set = 0, binding = 9, std430) readonly buffer Instances { GpuInstance instances[]; };
layout(set = 0, binding = 10) uniform usamplerBuffer farMotion; // GpuFarMotion per GpuLodVertex
// As instance.vert: the mirror plane's normal (xz).
layout(push_constant) uniform FarParams { vec4 mirrorNormal; };

// A sample's displacement from its mean pose, d = sum over the modes k its last-LOD vertex plays in
// the far field (at most kFarMotionModes, its block's strongest) of U_k q_k (clump_motion.glsl's
// sum), from that vertex's far motion texel (GpuFarMotion): its rows as half floats, zero past its
// rank, so that a sample reads no row of its own and runs no loop over its modes (llvmpipe would
// run such a loop's body for every SIMD row, whether or not a lane enters it: docs/BENCHMARKS.md,
// "The splat pass's loops"). The coordinates are the far field's copy of the last LOD's
// (GpuClump::motion.x), a frame's in one or two cache lines: `frames` holds where the instance's two
// frames start there.
vec3 farSampleDisplacement(uvec4 motion, uvec2 frames, GpuDrawInstance inst) {
    uint rank = motion.w >> kFarMotionRankShift;
    vec3 d = vec3(0.0);
    if (rank > 0u) {
        uint coordinate = motion.w & kFarMotionOffsetMask, second = rank > 1u ? 1u : 0u;
        uint q0 = frames.x + coordinate, q1 = frames.y + coordinate;
        float qa = texelFetch(motionData, int(q0)).r, qb = texelFetch(motionData, int(q0 + second)).r;
        if (inst.pose.z > 0.0) {
            qa = mix(qa, texelFetch(motionData, int(q1)).r, inst.pose.z);
            qb = mix(qb, texelFetch(motionData, int(q1 + second)).r, inst.pose.z);
        }
        vec2 a = unpackHalf2x16(motion.x), b = unpackHalf2x16(motion.y), c = unpackHalf2x16(motion.z);
        d = vec3(a, b.x) * qa + vec3(b.y, c) * qb;
    }
    return d;
}

// far_samples.h's octahedral normal.
vec3 unpackOctahedralNormal(uint packed) {
    vec2 p = unpackSnorm2x16(packed);
    vec3 n = vec3(p.x, p.y, 1.0 - abs(p.x) - abs(p.y));
    if (n.z < 0.0)
        n.xy = (1.0 - abs(n.yx)) * vec2(n.x >= 0.0 ? 1.0 : -1.0, n.y >= 0.0 ? 1.0 : -1.0);
    return normalize(n);
}

void main() {
    uint total = farDispatch.count;
    ivec2 size = ivec2(frame.lodScreen.zw);
    const uint lanes = gl_WorkGroupSize.x / kFarInstancesPerGroup;
    uint lane = gl_LocalInvocationID.x % lanes, set = gl_LocalInvocationID.x / lanes;
    // The loop over sets of instances tests at its end (as the square's loops below): a workgroup has
    // a set (the cull pass adds one workgroup per kFarInstancesPerGroup listed instances), though the
    // last set may be short: its threads past the list draw no sample.
    uint item = gl_WorkGroupID.x * kFarInstancesPerGroup + set;
    do {
        uvec2 listed = farList[min(item, total - 1u)];
        uint entry = listed.x;
        uint count = item < total ? listed.y : 0u;
        uint instance = entry & kLodEntryIndexMask;
        GpuDrawInstance inst = drawInstances[instance];
        bool isFadeLod = (entry & kLodFadeEntryBit) != 0u;
        float fade = inst.pose.w;
        GpuClump clump = clumps[inst.offsets.w >> 16u];
        bool mirrored = inst.positionScale.w < 0.0;
        vec3 m = vec3(mirrorNormal.x, 0.0, mirrorNormal.z);
        float c = inst.pose.x, s = inst.pose.y;
        mat3 yaw = mat3(c, 0.0, -s, 0.0, 1.0, 0.0, s, 0.0, c);
        float scale = abs(inst.positionScale.w);
        // Each drawn sample stands for an equal share of the surface (stochastic pruning).
        float area = uintBitsToFloat(clump.far.z) * scale * scale;
        float areaPerSample = area / float(count);
        // The eye's elevation above the base and, in clump space (yaw undone, then the mirror), its
        // azimuth: for the coverage gain and the samples' visibility bits (far_splat.h).
        vec3 toEye = frame.cameraPosition.xyz - inst.positionScale.xyz;
        float elevation = farEyeElevation(toEye.x, toEye.y, toEye.z);
        float baseW = max((frame.viewProj * vec4(inst.positionScale.xyz, 1.0)).w, 1e-3);
        float gain = farCoverageGain(
            clump, farInstanceSize(area, farPixelsPerMetre(frame.lodScreen.x, baseW, length(toEye))), elevation);
        vec3 eye = toEye * yaw;
        if (mirrored)
            eye -= 2.0 * dot(eye, m) * m;
        float azimuth = farEyeAzimuth(eye.x, eye.z);
        uint start = farSampleStart(instance, clump.far.y);
        // Where the instance's two frames (draw_instance.h: offsets.x and .y) start in the far
        // field's coordinates (GpuClump::motion.x, graphSizes.w per frame).
        uvec2 farFrames =
            clump.motion.x + (inst.offsets.xy - clump.motion.y) / max(clump.motion.z, 1u) * clump.graphSizes.w;
        uint next = lane;
        // A bound on every sample's coverage coin (below): its footprint at the nearest depth and
        // the farthest distance its instance reaches, facing the eye. clip.w is at least the depth
        // of the bounding sphere's centre less its radius, taken twice over (the sphere holds the
        // simulated motion, the modes replay it to within their error), and the distance to the
        // eye at most the centre's plus as much; then a sample's footprint (farSampleFootprint and
        // farPixelsPerMetre, |cosine| at most 1) is at most coinBound, and one whose random number
        // is at least coinBound loses the coin below. Such samples are passed over in the search,
        // before their motion and light are computed (docs/BENCHMARKS.md, "The coverage coin tossed
        // in the search"). The same samples win as without it; without a bound (the sphere reaching
        // the eye's plane) none is passed over.
        float radius = instances[instance].boundingRadius * scale;
        vec3 wRow = vec3(frame.viewProj[0][3], frame.viewProj[1][3], frame.viewProj[2][3]);
        vec3 centre = inst.positionScale.xyz + vec3(0.0, 0.5 * radius, 0.0);
        float wMin = dot(wRow, centre) + frame.viewProj[3][3] - 2.0 * radius * length(wRow);
        float coinBound = 2.0;
        if (wMin > 0.0) {
            float dMax = length(frame.cameraPosition.xyz - centre) + 2.0 * radius;
            float pixelsPerMetre = farPixelsPerMetre(frame.lodScreen.x, wMin, dMax);
            coinBound = areaPerSample * (pixelsPerMetre * pixelsPerMetre) * gain * 1.001;
        }
        for (;;) {
            // The next of this thread's samples that its own clump does not hide from here, found in
            // a loop of its own: a SIMD row (lavapipe's, or a GPU's warp) runs the rest of the body
            // once for every sample some lane draws, and about 60 % are hidden, so testing them in
            // the body would run it for nearly every sample (docs/BENCHMARKS.md).
            GpuFarSample farSample;
            float coin = 1.0; // the found sample's random number, for its coin below
            for (; next < count; next += lanes) {
                coin = farSampleRandom(instance, next);
                if (coin >= coinBound)
                    continue;
                farSample.position =
                    texelFetch(farSamples, int(2u * (clump.far.x + farSampleSlot(start, next, clump.far.y))));
                uint bit = farVisibilityBitAt(azimuth, elevation, farSampleRandom(instance, next + kFarAzimuthStream),
                                              farSampleRandom(instance, next + kFarElevationStream));
                if ((farSample.position.w >> bit & 1u) != 0u)
                    break;
            }
            if (next >= count)
                break;
            uint k = next;
            next += lanes;
            uint slot = clump.far.x + farSampleSlot(start, k, clump.far.y);
            farSample.data = texelFetch(farSamples, int(2u * slot + 1u));
            vec3 d = farSampleDisplacement(texelFetch(farMotion, int(farSample.data.w)), farFrames, inst);
            vec3 p = uintBitsToFloat(farSample.position.xyz) + d, n = unpackOctahedralNormal(farSample.data.x);
            if (mirrored) {
                p -= 2.0 * dot(p, m) * m;
                n -= 2.0 * dot(n, m) * m;
            }
            vec3 world = inst.positionScale.xyz + yaw * (p * scale);
            vec4 clip = frame.viewProj * vec4(world, 1.0);
            if (clip.w <= 0.0)
                continue;
            vec3 ndc = clip.xyz / clip.w;
            if (ndc.z <= 0.0 || ndc.z > 1.0)
                continue;
            // Stochastic coverage: below a pixel of footprint, the sample covers its pixel with
            // that probability; above, a square of about its footprint.
            vec3 toEye = frame.cameraPosition.xyz - world;
            float eyeDistance = length(toEye);
            float cosine = dot(yaw * n, toEye) / max(eyeDistance, 1e-6);
            if (cosine < 0.0 && clump.far.w != 0u)
                continue; // the far side of a closed surface: hidden by its near side
            float footprint =
                farSampleFootprint(areaPerSample, farPixelsPerMetre(frame.lodScreen.x, clip.w, eyeDistance), cosine) *
                gain;
            if (footprint < 1.0 && coin >= footprint)
                continue;
            uint side = farSplatSide(footprint);
            vec2 pixel = (ndc.xy * 0.5 + 0.5) * vec2(size);
            ivec2 corner = ivec2(farSplatCorner(pixel.x, side), farSplatCorner(pixel.y, side));
            if (corner.x >= size.x || corner.y >= size.y || corner.x + int(side) <= 0 || corner.y + int(side) <= 0)
                continue;

            // The side of the sheet the camera sees, lit as instance.vert lights its vertex.
            bool front = cosine >= 0.0;
            uint base = inst.offsets.z + farSample.data.z * (inst.offsets.w & 0xffffu);
            // (E, gradient) per channel: the front side's in the first 1.5 texels, the back side's in
            // the last 1.5; the texel not needed is not fetched.
            uvec4 middle = texelFetch(vertexLight, int(base + 1u));
            uvec4 outer = texelFetch(vertexLight, int(base + (front ? 0u : 2u)));
            vec4 r = front ? vec4(unpackHalf2x16(outer.x), unpackHalf2x16(outer.y))
                           : vec4(unpackHalf2x16(middle.z), unpackHalf2x16(middle.w));
            vec4 g = front ? vec4(unpackHalf2x16(outer.z), unpackHalf2x16(outer.w))
                           : vec4(unpackHalf2x16(outer.x), unpackHalf2x16(outer.y));
            vec4 b = front ? vec4(unpackHalf2x16(middle.x), unpackHalf2x16(middle.y))
                           : vec4(unpackHalf2x16(outer.z), unpackHalf2x16(outer.w));
            vec3 irradiance = vec3(r.x + dot(r.yzw, d), g.x + dot(g.yzw, d), b.x + dot(b.yzw, d));
            vec3 albedo = unpackRgb9e5(farSample.data.y);
            vec3 radiance = albedo * max(irradiance, 0.0) / kPi;
            if (kLodView)
                radiance = kLodViewColors[kLodFar] * (front ? 1.0 : 0.6) / max(frame.skyZenith.w, 1e-6);
            uint64_t word = packUint2x32(uvec2(packRgb9e5(radiance.r, radiance.g, radiance.b), farDepthKey(ndc.z)));

            // The square's rows and columns in loops tested at their end (a side is at least 1):
            // llvmpipe runs a loop's whole body in each pass, whatever its lanes decide, so loops
            // tested at their start ran the atomic's pass once more, for no lane, after each row
            // and again after the square (docs/BENCHMARKS.md, "The splat pass's loops"). The same
            // pixels, the same words.
            uint j = 0u;
            do {
                uint i = 0u;
                do {
                    ivec2 at = corner + ivec2(i, j);
                    if (at.x >= 0 && at.y >= 0 && at.x < size.x && at.y < size.y &&
                        (fade <= 0.0 || lodDitherKeeps(isFadeLod, fade, uint(at.x), uint(at.y))))
                        atomicMin(visibility[uint(at.y) * uint(size.x) + uint(at.x)], word);
                } while (++i < side);
            } while (++j < side);
        }
    } while ((item += gl_NumWorkGroups.x * kFarInstancesPerGroup) < total);
}
