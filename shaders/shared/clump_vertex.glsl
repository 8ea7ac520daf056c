// A clump vertex as the instances draw it, shared by instance.vert (the draw pass) and
// near_vertices.comp (the near raster). Needs common.glsl (kPi), the frame block, draw_instance.h
// (GpuDrawInstance), clump_motion.glsl (with the motion's texel views), and two texel views
// declared before it is included: `lodVertices` (GpuLodVertex, 3 RGBA32UI texels each) and
// `vertexLight` (RGBA32UI).

// Its irradiance / pi on both sides, to first order in its displacement d, from its light variant's
// three texels: (E, gradient) per side and channel as half floats (light.comp).
void clumpVertexLight(uvec4 w0, uvec4 w1, uvec4 w2, vec3 d, out vec3 front, out vec3 back) {
    vec4 l0 = vec4(unpackHalf2x16(w0.x), unpackHalf2x16(w0.y)), l1 = vec4(unpackHalf2x16(w0.z), unpackHalf2x16(w0.w));
    vec4 l2 = vec4(unpackHalf2x16(w1.x), unpackHalf2x16(w1.y)), l3 = vec4(unpackHalf2x16(w1.z), unpackHalf2x16(w1.w));
    vec4 l4 = vec4(unpackHalf2x16(w2.x), unpackHalf2x16(w2.y)), l5 = vec4(unpackHalf2x16(w2.z), unpackHalf2x16(w2.w));
    front = max(vec3(l0.x + dot(l0.yzw, d), l1.x + dot(l1.yzw, d), l2.x + dot(l2.yzw, d)), 0.0) / kPi;
    back = max(vec3(l3.x + dot(l3.yzw, d), l4.x + dot(l4.yzw, d), l5.x + dot(l5.yzw, d)), 0.0) / kPi;
}

// Its world position for the instance: p (x̄ + d, clump space) and its normal n reflected about the
// vertical mirror plane (xz: `mirror`) for a mirrored instance, then yawed, scaled and moved to the
// instance's base; n comes back in world space (yawed, not normalised).
vec3 clumpVertexWorld(GpuDrawInstance inst, vec3 p, inout vec3 n, vec2 mirror) {
    if (inst.positionScale.w < 0.0) {
        vec3 m = vec3(mirror.x, 0.0, mirror.y);
        p -= 2.0 * dot(p, m) * m;
        n -= 2.0 * dot(n, m) * m;
    }
    float c = inst.pose.x, s = inst.pose.y;
    mat3 yaw = mat3(c, 0.0, -s, 0.0, 1.0, 0.0, s, 0.0, c);
    n = yaw * n;
    return inst.positionScale.xyz + yaw * (p * abs(inst.positionScale.w));
}

// One LOD vertex moved and lit for an instance: its clip position, the light of both sides / pi,
// uv and the facing term n . (eye - x), and the LOD it belongs to (the LOD view's colour). `mirror`
// is the xz normal of the mirror plane (clumpVertexWorld).
struct ClumpVertex {
    vec4 clip;
    vec3 front;
    vec3 back;
    vec3 uvFacing;
    uint lod;
};

ClumpVertex shadeClumpVertex(uint index, GpuDrawInstance inst, vec2 mirror) {
    ClumpVertex o;
    vec4 positionU = uintBitsToFloat(texelFetch(lodVertices, int(3u * index)));
    vec4 normalV = uintBitsToFloat(texelFetch(lodVertices, int(3u * index + 1u)));
    uvec4 motion = texelFetch(lodVertices, int(3u * index + 2u));
    // x̄ + U q, q blended across a graph jump (motion_step.h): the old path's weight fades from 1.
    vec3 d = clumpVertexDisplacement(motion, inst);
    // Irradiance of both sides to first order in d, for this instance's light variant (its yaw bin,
    // mirrored or not: light.comp), from half floats: (E, gradient) per side and channel.
    uint base = inst.offsets.z + motion.z * (inst.offsets.w & 0xffffu);
    clumpVertexLight(texelFetch(vertexLight, int(base)), texelFetch(vertexLight, int(base + 1u)),
                     texelFetch(vertexLight, int(base + 2u)), d, o.front, o.back);
    vec3 n = normalV.xyz;
    vec3 world = clumpVertexWorld(inst, positionU.xyz + d, n, mirror);
    o.clip = frame.viewProj * vec4(world, 1.0);
    o.uvFacing = vec3(positionU.w, normalV.w, dot(n, frame.cameraPosition.xyz - world));
    o.lod = motion.w >> 16u;
    return o;
}
