#include "render/near_reference.h"

#include "render/field_packing.h"
#include "render/reference_motion.h"

#include "core/error.h"
#include "far_splat.h"
#include "lod_select.h"
#include "near_raster.h"

#include <glm/gtc/packing.hpp>

#include <algorithm>
#include <cmath>
#include <string>

namespace meadow {
namespace {

constexpr float kPi = 3.14159265358979f; // common.glsl's

template <typename T> const T& at(const std::vector<T>& values, size_t index, const char* what) {
    if (index >= values.size())
        throw Error(std::string("nearRasterReference: ") + what + " index " + std::to_string(index) +
                    " is outside its " + std::to_string(values.size()) + " entries");
    return values[index];
}

// near_vertices.comp's output for one vertex, as near_raster.comp reads it back.
struct Shaded {
    glm::vec2 pixel;
    float invW;
    glm::vec3 front, back, uvFacing;
};

glm::vec3 rgb9e5(glm::vec3 c) {
    const gpu::FarVec3 v = gpu::unpackRgb9e5(gpu::packRgb9e5(c.x, c.y, c.z));
    return {v.x, v.y, v.z};
}

Shaded shadeVertex(const NearRasterInputs& in, uint32_t index, const gpu::GpuDrawInstance& inst) {
    const gpu::GpuFrame& frame = in.frame;
    const gpu::GpuLodVertex& v = at(in.lodVertices, index, "LOD vertex");
    const glm::vec3 d = clumpVertexDisplacement(in.motionData, v.motion, inst, "nearRasterReference");
    const size_t base = size_t(inst.offsets.z) + size_t(v.motion.z) * (inst.offsets.w & 0xffffu);
    const glm::uvec4 w0 = at(in.vertexLight, base, "vertex light"), w1 = at(in.vertexLight, base + 1, "vertex light"),
                     w2 = at(in.vertexLight, base + 2, "vertex light");
    auto halves = [](uint32_t a, uint32_t b) { return glm::vec4(glm::unpackHalf2x16(a), glm::unpackHalf2x16(b)); };
    const glm::vec4 l0 = halves(w0.x, w0.y), l1 = halves(w0.z, w0.w), l2 = halves(w1.x, w1.y);
    const glm::vec4 l3 = halves(w1.z, w1.w), l4 = halves(w2.x, w2.y), l5 = halves(w2.z, w2.w);
    auto lit = [&](const glm::vec4& l) { return l.x + glm::dot(glm::vec3(l.y, l.z, l.w), d); };
    Shaded o;
    o.front = rgb9e5(glm::max(glm::vec3(lit(l0), lit(l1), lit(l2)), 0.0f) / kPi);
    o.back = rgb9e5(glm::max(glm::vec3(lit(l3), lit(l4), lit(l5)), 0.0f) / kPi);

    glm::vec3 p = glm::vec3(v.positionU) + d, n = glm::vec3(v.normalV);
    if (inst.positionScale.w < 0.0f) {
        const glm::vec3 m(in.mirrorNormal.x, 0.0f, in.mirrorNormal.z);
        p -= 2.0f * glm::dot(p, m) * m;
        n -= 2.0f * glm::dot(n, m) * m;
    }
    const float c = inst.pose.x, s = inst.pose.y;
    const glm::mat3 yaw(c, 0.0f, -s, 0.0f, 1.0f, 0.0f, s, 0.0f, c);
    const glm::vec3 world = glm::vec3(inst.positionScale) + yaw * (p * std::abs(inst.positionScale.w));
    const glm::vec4 clip = frame.viewProj * glm::vec4(world, 1.0f);
    if (!(clip.w > 0.0f))
        throw Error("nearRasterReference: a listed vertex lies behind the eye");
    o.invW = 1.0f / clip.w;
    o.pixel = (glm::vec2(clip) * o.invW * 0.5f + 0.5f) * glm::vec2(frame.lodScreen.z, frame.lodScreen.w);
    o.uvFacing = glm::vec3(v.positionU.w, v.normalV.w, glm::dot(yaw * n, glm::vec3(frame.cameraPosition) - world));
    return o;
}

} // namespace

std::vector<uint64_t> nearRasterReference(const NearRasterInputs& in) {
    const gpu::GpuFrame& frame = in.frame;
    if (frame.motion.z == gpu::kDebugViewLod)
        throw Error("nearRasterReference: the LOD debug view's colours are not modelled");
    const int width = int(frame.lodScreen.z), height = int(frame.lodScreen.w);
    if (width <= 0 || height <= 0)
        throw Error("nearRasterReference: the frame's size is " + std::to_string(width) + "x" + std::to_string(height));
    if (in.atlas.rgba.size() < 4)
        throw Error("nearRasterReference: the atlas is empty");
    for (size_t i = 4; i < in.atlas.rgba.size(); ++i)
        if (in.atlas.rgba[i] != in.atlas.rgba[i % 4])
            throw Error("nearRasterReference: only a uniform atlas is modelled");
    // The texel as the renderer stores it (field_packing.h: linear, half floats).
    const std::vector<uint16_t> texel = packAtlas(RgbaImage{1, 1, {in.atlas.rgba.begin(), in.atlas.rgba.begin() + 4}});
    const glm::vec4 atlasTexel(glm::unpackHalf1x16(texel[0]), glm::unpackHalf1x16(texel[1]),
                               glm::unpackHalf1x16(texel[2]), glm::unpackHalf1x16(texel[3]));
    const uint64_t empty = (uint64_t(gpu::kFarEmpty) << 32) | gpu::kFarEmpty;
    std::vector<uint64_t> visibility(size_t(width) * size_t(height), empty);
    const float nearPlane = frame.viewProj[3][2];

    for (const glm::uvec4& listed : in.nearList) {
        const uint32_t entry = listed.x;
        const gpu::GpuDrawInstance& inst = at(in.drawInstances, entry & gpu::kLodEntryIndexMask, "draw instance");
        const glm::uvec4 mesh = at(in.nearMeshes, listed.y, "near mesh");
        const gpu::GpuClump& clump = at(in.clumps, inst.offsets.w >> 16u, "clump");
        const glm::vec4 texelAt = clump.albedo.w > 0.5f ? glm::vec4(glm::vec3(clump.albedo), 1.0f) : atlasTexel;
        const bool fading = inst.pose.w > 0.0f;
        const bool isFadeLod = (entry & gpu::kLodFadeEntryBit) != 0u;
        const uint32_t ditherLevel = gpu::lodDitherLevel(inst.pose.w);
        std::vector<Shaded> shaded(mesh.y);
        for (uint32_t v = 0; v < mesh.y; ++v)
            shaded[v] = shadeVertex(in, mesh.x + v, inst);
        const glm::uvec2 part = gpu::nearPartRange(listed.w, mesh.w / 3); // the listed part's triangles
        for (uint32_t t = part.x; t < part.y; ++t) {
            const uint32_t first = mesh.z + 3 * t;
            Shaded v0 = at(shaded, at(in.indices, first, "index"), "mesh vertex");
            Shaded v1 = at(shaded, at(in.indices, first + 1, "index"), "mesh vertex");
            Shaded v2 = at(shaded, at(in.indices, first + 2, "index"), "mesh vertex");
            const gpu::NearTriangle tri =
                gpu::nearSetUp(v0.pixel, v1.pixel, v2.pixel, width, height, gpu::nearListedSub(listed.w));
            if (!tri.drawn)
                continue;
            if (tri.swapped)
                std::swap(v1, v2);
            gpu::NearEdge e0 = gpu::nearEdgeStart(tri.x1, tri.y1, tri.x2, tri.y2, tri.rowLo, tri.sub);
            gpu::NearEdge e1 = gpu::nearEdgeStart(tri.x2, tri.y2, tri.x0, tri.y0, tri.rowLo, tri.sub);
            gpu::NearEdge e2 = gpu::nearEdgeStart(tri.x0, tri.y0, tri.x1, tri.y1, tri.rowLo, tri.sub);
            const float invArea = 1.0f / float(tri.area);
            const glm::vec3 invW(v0.invW, v1.invW, v2.invW);
            const glm::vec3 depth = nearPlane * invW;
            for (int row = tri.rowLo;; ++row) {
                const int lo = gpu::nearSpanLow(e2, gpu::nearSpanLow(e1, gpu::nearSpanLow(e0, tri.colLo)));
                const int hi = gpu::nearSpanHigh(e2, gpu::nearSpanHigh(e1, gpu::nearSpanHigh(e0, tri.colHi)));
                for (int col = lo; col <= hi; ++col) {
                    const uint32_t px = uint32_t(tri.originX + col), py = uint32_t(tri.originY + row);
                    if (fading && !gpu::lodDitherKeepsLevel(isFadeLod, ditherLevel, px, py))
                        continue;
                    const glm::vec3 w =
                        glm::vec3(float(gpu::nearEdgeValue(e0, col)), float(gpu::nearEdgeValue(e1, col)),
                                  float(gpu::nearEdgeValue(e2, col))) *
                        invArea;
                    glm::vec3 pw = w * invW;
                    pw /= pw.x + pw.y + pw.z;
                    const glm::vec3 uvFacing = pw.x * v0.uvFacing + pw.y * v1.uvFacing + pw.z * v2.uvFacing;
                    if (texelAt.a < 0.5f)
                        continue;
                    const bool front = uvFacing.z >= 0.0f;
                    const glm::vec3 light = front ? pw.x * v0.front + pw.y * v1.front + pw.z * v2.front
                                                  : pw.x * v0.back + pw.y * v1.back + pw.z * v2.back;
                    const glm::vec3 radiance = glm::vec3(texelAt) * light;
                    const uint64_t word = (uint64_t(gpu::farDepthKey(glm::dot(w, depth))) << 32) |
                                          gpu::packRgb9e5(radiance.x, radiance.y, radiance.z);
                    uint64_t& slot = visibility[size_t(py) * size_t(width) + px];
                    slot = std::min(slot, word);
                }
                if (row >= tri.rowHi)
                    break;
                e0 = gpu::nearEdgeNextRow(e0);
                e1 = gpu::nearEdgeNextRow(e1);
                e2 = gpu::nearEdgeNextRow(e2);
            }
        }
    }
    return visibility;
}

} // namespace meadow
