// Motion reduction by principal component analysis (docs/ARCHITECTURE.md, Motion):
// x(t) = mean + U q(t), as James & Fatahalian 2003 and Cove & James 2004 store their precomputed
// deformations.
#pragma once

#include <Eigen/Core>

#include <cstdint>
#include <vector>

namespace meadow {

struct PcaResult {
    Eigen::VectorXf mean;                     // n: the mean frame
    Eigen::MatrixXf basis;                    // n x r, orthonormal columns, canonical sign (largest-|.| entry positive)
    Eigen::MatrixXf coords;                   // r x F: reduced coordinates q of each frame, U^T (x - mean)
    std::vector<double> singularValues;       // all min(n, F) singular values of the centred data, descending
    std::vector<double> relativeErrorPerRank; // [k] = ||Xc - U_k U_k^T Xc||_F / ||Xc||_F, k = 0..r
};

// samples: n x F, column f is frame f's stacked vertex displacements (or positions). The rank r
// is min(maxRank, the numerical rank): directions whose singular value is below 1e-6 of the
// largest are noise of the eigen-solver, not motion, and are never returned.
//
// Method: the eigen-decomposition of the smaller Gram matrix in double precision (F x F when
// F <= n, the usual case of many vertices and a few thousand frames; n x n otherwise), instead of
// an SVD of the n x F matrix, which costs O(n F^2) either way but needs a copy of the whole data.
// Basis vectors from the F x F route are re-orthonormalised (Householder QR) so U^T U = I to
// rounding. relativeErrorPerRank is measured from the projections, ||Xc||^2 - sum of ||q_i||^2,
// not derived from the singular values, so the Eckart–Young identity is a real check.
// Deterministic for any TBB thread count. Throws meadow::Error on empty or non-finite input.
PcaResult computePca(const Eigen::MatrixXf& samples, uint32_t maxRank);

// The smallest rank k <= r with relativeErrorPerRank[k] <= maxRelativeError (r if none is).
uint32_t rankForRelativeError(const PcaResult& pca, double maxRelativeError);

} // namespace meadow
