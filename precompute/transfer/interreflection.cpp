// Interreflected diffuse transfer (Sloan, Kautz and Snyder 2002, section 4, "T_DI"): light that
// reached the clump after b - 1 bounces leaves each surface diffusely and is gathered by every
// vertex that sees it. Bounce b gathers only bounce b - 1:
//
//     T^b_p,side = sum over p's rays hitting the clump of  (4 pi / N) |n_p . w| * rho(h) / pi * X^(b-1)(h, side of h
//     facing p)
//
// with h the hit point, rho its albedo and X^(b-1) the previous bounce's transfer (with
// translucency) interpolated with the hit's barycentrics: the radiosity method's Gouraud
// assumption, as in the paper, which also interpolates transfer across triangles. The rays and
// their hits were recorded once (shadowed_transfer.cpp), so a bounce costs no ray.
//
// Colour. Bounce 0 is colourless; every later bounce carries the tint of what it bounced off, so
// the result is RGB. A vertex's own albedo is never folded in (transfer.h): the renderer applies
// it per fragment. Translucency is applied to every bounce before the next gathers it, so light
// that passes through a leaf and then bounces is counted as well.
//
// The ground (transfer.h) is a source of first-bounce light only: a ray of bounce 1 that hit the
// ground gathers groundAlbedo / pi times the ground's own shadowed direct transfer there.
#include "light/sh.h"
#include "transfer/bake_detail.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cassert>
#include <numbers>

namespace meadow::transfer::detail {

std::vector<double> vertexExitance(std::span<const double> transfer, std::span<const glm::vec3> albedo, int order) {
    const size_t n2 = size_t(order * order);
    const size_t vertexCount = albedo.size();
    assert(transfer.size() == vertexCount * kSideCount * kChannelCount * n2);
    std::vector<double> exitance(transfer.size());
    tbb::parallel_for(tbb::blocked_range<size_t>(0, vertexCount, 256), [&](const tbb::blocked_range<size_t>& range) {
        for (size_t v = range.begin(); v != range.end(); ++v) {
            for (uint32_t side = 0; side < kSideCount; ++side) {
                for (uint32_t c = 0; c < kChannelCount; ++c) {
                    const double scale = double(albedo[v][int(c)]) / std::numbers::pi;
                    const size_t base = ((v * kSideCount + side) * kChannelCount + c) * n2;
                    for (size_t i = 0; i < n2; ++i)
                        exitance[base + i] = scale * transfer[base + i];
                }
            }
        }
    });
    return exitance;
}

void gatherPoint(const HitRecords& records, uint32_t point, std::span<const uint32_t> indices,
                 std::span<const double> exitance, const GroundSource* ground, int order, double* out) {
    const size_t n2 = size_t(order * order);
    const size_t sideStride = kChannelCount * n2; // one side of one vertex
    const HitRecord* hits = records.hits.data() + size_t(point) * records.raysPerPoint;
    double groundDirect[sh::kMaxOrder * sh::kMaxOrder];
    for (uint32_t k = 0; k < records.counts[point]; ++k) {
        const HitRecord& hit = hits[k];
        double* receiver = out + ((hit.target & kReceiverBackSide) ? sideStride : 0);
        const uint32_t target = hit.target & kTargetMask;
        if (target == kGroundTarget) {
            if (!ground)
                continue;
            ground->directAt(hit.u, hit.v, groundDirect);
            for (uint32_t c = 0; c < kChannelCount; ++c) {
                const double scale =
                    double(hit.weight) * double(ground->settings->groundAlbedo[int(c)]) / std::numbers::pi;
                for (size_t i = 0; i < n2; ++i)
                    receiver[c * n2 + i] += scale * groundDirect[i];
            }
            continue;
        }
        // The side of the hit triangle that faced the ray: the same side at its three vertices.
        const size_t side = (hit.target & kHitBackSide) ? 1 : 0;
        const double w0 = double(hit.weight) * (1.0 - double(hit.u) - double(hit.v));
        const double w1 = double(hit.weight) * double(hit.u);
        const double w2 = double(hit.weight) * double(hit.v);
        const double* e0 = exitance.data() + (size_t(indices[3 * size_t(target)]) * kSideCount + side) * sideStride;
        const double* e1 = exitance.data() + (size_t(indices[3 * size_t(target) + 1]) * kSideCount + side) * sideStride;
        const double* e2 = exitance.data() + (size_t(indices[3 * size_t(target) + 2]) * kSideCount + side) * sideStride;
        for (size_t i = 0; i < sideStride; ++i)
            receiver[i] += w0 * e0[i] + w1 * e1[i] + w2 * e2[i];
    }
}

void applyTranslucency(std::span<const double> raw, std::span<const float> translucency, int order,
                       std::span<double> out) {
    const size_t sideStride = kChannelCount * size_t(order * order);
    assert(raw.size() == translucency.size() * kSideCount * sideStride && out.size() == raw.size());
    tbb::parallel_for(tbb::blocked_range<size_t>(0, translucency.size(), 256),
                      [&](const tbb::blocked_range<size_t>& range) {
                          for (size_t v = range.begin(); v != range.end(); ++v) {
                              const double tau = translucency[v];
                              const double* front = raw.data() + v * kSideCount * sideStride;
                              const double* back = front + sideStride;
                              double* outFront = out.data() + v * kSideCount * sideStride;
                              double* outBack = outFront + sideStride;
                              for (size_t i = 0; i < sideStride; ++i) {
                                  outFront[i] = front[i] + tau * back[i];
                                  outBack[i] = back[i] + tau * front[i];
                              }
                          }
                      });
}

std::vector<double> interreflect(const HitRecords& records, std::span<const double> direct,
                                 std::span<const uint32_t> indices, std::span<const glm::vec3> albedo,
                                 std::span<const float> translucency, const BakeSettings& settings,
                                 const GroundSource& ground) {
    const int order = settings.order;
    const size_t n2 = size_t(order * order);
    const size_t vertexCount = albedo.size();
    const size_t sideStride = kChannelCount * n2;
    assert(direct.size() == vertexCount * kSideCount * n2);

    // Bounce 0: the colourless direct term, the same in every channel.
    std::vector<double> raw(vertexCount * kSideCount * sideStride);
    for (size_t vs = 0; vs < vertexCount * kSideCount; ++vs) {
        for (uint32_t c = 0; c < kChannelCount; ++c) {
            for (size_t i = 0; i < n2; ++i)
                raw[vs * sideStride + c * n2 + i] = direct[vs * n2 + i];
        }
    }
    std::vector<double> bounce(raw.size());
    applyTranslucency(raw, translucency, order, bounce);
    std::vector<double> total = bounce;

    for (uint32_t b = 1; b <= settings.bounces; ++b) {
        const std::vector<double> exitance = vertexExitance(bounce, albedo, order);
        const GroundSource* groundSource = b == 1 ? &ground : nullptr;
        tbb::parallel_for(tbb::blocked_range<size_t>(0, vertexCount, 16), [&](const tbb::blocked_range<size_t>& range) {
            for (size_t v = range.begin(); v != range.end(); ++v) {
                double* out = raw.data() + v * kSideCount * sideStride;
                std::fill(out, out + kSideCount * sideStride, 0.0);
                gatherPoint(records, uint32_t(v), indices, exitance, groundSource, order, out);
            }
        });
        applyTranslucency(raw, translucency, order, bounce);
        for (size_t i = 0; i < total.size(); ++i)
            total[i] += bounce[i];
    }
    return total;
}

} // namespace meadow::transfer::detail
