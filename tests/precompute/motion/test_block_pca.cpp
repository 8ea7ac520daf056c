// Block PCA (one block per rod): the Eckart–Young identity across blocks, optimality of the greedy
// allocation of modes to blocks, the run-time basis layout, and rejection of bad input.
#include "motion/block_pca.h"

#include "core/error.h"
#include "core/random.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <Eigen/QR>

#include <algorithm>
#include <cmath>
#include <functional>

using namespace meadow;

namespace {

// Vertex data of `blockCount` independent "rods", interleaved in vertex order so that blocks are
// not contiguous ranges: block b's vertices are v with v % blockCount == b. Each block's centred
// data has the singular values spectra[b] exactly.
struct BlockData {
    Eigen::MatrixXf samples; // 3V x F
    std::vector<uint32_t> vertexBlock;
};

BlockData makeBlockData(uint32_t verticesPerBlock, Eigen::Index frames, const std::vector<std::vector<double>>& spectra,
                        uint64_t seed) {
    const uint32_t blockCount = uint32_t(spectra.size());
    BlockData data;
    data.samples.resize(Eigen::Index(3 * verticesPerBlock * blockCount), frames);
    data.vertexBlock.resize(verticesPerBlock * blockCount);
    Random random(seed);
    for (uint32_t b = 0; b < blockCount; ++b) {
        const Eigen::Index n = 3 * verticesPerBlock, k = Eigen::Index(spectra[b].size());
        Eigen::MatrixXd a(n, k), c(frames, k);
        for (Eigen::Index i = 0; i < a.size(); ++i)
            a.data()[i] = random.uniform(-1.0f, 1.0f);
        for (Eigen::Index i = 0; i < c.size(); ++i)
            c.data()[i] = random.uniform(-1.0f, 1.0f);
        c.rowwise() -= c.colwise().mean();
        const Eigen::MatrixXd qa =
            Eigen::HouseholderQR<Eigen::MatrixXd>(a).householderQ() * Eigen::MatrixXd::Identity(n, k);
        const Eigen::MatrixXd qc =
            Eigen::HouseholderQR<Eigen::MatrixXd>(c).householderQ() * Eigen::MatrixXd::Identity(frames, k);
        Eigen::VectorXd s(k);
        for (Eigen::Index i = 0; i < k; ++i)
            s(i) = spectra[b][size_t(i)];
        const Eigen::MatrixXd x = qa * s.asDiagonal() * qc.transpose();
        for (uint32_t i = 0; i < verticesPerBlock; ++i) {
            const uint32_t v = i * blockCount + b;
            data.vertexBlock[v] = b;
            for (int axis = 0; axis < 3; ++axis)
                data.samples.row(Eigen::Index(3 * v + axis)) =
                    (x.row(Eigen::Index(3 * i + axis)).array() + 0.1 * double(v % 5)).cast<float>();
        }
    }
    return data;
}

const std::vector<std::vector<double>> kSpectra = {
    {9.0, 4.0, 1.5, 0.6, 0.2}, // a busy blade
    {6.0, 5.5, 0.3},           // two strong modes, then little
    {2.0, 0.1},                // a stiff stem
    {7.0, 1.0, 0.9, 0.8},      // one strong mode over a flat tail
};

double energy(const std::vector<std::vector<double>>& spectra) {
    double e = 0.0;
    for (const auto& s : spectra)
        for (double v : s)
            e += v * v;
    return e;
}

} // namespace

TEST(BlockPca, ErrorEqualsTheDroppedSingularValuesAcrossBlocks) {
    const BlockData data = makeBlockData(12, 80, kSpectra, 1);
    const BlockPcaResult pca = computeBlockPca(data.samples, data.vertexBlock, 4, 16);
    ASSERT_EQ(pca.modeOrder.size(), 14u); // every block's numerical rank, nothing more
    // Eckart–Young across blocks: keeping the k largest singular values of all blocks leaves the
    // energy of the others. Tolerance: float storage of the data (values of order 1).
    std::vector<double> all;
    for (const auto& s : kSpectra)
        all.insert(all.end(), s.begin(), s.end());
    std::sort(all.rbegin(), all.rend());
    const double total = energy(kSpectra);
    double dropped = total;
    for (size_t k = 0; k <= all.size(); ++k) {
        if (k > 0)
            dropped -= all[k - 1] * all[k - 1];
        EXPECT_NEAR(pca.relativeErrorPerMode[k], std::sqrt(std::max(0.0, dropped) / total), 1e-4) << "modes " << k;
    }
    // The order is by singular value: the blade's 9 first, then the blade of 7.
    EXPECT_EQ(pca.modeOrder[0], std::make_pair(0u, 0u));
    EXPECT_EQ(pca.modeOrder[1], std::make_pair(3u, 0u));
    EXPECT_EQ(pca.modeOrder[2], std::make_pair(1u, 0u));
}

