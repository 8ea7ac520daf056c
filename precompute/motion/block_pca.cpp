#include "motion/block_pca.h"

#include "core/error.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <tuple>

namespace meadow {

BlockPcaResult computeBlockPca(const Eigen::MatrixXf& samples, const std::vector<uint32_t>& vertexBlock,
                               uint32_t blockCount, uint32_t maxModesPerBlock) {
    const Eigen::Index frames = samples.cols();
    if (samples.rows() == 0 || frames == 0)
        throw Error("block PCA: the sample matrix is empty");
    if (size_t(samples.rows()) != 3 * vertexBlock.size())
        throw Error("block PCA: " + std::to_string(samples.rows()) + " sample rows for " +
                    std::to_string(vertexBlock.size()) + " vertices (3 rows each)");
    if (!samples.allFinite())
        throw Error("block PCA: the samples hold NaN or infinite values");

    BlockPcaResult result;
    result.vertexBlock = vertexBlock;
    result.blockVertices.resize(blockCount);
    for (uint32_t v = 0; v < vertexBlock.size(); ++v) {
        if (vertexBlock[v] >= blockCount)
            throw Error("block PCA: vertex " + std::to_string(v) + " names block " + std::to_string(vertexBlock[v]) +
                        " of " + std::to_string(blockCount));
        result.blockVertices[vertexBlock[v]].push_back(v);
    }

    // Each block is an independent PCA; computePca is deterministic for any thread count, and
    // each block writes only its own slot.
    result.blocks.resize(blockCount);
    std::vector<double> blockEnergy(blockCount, 0.0);
    result.mean = Eigen::VectorXf::Zero(samples.rows());
    tbb::parallel_for(uint32_t(0), blockCount, [&](uint32_t b) {
        const std::vector<uint32_t>& vertices = result.blockVertices[b];
        if (vertices.empty())
            return;
        Eigen::MatrixXf rows(Eigen::Index(3 * vertices.size()), frames);
        for (size_t i = 0; i < vertices.size(); ++i)
            rows.middleRows(Eigen::Index(3 * i), 3) = samples.middleRows(Eigen::Index(3 * vertices[i]), 3);
        PcaResult pca = computePca(rows, std::min<uint32_t>(maxModesPerBlock, uint32_t(rows.rows())));
        // The block's total centred energy, so that errors combine across blocks.
        const Eigen::MatrixXd centred = rows.cast<double>().colwise() - pca.mean.cast<double>();
        blockEnergy[b] = centred.squaredNorm();
        for (size_t i = 0; i < vertices.size(); ++i)
            result.mean.segment(Eigen::Index(3 * vertices[i]), 3) = pca.mean.segment(Eigen::Index(3 * i), 3);
        result.blocks[b] = std::move(pca);
    });

    for (uint32_t b = 0; b < blockCount; ++b)
        for (uint32_t i = 0; i < uint32_t(result.blocks[b].basis.cols()); ++i)
            result.modeOrder.emplace_back(b, i);
    std::sort(result.modeOrder.begin(), result.modeOrder.end(), [&](const auto& x, const auto& y) {
        const double sx = result.blocks[x.first].singularValues[x.second];
        const double sy = result.blocks[y.first].singularValues[y.second];
        return std::tie(sy, x.first, x.second) < std::tie(sx, y.first, y.second);
    });

    double total = 0.0;
    for (double e : blockEnergy)
        total += e;
    result.relativeErrorPerMode.assign(result.modeOrder.size() + 1, 0.0);
    double captured = 0.0;
    for (size_t k = 0; k <= result.modeOrder.size(); ++k) {
        if (k > 0) {
            const auto [b, i] = result.modeOrder[k - 1];
            captured += double(result.blocks[b].coords.row(Eigen::Index(i)).cast<double>().squaredNorm());
        }
        result.relativeErrorPerMode[k] = total > 0.0 ? std::sqrt(std::max(0.0, total - captured) / total) : 0.0;
    }
    return result;
}

uint32_t modesForRelativeError(const BlockPcaResult& pca, double maxRelativeError) {
    for (size_t k = 0; k < pca.relativeErrorPerMode.size(); ++k)
        if (pca.relativeErrorPerMode[k] <= maxRelativeError)
            return uint32_t(k);
    return uint32_t(pca.modeOrder.size());
}

std::vector<uint32_t> blockRanksForModes(const BlockPcaResult& pca, uint32_t modes) {
    std::vector<uint32_t> ranks(pca.blocks.size(), 0);
    for (uint32_t k = 0; k < std::min<size_t>(modes, pca.modeOrder.size()); ++k)
        ++ranks[pca.modeOrder[k].first];
    return ranks;
}

MotionBasis makeMotionBasis(const BlockPcaResult& pca, const std::array<uint32_t, kLodCount>& lodModes) {
    MotionBasis out;
    const uint32_t blockCount = uint32_t(pca.blocks.size());
    const Eigen::Index frames = pca.blocks.empty() ? 0 : [&] {
        for (const PcaResult& b : pca.blocks)
            if (b.coords.cols() > 0)
                return b.coords.cols();
        return Eigen::Index(0);
    }();
    out.frames = uint32_t(frames);
    out.vertexBlock = pca.vertexBlock;
    out.relativeErrorPerMode = pca.relativeErrorPerMode;
    out.blocks.resize(blockCount);
    for (uint32_t lod = 0; lod < kLodCount; ++lod) {
        std::vector<uint32_t> ranks = blockRanksForModes(pca, lodModes[lod]);
        out.lodModes[lod] = 0;
        for (uint32_t b = 0; b < blockCount; ++b) {
            out.blocks[b].ranks[lod] = ranks[b];
            out.lodModes[lod] += ranks[b];
        }
    }
    uint32_t offset = 0;
    for (MotionBlock& block : out.blocks) {
        block.coordOffset = offset;
        offset += block.ranks[0];
    }

    // Basis rows, vertex by vertex: the vertex's position in its block's row order.
    std::vector<uint32_t> indexInBlock(pca.vertexBlock.size(), 0);
    for (const std::vector<uint32_t>& vertices : pca.blockVertices)
        for (size_t i = 0; i < vertices.size(); ++i)
            indexInBlock[vertices[i]] = uint32_t(i);
    for (uint32_t v = 0; v < pca.vertexBlock.size(); ++v) {
        const uint32_t b = pca.vertexBlock[v];
        const Eigen::MatrixXf& u = pca.blocks[b].basis;
        for (uint32_t k = 0; k < out.blocks[b].ranks[0]; ++k)
            for (int axis = 0; axis < 3; ++axis)
                out.basis.push_back(u(Eigen::Index(3 * indexInBlock[v] + axis), Eigen::Index(k)));
    }
    out.coords.resize(size_t(frames) * out.lodModes[0]);
    for (uint32_t b = 0; b < blockCount; ++b)
        for (uint32_t k = 0; k < out.blocks[b].ranks[0]; ++k)
            for (Eigen::Index f = 0; f < frames; ++f)
                out.coords[size_t(f) * out.lodModes[0] + out.blocks[b].coordOffset + k] =
                    pca.blocks[b].coords(Eigen::Index(k), f);
    out.finish("motion basis");
    return out;
}

} // namespace meadow
