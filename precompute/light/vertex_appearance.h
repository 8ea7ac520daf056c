// A vertex's light transfer to first order in its own displacement (docs/ARCHITECTURE.md, Light
// transfer):
//
//     T_v(f) ≈ T̄_v + G_v d_v(f)
//
// with d_v(f) the vertex's displacement from its mean position at motion frame f (the x̄ + U q
// reconstruction the renderer computes anyway), fitted by least squares over the baked frames.
//
// Why not James and Fatahalian's low-rank basis with per-frame coordinates interpolated between
// baked frames: measured on the simulated iris clumps (docs/BENCHMARKS.md), 20 s of turbulent
// motion per wind level sampled every second gives held-out errors no better than the mean
// transfer alone, because the transfer changes faster than any affordable sampling in time. The
// displacement of the vertex itself, known at every frame, predicts its transfer better (the
// blade turning towards or away from the sky, moving into or out of its neighbours' shade), costs
// three values per transfer coefficient, and needs no per-instance appearance coordinates: after
// the light pass projects T̄ and G onto the sky, a vertex's irradiance is one dot product with d.
#pragma once

#include "library/clump.h"

#include <Eigen/Core>
#include <glm/glm.hpp>

#include <cstdint>
#include <span>
#include <vector>

namespace meadow {

// baked: (vertexCount x valuesPerVertex) x S, column s the transfer at baked frame s, vertex-major;
// displacements[s][v]: vertex v's displacement at baked frame s. The gradient is regularised
// (ridge) so that displacements varying by less than `ridgeMetres` carry no information: a vertex
// that hardly moves gets its mean and a gradient near zero instead of a fit to noise. Throws
// meadow::Error on inconsistent sizes, fewer than 2 frames or non-finite input. Deterministic.
VertexAppearance fitVertexAppearance(const Eigen::MatrixXf& baked, uint32_t valuesPerVertex,
                                     const std::vector<std::vector<glm::vec3>>& displacements, float ridgeMetres);

// T̄ + G d for every vertex, vertex-major, as `baked`'s columns.
Eigen::VectorXf evaluateVertexAppearance(const VertexAppearance& model, std::span<const glm::vec3> displacement);

} // namespace meadow
