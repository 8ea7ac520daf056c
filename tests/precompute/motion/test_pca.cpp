#include "motion/pca.h"

#include "core/error.h"
#include "core/random.h"
#include "synthetic_motion.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <Eigen/QR>

#include <cmath>
#include <cstring>

using namespace meadow;

namespace {

// n x F data with a known, decaying spectrum: X = mean + Q1 diag(s) Q2^T.
Eigen::MatrixXf spectrumMatrix(Eigen::Index n, Eigen::Index frames, const std::vector<double>& spectrum,
                               uint64_t seed) {
    Random random(seed);
    const Eigen::Index k = Eigen::Index(spectrum.size());
    Eigen::MatrixXd a(n, k), b(frames, k);
    for (Eigen::Index i = 0; i < a.size(); ++i)
        a.data()[i] = random.uniform(-1.0f, 1.0f);
    for (Eigen::Index i = 0; i < b.size(); ++i)
        b.data()[i] = random.uniform(-1.0f, 1.0f);
    // Centre the frame factor so the mean stays exactly the added offset.
    b.rowwise() -= b.colwise().mean();
    const Eigen::MatrixXd qa =
        Eigen::HouseholderQR<Eigen::MatrixXd>(a).householderQ() * Eigen::MatrixXd::Identity(n, k);
    const Eigen::MatrixXd qb =
        Eigen::HouseholderQR<Eigen::MatrixXd>(b).householderQ() * Eigen::MatrixXd::Identity(frames, k);
    Eigen::VectorXd s(k);
    for (Eigen::Index i = 0; i < k; ++i)
        s(i) = spectrum[size_t(i)];
    Eigen::MatrixXd x = qa * s.asDiagonal() * qb.transpose();
    for (Eigen::Index r = 0; r < n; ++r)
        x.row(r).array() += 0.25 * double(r % 7);
    return x.cast<float>();
}

// A decaying spectrum with no value so small that float data cannot hold it.
std::vector<double> decayingSpectrum(size_t k) {
    std::vector<double> s(k);
    for (size_t i = 0; i < k; ++i)
        s[i] = 10.0 * std::pow(0.8, double(i));
    return s;
}

void expectPcaIdentities(const Eigen::MatrixXf& x, uint32_t maxRank) {
    const PcaResult pca = computePca(x, maxRank);
    const Eigen::Index r = pca.basis.cols();
    ASSERT_EQ(pca.coords.rows(), r);
    ASSERT_EQ(pca.relativeErrorPerRank.size(), size_t(r) + 1);

    // Orthonormal basis; tolerance: float storage of double-orthonormalised columns.
    const Eigen::MatrixXf gram = pca.basis.transpose() * pca.basis;
    EXPECT_LE((gram - Eigen::MatrixXf::Identity(r, r)).cwiseAbs().maxCoeff(), 1e-4f);

    // Eckart–Young: the measured error equals the energy of the dropped singular values.
    double total = 0.0;
    for (double s : pca.singularValues)
        total += s * s;
    for (Eigen::Index k = 0; k <= r; ++k) {
        double dropped = 0.0;
        for (size_t i = size_t(k); i < pca.singularValues.size(); ++i)
            dropped += pca.singularValues[i] * pca.singularValues[i];
        EXPECT_NEAR(pca.relativeErrorPerRank[size_t(k)], std::sqrt(dropped / total), 1e-4) << "rank " << k;
        if (k > 0) {
            EXPECT_LE(pca.relativeErrorPerRank[size_t(k)], pca.relativeErrorPerRank[size_t(k - 1)] + 1e-12);
        }
    }
    EXPECT_NEAR(pca.relativeErrorPerRank[0], 1.0, 1e-9); // nothing captured at rank 0
    for (size_t i = 1; i < pca.singularValues.size(); ++i)
        EXPECT_GE(pca.singularValues[i - 1], pca.singularValues[i]);

    // The reported error at one rank also matches an explicit reconstruction (float tolerance).
    const Eigen::Index k = r / 2;
    const Eigen::MatrixXd centred = x.cast<double>().colwise() - pca.mean.cast<double>();
    const Eigen::MatrixXd uk = pca.basis.leftCols(k).cast<double>();
    const double explicitError = (centred - uk * (uk.transpose() * centred)).norm() / centred.norm();
    EXPECT_NEAR(explicitError, pca.relativeErrorPerRank[size_t(k)], 1e-4);
}

} // namespace

TEST(Pca, IdentitiesWhenFramesAreFewerThanCoordinates) {
    // F <= n: the F x F Gram route, the usual shape of vertex data.
    expectPcaIdentities(spectrumMatrix(240, 90, decayingSpectrum(20), 1), 20);
}

