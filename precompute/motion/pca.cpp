#include "motion/pca.h"

#include "core/error.h"
#include "core/random.h"

#include <Eigen/Eigenvalues>
#include <Eigen/QR>

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace meadow {
namespace {

// Fixed block sizes: each block's arithmetic is the same whichever thread runs it, which is what
// makes the result independent of the thread count (Eigen itself runs single-threaded here).
constexpr Eigen::Index kRowChunk = 512;
constexpr Eigen::Index kColumnBlock = 64;

Eigen::MatrixXd centredRows(const Eigen::MatrixXf& samples, const Eigen::VectorXd& mean, Eigen::Index row,
                            Eigen::Index rows) {
    return samples.middleRows(row, rows).cast<double>().colwise() - mean.segment(row, rows);
}

// G = Xc^T Xc (F x F), accumulated over row chunks in order; the column blocks of each chunk's
// product run in parallel.
Eigen::MatrixXd gramOfFrames(const Eigen::MatrixXf& samples, const Eigen::VectorXd& mean) {
    const Eigen::Index n = samples.rows(), frames = samples.cols();
    Eigen::MatrixXd gram = Eigen::MatrixXd::Zero(frames, frames);
    const Eigen::Index blocks = (frames + kColumnBlock - 1) / kColumnBlock;
    for (Eigen::Index row = 0; row < n; row += kRowChunk) {
        const Eigen::MatrixXd chunk = centredRows(samples, mean, row, std::min(kRowChunk, n - row));
        tbb::parallel_for(Eigen::Index(0), blocks, [&](Eigen::Index block) {
            const Eigen::Index col = block * kColumnBlock, cols = std::min(kColumnBlock, frames - col);
            // Upper triangle and diagonal blocks only; mirrored below.
            const Eigen::Index top = col + cols;
            gram.block(0, col, top, cols).noalias() += chunk.leftCols(top).transpose() * chunk.middleCols(col, cols);
        });
    }
    gram.triangularView<Eigen::StrictlyLower>() = gram.transpose();
    return gram;
}

// C = Xc Xc^T (n x n) for the rare case of fewer coordinates than frames.
Eigen::MatrixXd covarianceOfCoordinates(const Eigen::MatrixXf& samples, const Eigen::VectorXd& mean) {
    const Eigen::MatrixXd centred = samples.cast<double>().colwise() - mean;
    return centred * centred.transpose();
}

// Rows of a * b in fixed row chunks, in parallel: the same bits for any thread count.
Eigen::MatrixXd multiplyByRowChunks(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
    Eigen::MatrixXd result(a.rows(), b.cols());
    const Eigen::Index chunks = (a.rows() + kColumnBlock * 4 - 1) / (kColumnBlock * 4);
    tbb::parallel_for(Eigen::Index(0), chunks, [&](Eigen::Index chunk) {
        const Eigen::Index row = chunk * kColumnBlock * 4, rows = std::min(kColumnBlock * 4, a.rows() - row);
        result.middleRows(row, rows).noalias() = a.middleRows(row, rows) * b;
    });
    return result;
}

Eigen::MatrixXd orthonormalColumns(const Eigen::MatrixXd& y) {
    const Eigen::HouseholderQR<Eigen::MatrixXd> qr(y);
    return qr.householderQ() * Eigen::MatrixXd::Identity(y.rows(), y.cols());
}

// Below this size the full eigen-solver is quick; above it, computing all eigenvectors is the
// whole cost of the PCA (27 s at F = 2,500 on one core), while only r <= ~40 are needed.
constexpr Eigen::Index kFullSolverLimit = 512;

// Eigenvalues (all, descending) and the leading `count` eigenvectors of a symmetric positive
// semi-definite g. Large matrices: eigenvalues alone by tridiagonalisation (Eigen), leading
// eigenvectors by block subspace iteration with Rayleigh–Ritz (Golub & Van Loan, 8.2.4), run
// until every wanted Ritz pair's residual is below 1e-10 of the largest eigenvalue.
void leadingEigenpairs(const Eigen::MatrixXd& g, Eigen::Index count, Eigen::VectorXd& values,
                       Eigen::MatrixXd& vectors) {
    const Eigen::Index m = g.rows();
    if (m <= kFullSolverLimit) {
        const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(g);
        if (eigen.info() != Eigen::Success)
            throw Error("PCA: the eigen-decomposition did not converge");
        values = eigen.eigenvalues().reverse();
        vectors = eigen.eigenvectors().rowwise().reverse().leftCols(count);
        return;
    }
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> spectrum(g, Eigen::EigenvaluesOnly);
    if (spectrum.info() != Eigen::Success)
        throw Error("PCA: the eigenvalue computation did not converge");
    values = spectrum.eigenvalues().reverse();
    if (count == 0) {
        vectors.resize(m, 0);
        return;
    }
    // A wider block than wanted speeds convergence to the ratio lambda_(block+1) / lambda_count.
    const Eigen::Index block = std::min(m, count + std::max<Eigen::Index>(10, count / 2));
    Random random(0x6d656164u); // fixed start: deterministic
    Eigen::MatrixXd q(m, block);
    for (Eigen::Index i = 0; i < q.size(); ++i)
        q.data()[i] = double(random.uniform(-1.0f, 1.0f));
    q = orthonormalColumns(q);
    const double tolerance = 1e-10 * std::max(values(0), std::numeric_limits<double>::min());
    for (int iteration = 1;; ++iteration) {
        const Eigen::MatrixXd gq = multiplyByRowChunks(g, q);
        if (iteration % 4 == 0 || iteration == 400) {
            const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> ritz(q.transpose() * gq);
            const Eigen::MatrixXd w = ritz.eigenvectors().rowwise().reverse().leftCols(count);
            const Eigen::VectorXd theta = ritz.eigenvalues().reverse().head(count);
            const Eigen::MatrixXd residual = gq * w - (q * w) * theta.asDiagonal();
            if (residual.colwise().norm().maxCoeff() <= tolerance || iteration == 400) {
                vectors = q * w;
                return;
            }
        }
        q = orthonormalColumns(gq);
    }
}

} // namespace

PcaResult computePca(const Eigen::MatrixXf& samples, uint32_t maxRank) {
    const Eigen::Index n = samples.rows(), frames = samples.cols();
    if (n == 0 || frames == 0)
        throw Error("PCA: the sample matrix is empty (" + std::to_string(n) + " x " + std::to_string(frames) + ")");
    if (!samples.allFinite())
        throw Error("PCA: the samples hold NaN or infinite values");

    Eigen::VectorXd mean = Eigen::VectorXd::Zero(n);
    for (Eigen::Index f = 0; f < frames; ++f)
        mean += samples.col(f).cast<double>();
    mean /= double(frames);

    const bool byFrames = frames <= n;
    const Eigen::MatrixXd gram = byFrames ? gramOfFrames(samples, mean) : covarianceOfCoordinates(samples, mean);
    const Eigen::Index m = gram.rows();
    Eigen::VectorXd eigenvalues;
    Eigen::MatrixXd eigenvectors;
    leadingEigenpairs(gram, std::min<Eigen::Index>(m, maxRank), eigenvalues, eigenvectors);

    PcaResult result;
    result.singularValues.resize(size_t(m));
    for (Eigen::Index i = 0; i < m; ++i)
        result.singularValues[size_t(i)] = std::sqrt(std::max(0.0, eigenvalues(i)));
    const double largest = result.singularValues[0];
    Eigen::Index rank = 0;
    while (rank < std::min<Eigen::Index>(m, maxRank) && largest > 0.0 &&
           result.singularValues[size_t(rank)] > 1e-6 * largest)
        ++rank;

    Eigen::MatrixXd basis(n, rank);
    if (byFrames && rank > 0) {
        // U = Xc V Sigma^-1, then QR to remove the eigen-solver's loss of orthogonality for the
        // smaller singular values.
        Eigen::MatrixXd projector(frames, rank);
        for (Eigen::Index i = 0; i < rank; ++i)
            projector.col(i) = eigenvectors.col(i) / result.singularValues[size_t(i)];
        const Eigen::Index chunks = (n + kRowChunk - 1) / kRowChunk;
        tbb::parallel_for(Eigen::Index(0), chunks, [&](Eigen::Index chunk) {
            const Eigen::Index row = chunk * kRowChunk, rows = std::min(kRowChunk, n - row);
            basis.middleRows(row, rows).noalias() = centredRows(samples, mean, row, rows) * projector;
        });
        const Eigen::HouseholderQR<Eigen::MatrixXd> qr(basis);
        Eigen::MatrixXd q = qr.householderQ() * Eigen::MatrixXd::Identity(n, rank);
        for (Eigen::Index i = 0; i < rank; ++i)
            if (qr.matrixQR()(i, i) < 0.0)
                q.col(i) = -q.col(i);
        basis = q;
    } else {
        for (Eigen::Index i = 0; i < rank; ++i)
            basis.col(i) = eigenvectors.col(i);
    }
    // Canonical sign: a basis vector and its negative are equally valid; fix the one whose
    // largest-magnitude entry (the first, on ties) is positive, so reruns and LODs agree.
    for (Eigen::Index i = 0; i < rank; ++i) {
        Eigen::Index at = 0;
        basis.col(i).cwiseAbs().maxCoeff(&at);
        if (basis(at, i) < 0.0)
            basis.col(i) = -basis.col(i);
    }

    Eigen::MatrixXd coords(rank, frames);
    double total = 0.0;
    {
        const Eigen::Index blocks = (frames + kColumnBlock - 1) / kColumnBlock;
        std::vector<double> blockEnergy(size_t(blocks), 0.0);
        tbb::parallel_for(Eigen::Index(0), blocks, [&](Eigen::Index block) {
            const Eigen::Index col = block * kColumnBlock, cols = std::min(kColumnBlock, frames - col);
            const Eigen::MatrixXd centred = samples.middleCols(col, cols).cast<double>().colwise() - mean;
            coords.middleCols(col, cols).noalias() = basis.transpose() * centred;
            blockEnergy[size_t(block)] = centred.squaredNorm();
        });
        for (double e : blockEnergy)
            total += e;
    }
    result.relativeErrorPerRank.assign(size_t(rank) + 1, 0.0);
    double captured = 0.0;
    for (Eigen::Index k = 0; k <= rank; ++k) {
        if (k > 0)
            captured += coords.row(k - 1).squaredNorm();
        result.relativeErrorPerRank[size_t(k)] = total > 0.0 ? std::sqrt(std::max(0.0, total - captured) / total) : 0.0;
    }

    result.mean = mean.cast<float>();
    result.basis = basis.cast<float>();
    result.coords = coords.cast<float>();
    return result;
}

uint32_t rankForRelativeError(const PcaResult& pca, double maxRelativeError) {
    for (size_t k = 0; k < pca.relativeErrorPerRank.size(); ++k)
        if (pca.relativeErrorPerRank[k] <= maxRelativeError)
            return uint32_t(k);
    return uint32_t(pca.relativeErrorPerRank.empty() ? 0 : pca.relativeErrorPerRank.size() - 1);
}

} // namespace meadow