TEST(BlockPca, GreedyAllocationIsTheLeastErrorForEveryModeCount) {
    const BlockData data = makeBlockData(10, 60, kSpectra, 2);
    const BlockPcaResult pca = computeBlockPca(data.samples, data.vertexBlock, 4, 16);
    // Brute force over every allocation (r_0..r_3) of k modes to the blocks, each a prefix of the
    // block's own modes: none leaves less error than the greedy choice.
    const double total = energy(kSpectra);
    for (uint32_t k = 0; k <= 14; ++k) {
        double best = total;
        std::function<void(size_t, uint32_t, double)> search = [&](size_t b, uint32_t left, double captured) {
            if (b == kSpectra.size()) {
                if (left == 0)
                    best = std::min(best, total - captured);
                return;
            }
            double c = captured;
            for (uint32_t r = 0; r <= std::min<uint32_t>(left, uint32_t(kSpectra[b].size())); ++r) {
                if (r > 0)
                    c += kSpectra[b][r - 1] * kSpectra[b][r - 1];
                search(b + 1, left - r, c);
            }
        };
        search(0, k, 0.0);
        // Tolerance: float data, relative errors of order 1e-5.
        EXPECT_NEAR(pca.relativeErrorPerMode[k], std::sqrt(std::max(0.0, best) / total), 1e-4) << "modes " << k;
        // Each block's share of the first k modes is a prefix of its modes, and they add up to k.
        const std::vector<uint32_t> ranks = blockRanksForModes(pca, k);
        uint32_t sum = 0;
        for (uint32_t b = 0; b < 4; ++b) {
            sum += ranks[b];
            for (uint32_t i = 0; i < ranks[b]; ++i)
                EXPECT_NE(std::find(pca.modeOrder.begin(), pca.modeOrder.begin() + k, std::make_pair(b, i)),
                          pca.modeOrder.begin() + k);
        }
        EXPECT_EQ(sum, k);
    }
}

TEST(BlockPca, MotionBasisReconstructsEveryFrameAndLod) {
    const BlockData data = makeBlockData(9, 50, kSpectra, 3);
    const BlockPcaResult pca = computeBlockPca(data.samples, data.vertexBlock, 4, 16);
    const std::array<uint32_t, kLodCount> lodModes = {14, 9, 5, 2, 1};
    const MotionBasis basis = makeMotionBasis(pca, lodModes);
    EXPECT_EQ(basis.frames, 50u);
    EXPECT_EQ(basis.lodModes, lodModes);
    EXPECT_EQ(basis.maxBlockRank(0), 5u); // the busy blade
    for (uint32_t lod = 0; lod < kLodCount; ++lod) {
        const std::vector<uint32_t> ranks = blockRanksForModes(pca, lodModes[lod]);
        for (uint32_t b = 0; b < 4; ++b)
            EXPECT_EQ(basis.blocks[b].ranks[lod], ranks[b]);
        // Independently of the layout: the reconstruction's error over all frames is the error
        // the PCA reports for that many modes. Tolerance: float rounding.
        double err = 0.0, total = 0.0;
        for (uint32_t f = 0; f < basis.frames; ++f)
            for (uint32_t v = 0; v < basis.vertexBlock.size(); ++v) {
                const glm::vec3 x(data.samples(3 * v, f), data.samples(3 * v + 1, f), data.samples(3 * v + 2, f));
                const glm::vec3 mean(pca.mean(3 * v), pca.mean(3 * v + 1), pca.mean(3 * v + 2));
                const glm::vec3 d = x - mean - basis.displacement(v, f, lod);
                err += double(glm::dot(d, d));
                total += double(glm::dot(x - mean, x - mean));
            }
        EXPECT_NEAR(std::sqrt(err / total), pca.relativeErrorPerMode[lodModes[lod]], 1e-4) << "LOD " << lod;
    }
}

TEST(BlockPca, DeterministicAcrossThreadCounts) {
    const BlockData data = makeBlockData(40, 200, kSpectra, 4);
    auto run = [&](size_t threads) {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
        return makeMotionBasis(computeBlockPca(data.samples, data.vertexBlock, 4, 8), {10, 6, 4, 2, 1});
    };
    const MotionBasis one = run(1), two = run(2);
    EXPECT_EQ(one.basis, two.basis);
    EXPECT_EQ(one.coords, two.coords);
    EXPECT_EQ(one.relativeErrorPerMode, two.relativeErrorPerMode);
}

TEST(BlockPca, RejectsBadInput) {
    const BlockData data = makeBlockData(4, 20, kSpectra, 5);
    std::vector<uint32_t> outOfRange = data.vertexBlock;
    outOfRange[3] = 9;
    EXPECT_THROW(computeBlockPca(data.samples, outOfRange, 4, 8), Error);
    EXPECT_THROW(computeBlockPca(data.samples.topRows(6), data.vertexBlock, 4, 8), Error);
    Eigen::MatrixXf nan = data.samples;
    nan(2, 3) = std::nanf("");
    EXPECT_THROW(computeBlockPca(nan, data.vertexBlock, 4, 8), Error);
}

TEST(BlockPca, MotionBasisRejectsInconsistentTables) {
    const BlockData data = makeBlockData(4, 20, kSpectra, 6);
    const MotionBasis good = makeMotionBasis(computeBlockPca(data.samples, data.vertexBlock, 4, 8), {8, 6, 4, 2, 1});
    auto expectRejected = [](MotionBasis b, const char* problem) {
        try {
            b.finish("test.mlib");
            ADD_FAILURE() << "accepted: " << problem;
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find("test.mlib"), std::string::npos) << e.what();
        }
    };
    MotionBasis b = good;
    b.basis.pop_back();
    expectRejected(b, "short basis");
    b = good;
    b.coords.push_back(0.0f);
    expectRejected(b, "long coordinates");
    b = good;
    b.blocks[1].ranks[2] = b.blocks[1].ranks[1] + 1;
    expectRejected(b, "a far LOD with more modes");
    b = good;
    b.blocks[2].coordOffset += 1;
    expectRejected(b, "overlapping coordinate ranges");
    b = good;
    b.vertexBlock[0] = 99;
    expectRejected(b, "a vertex in no block");
    b = good;
    b.coords[0] = std::nanf("");
    expectRejected(b, "NaN");
}