TEST(Pca, IdentitiesWhenCoordinatesAreFewerThanFrames) {
    // n < F: the n x n covariance route.
    expectPcaIdentities(spectrumMatrix(30, 200, decayingSpectrum(30), 2), 30);
}

TEST(Pca, IdentitiesWithTheIterativeEigenSolver) {
    // F = 600 > 512: eigenvalues by tridiagonalisation, leading vectors by subspace iteration.
    expectPcaIdentities(spectrumMatrix(700, 600, decayingSpectrum(60), 8), 30);
}

TEST(Pca, FullRankHasZeroError) {
    const PcaResult pca = computePca(spectrumMatrix(60, 40, decayingSpectrum(12), 3), 64);
    // The rank stops at the data's numerical rank (12 directions), where nothing is left.
    EXPECT_EQ(pca.basis.cols(), 12);
    EXPECT_NEAR(pca.relativeErrorPerRank.back(), 0.0, 1e-4);
    EXPECT_EQ(rankForRelativeError(pca, 1e-3), 12u);
    EXPECT_EQ(rankForRelativeError(pca, 1.0), 0u);
}

TEST(Pca, ReconstructsLowRankDataExactly) {
    // Displacements of 400 "vertices" (n = 1200) driven by 12 synthetic modes.
    const test::SyntheticMotion motion = test::makeSyntheticMotion(2, 2, 100, 12, 4);
    Random random(5);
    Eigen::MatrixXf modes(1200, 12);
    for (Eigen::Index i = 0; i < modes.size(); ++i)
        modes.data()[i] = random.uniform(-0.05f, 0.05f);
    Eigen::VectorXf rest(1200);
    for (Eigen::Index i = 0; i < rest.size(); ++i)
        rest(i) = random.uniform(-1.0f, 1.0f);
    const Eigen::MatrixXf x = (modes * motion.q).colwise() + rest;
    const PcaResult pca = computePca(x, 30);
    ASSERT_EQ(pca.basis.cols(), 12);
    const Eigen::MatrixXf rebuilt = (pca.basis * pca.coords).colwise() + pca.mean;
    // Tolerance: float rounding of 1200-long dot products on values of order 0.1.
    EXPECT_LE((rebuilt - x).cwiseAbs().maxCoeff(), 2e-5f * std::max(1.0f, x.cwiseAbs().maxCoeff()));
    EXPECT_LE(pca.relativeErrorPerRank[12], 1e-4);
    EXPECT_LE(rankForRelativeError(pca, 0.01), 12u);
}

TEST(Pca, CanonicalSigns) {
    const PcaResult pca = computePca(spectrumMatrix(100, 50, decayingSpectrum(10), 6), 10);
    for (Eigen::Index i = 0; i < pca.basis.cols(); ++i) {
        Eigen::Index at = 0;
        pca.basis.col(i).cwiseAbs().maxCoeff(&at);
        EXPECT_GT(pca.basis(at, i), 0.0f) << "column " << i;
    }
    // Flipping the data's sign flips the modes' coordinates, not the basis.
    const Eigen::MatrixXf x = spectrumMatrix(100, 50, decayingSpectrum(10), 6);
    const PcaResult flipped = computePca(-x, 10);
    EXPECT_LE((flipped.basis - pca.basis).cwiseAbs().maxCoeff(), 1e-4f);
    EXPECT_LE((flipped.coords + pca.coords).cwiseAbs().maxCoeff(), 1e-3f);
}

TEST(Pca, DeterministicAcrossThreadCounts) {
    const Eigen::MatrixXf x = spectrumMatrix(1100, 300, decayingSpectrum(40), 7);
    auto run = [&](size_t threads) {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
        return computePca(x, 24);
    };
    const PcaResult one = run(1), two = run(2);
    auto sameBits = [](const Eigen::MatrixXf& a, const Eigen::MatrixXf& b) {
        return a.rows() == b.rows() && a.cols() == b.cols() &&
               std::memcmp(a.data(), b.data(), sizeof(float) * size_t(a.size())) == 0;
    };
    EXPECT_TRUE(sameBits(one.basis, two.basis));
    EXPECT_TRUE(sameBits(one.coords, two.coords));
    EXPECT_TRUE(sameBits(one.mean, two.mean));
    EXPECT_EQ(one.singularValues, two.singularValues);
    EXPECT_EQ(one.relativeErrorPerRank, two.relativeErrorPerRank);
}

TEST(Pca, RejectsBadInput) {
    EXPECT_THROW(computePca(Eigen::MatrixXf(0, 5), 3), Error);
    Eigen::MatrixXf nan = Eigen::MatrixXf::Zero(4, 4);
    nan(1, 2) = std::nanf("");
    EXPECT_THROW(computePca(nan, 3), Error);
}
