// Attribute groups and collapse groups from a clump's data (lod.h): what "weighs lighting and
// motion" (Cove & James 2004, section 2.3) means in numbers the attribute quadric can use.
#include "lod/lod.h"

#include "core/error.h"
#include "light/vertex_appearance.h"
#include "plants/plant.h"

#include <cmath>
#include <string>

namespace meadow {

std::vector<uint32_t> rodGroups(const PlantMesh& mesh) {
    if (mesh.skin.size() != mesh.positions.size())
        throw Error("LOD: the plant mesh has " + std::to_string(mesh.skin.size()) + " skin bindings for " +
                    std::to_string(mesh.positions.size()) + " vertices");
    std::vector<uint32_t> groups(mesh.skin.size());
    for (size_t v = 0; v < groups.size(); ++v)
        groups[v] = mesh.skin[v].rod;
    return groups;
}

AttributeValues motionAttributes(const MotionBasis& motion, uint32_t lod) {
    if (lod >= kLodCount)
        throw Error("LOD: motion attributes asked for LOD " + std::to_string(lod) + " of " + std::to_string(kLodCount));
    if (motion.vertexRowOffset.size() != motion.vertexBlock.size())
        throw Error("LOD: the motion basis is not finished (MotionBasis::finish computes its row offsets)");
    if (motion.frames == 0)
        throw Error("LOD: the motion basis has no frames to scale its modes by");
    const uint32_t coordsPerFrame = motion.modesPerFrame();
    // RMS of each coordinate over the frames: PCA coordinates are centred, so this is their
    // standard deviation, the typical size of that mode's contribution.
    std::vector<double> sigma(coordsPerFrame, 0.0);
    for (uint32_t f = 0; f < motion.frames; ++f)
        for (uint32_t k = 0; k < coordsPerFrame; ++k) {
            const double q = motion.coords[size_t(f) * coordsPerFrame + k];
            sigma[k] += q * q;
        }
    for (double& s : sigma)
        s = std::sqrt(s / double(motion.frames));

    AttributeValues result;
    result.width = 3 * motion.maxBlockRank(lod);
    if (result.width == 0)
        throw Error("LOD: the motion basis uses no modes at LOD " + std::to_string(lod));
    result.values.assign(motion.vertexBlock.size() * result.width, 0.0f);
    for (size_t v = 0; v < motion.vertexBlock.size(); ++v) {
        const MotionBlock& block = motion.blocks[motion.vertexBlock[v]];
        const float* rows = &motion.basis[motion.vertexRowOffset[v]];
        float* out = &result.values[v * result.width];
        for (uint32_t k = 0; k < block.ranks[lod]; ++k)
            for (uint32_t axis = 0; axis < 3; ++axis)
                out[3 * k + axis] = float(double(rows[3 * k + axis]) * sigma[block.coordOffset + k]);
    }
    return result;
}

AttributeValues meanTransferAttributes(const VertexAppearance& appearance) {
    const uint32_t n = appearance.vertexCount, width = appearance.valuesPerVertex;
    if (n == 0 || width == 0 || appearance.coefficients.size() != size_t(n) * width * 4)
        throw Error("LOD: the vertex appearance holds " + std::to_string(appearance.coefficients.size()) +
                    " coefficients for " + std::to_string(n) + " vertices x " + std::to_string(width) + " values x 4");
    AttributeValues result;
    result.width = width;
    result.values.resize(size_t(n) * width);
    std::vector<double> mean(width, 0.0);
    for (uint32_t v = 0; v < n; ++v)
        for (uint32_t j = 0; j < width; ++j) {
            const float t = appearance.at(v, j)[0];
            if (!std::isfinite(t))
                throw Error("LOD: the mean transfer of vertex " + std::to_string(v) + " is not finite");
            result.values[size_t(v) * width + j] = t;
            mean[j] += t;
        }
    for (double& m : mean)
        m /= double(n);
    double deviation = 0.0;
    for (uint32_t v = 0; v < n; ++v)
        for (uint32_t j = 0; j < width; ++j) {
            const double d = result.values[size_t(v) * width + j] - mean[j];
            deviation += d * d;
        }
    deviation = std::sqrt(deviation / (double(n) * width));
    // A constant transfer has no differences to weigh; leave it unscaled rather than divide by 0.
    const double scale = deviation > 0.0 ? 1.0 / deviation : 1.0;
    for (float& value : result.values)
        value = float(double(value) * scale);
    return result;
}

} // namespace meadow
