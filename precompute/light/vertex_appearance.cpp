#include "light/vertex_appearance.h"

#include "core/error.h"

#include <Eigen/Cholesky>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <string>

namespace meadow {

VertexAppearance fitVertexAppearance(const Eigen::MatrixXf& baked, uint32_t valuesPerVertex,
                                     const std::vector<std::vector<glm::vec3>>& displacements, float ridgeMetres) {
    const Eigen::Index frames = baked.cols();
    if (valuesPerVertex == 0 || baked.rows() % valuesPerVertex != 0)
        throw Error("vertex appearance: " + std::to_string(baked.rows()) +
                    " transfer values are not a whole number of " + std::to_string(valuesPerVertex) +
                    "-value vertices");
    if (frames < 2 || size_t(frames) != displacements.size())
        throw Error("vertex appearance: " + std::to_string(frames) + " baked frames for " +
                    std::to_string(displacements.size()) + " displacement sets (at least 2 needed)");
    const uint32_t vertexCount = uint32_t(baked.rows() / valuesPerVertex);
    for (const std::vector<glm::vec3>& d : displacements) {
        if (d.size() != vertexCount)
            throw Error("vertex appearance: a displacement set has " + std::to_string(d.size()) + " vertices, not " +
                        std::to_string(vertexCount));
        for (const glm::vec3& x : d)
            if (!std::isfinite(x.x) || !std::isfinite(x.y) || !std::isfinite(x.z))
                throw Error("vertex appearance: a displacement is not finite");
    }
    if (!baked.allFinite())
        throw Error("vertex appearance: a baked transfer holds NaN or infinite values");
    if (!(ridgeMetres >= 0.0f) || !std::isfinite(ridgeMetres))
        throw Error("vertex appearance: the ridge must be a finite length >= 0");

    VertexAppearance model;
    model.vertexCount = vertexCount;
    model.valuesPerVertex = valuesPerVertex;
    model.coefficients.assign(size_t(vertexCount) * valuesPerVertex * 4, 0.0f);
    // Each vertex is an independent least-squares problem written to its own slots.
    tbb::parallel_for(tbb::blocked_range<uint32_t>(0, vertexCount, 64), [&](const tbb::blocked_range<uint32_t>& range) {
        for (uint32_t v = range.begin(); v != range.end(); ++v) {
            // Centre the regressors: the intercept is then the mean transfer, and the ridge acts
            // on the gradient alone.
            Eigen::MatrixXd x(frames, 3);
            for (Eigen::Index s = 0; s < frames; ++s) {
                const glm::vec3& d = displacements[size_t(s)][v];
                x.row(s) << d.x, d.y, d.z;
            }
            const Eigen::RowVector3d centre = x.colwise().mean();
            x.rowwise() -= centre;
            const Eigen::MatrixXd y =
                baked.middleRows(Eigen::Index(v) * valuesPerVertex, valuesPerVertex).transpose().cast<double>();
            const Eigen::RowVectorXd yMean = y.colwise().mean();
            Eigen::Matrix3d normal = x.transpose() * x;
            normal.diagonal().array() += double(frames) * double(ridgeMetres) * double(ridgeMetres);
            const Eigen::MatrixXd gradient = normal.ldlt().solve(x.transpose() * (y.rowwise() - yMean)); // 3 x values
            for (uint32_t i = 0; i < valuesPerVertex; ++i) {
                float* out = &model.coefficients[(size_t(v) * valuesPerVertex + i) * 4];
                // T̄ at zero displacement: the fit passes through (centre, yMean).
                out[0] = float(yMean(i) - centre.dot(gradient.col(i)));
                out[1] = float(gradient(0, i));
                out[2] = float(gradient(1, i));
                out[3] = float(gradient(2, i));
            }
        }
    });
    return model;
}

Eigen::VectorXf evaluateVertexAppearance(const VertexAppearance& model, std::span<const glm::vec3> displacement) {
    Eigen::VectorXf out(Eigen::Index(size_t(model.vertexCount) * model.valuesPerVertex));
    for (uint32_t v = 0; v < model.vertexCount; ++v) {
        const glm::vec3 d = displacement[v];
        for (uint32_t i = 0; i < model.valuesPerVertex; ++i) {
            const float* c = model.at(v, i);
            out(Eigen::Index(size_t(v) * model.valuesPerVertex + i)) = c[0] + c[1] * d.x + c[2] * d.y + c[3] * d.z;
        }
    }
    return out;
}

} // namespace meadow
