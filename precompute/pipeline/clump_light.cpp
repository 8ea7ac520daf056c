#include "pipeline/clump_light.h"

#include "core/error.h"
#include "plants/atlas.h"

#include <algorithm>
#include <chrono>
#include <cmath>

namespace meadow {
namespace {

double secondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// One frame held out of the models per clip: halfway between its first two baked frames, when
// there is a frame between them.
std::vector<uint32_t> heldOutFrames(const std::vector<MotionClip>& clips, const std::vector<uint32_t>& baked) {
    std::vector<uint32_t> frames;
    for (const MotionClip& clip : clips) {
        auto first = std::lower_bound(baked.begin(), baked.end(), clip.firstFrame);
        if (first == baked.end() || first + 1 == baked.end())
            continue;
        if (*(first + 1) - *first >= 2)
            frames.push_back((*first + *(first + 1)) / 2);
    }
    return frames;
}

} // namespace

Eigen::VectorXd irradiance(const Eigen::VectorXf& transfer, const std::vector<float>& sky, int order) {
    const Eigen::Index n = Eigen::Index(order * order);
    Eigen::VectorXd e(transfer.size() / n);
    for (Eigen::Index g = 0; g < e.size(); ++g) {
        const Eigen::Index channel = g % 3;
        double sum = 0.0;
        for (Eigen::Index i = 0; i < n; ++i)
            sum += double(transfer(g * n + i)) * double(sky[size_t(3 * i + channel)]);
        e(g) = sum;
    }
    return e;
}

namespace {

double relativeDifference(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
    const double norm = b.norm();
    return norm > 0.0 ? (a - b).norm() / norm : 0.0;
}

} // namespace

std::vector<glm::vec3> vertexAlbedo(const Mesh& mesh, const RgbaImage& atlas) {
    if (atlas.width == 0 || atlas.height == 0 || atlas.rgba.size() != size_t(atlas.width) * atlas.height * 4)
        throw Error("vertex albedo: the atlas is empty or has the wrong size");
    std::vector<glm::vec3> albedo(mesh.vertices.size());
    for (size_t v = 0; v < mesh.vertices.size(); ++v) {
        const float u = mesh.vertices[v].positionU.w, t = mesh.vertices[v].normalV.w;
        const int cx = std::clamp(int(std::floor(u * float(atlas.width))), 0, int(atlas.width) - 1);
        const int cy = std::clamp(int(std::floor(t * float(atlas.height))), 0, int(atlas.height) - 1);
        glm::vec3 sum(0.0f);
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
                const int x = std::clamp(cx + dx, 0, int(atlas.width) - 1);
                const int y = std::clamp(cy + dy, 0, int(atlas.height) - 1);
                const uint8_t* texel = &atlas.rgba[(size_t(y) * atlas.width + size_t(x)) * 4];
                sum += glm::vec3(srgbToLinear(texel[0]), srgbToLinear(texel[1]), srgbToLinear(texel[2]));
            }
        albedo[v] = sum / 9.0f;
    }
    return albedo;
}

ClumpLight buildClumpLight(const ClumpMotion& motion, const Mesh& meanPose, const std::vector<glm::vec3>& albedo,
                           const LightParams& params, const std::vector<float>& testSky) {
    const MotionBasis& basis = motion.basis;
    const uint32_t vertexCount = uint32_t(meanPose.vertices.size());
    if (albedo.size() != vertexCount || basis.vertexBlock.size() != vertexCount)
        throw Error("clump " + motion.clump.name + ": light bake inputs disagree on the vertex count");
    if (testSky.size() != size_t(3 * sh::coefficientCount(params.bake.order)))
        throw Error("clump " + motion.clump.name + ": the test sky's SH order differs from the bake's");

    auto start = std::chrono::steady_clock::now();
    const std::vector<float> translucency = transfer::translucencyForParts(motion.clump.mesh.parts, params.bake);
    transfer::TransferBaker baker(meanPose.indices, albedo, translucency, params.bake);
    const std::vector<uint32_t> baked = appearanceBakeFrames(motion.clips, params.framesPerLevel);
    const std::vector<uint32_t> heldOut = heldOutFrames(motion.clips, baked);

    auto displacements = [&](uint32_t frame) {
        std::vector<glm::vec3> d(vertexCount);
        for (uint32_t v = 0; v < vertexCount; ++v)
            d[v] = basis.displacement(v, frame);
        return d;
    };
    auto bakeFrame = [&](transfer::TransferBaker& with, uint32_t frame) {
        const Mesh posed = meshAtFrame(meanPose, basis, frame);
        std::vector<glm::vec3> positions(vertexCount), normals(vertexCount);
        for (uint32_t v = 0; v < vertexCount; ++v) {
            positions[v] = glm::vec3(posed.vertices[v].positionU);
            normals[v] = glm::vec3(posed.vertices[v].normalV);
        }
        return with.bake(positions, normals);
    };
    auto asVector = [](const std::vector<float>& values) {
        return Eigen::VectorXf(Eigen::Map<const Eigen::VectorXf>(values.data(), Eigen::Index(values.size())));
    };

    ClumpLight out;
    out.bakedFrames = baked;
    Eigen::MatrixXf vertexSamples, groundSamples;
    std::vector<std::vector<glm::vec3>> bakedDisplacements;
    for (size_t s = 0; s < baked.size(); ++s) {
        const transfer::ClumpTransfer t = bakeFrame(baker, baked[s]);
        if (s == 0) {
            out.order = t.vertices.order;
            out.groundResolution = t.ground.resolution;
            out.groundSize = t.ground.size;
            vertexSamples.resize(Eigen::Index(t.vertices.coefficients.size()), Eigen::Index(baked.size()));
            groundSamples.resize(Eigen::Index(t.ground.coefficients.size()), Eigen::Index(baked.size()));
        }
        vertexSamples.col(Eigen::Index(s)) = asVector(t.vertices.coefficients);
        groundSamples.col(Eigen::Index(s)) = asVector(t.ground.coefficients);
        bakedDisplacements.push_back(displacements(baked[s]));
    }
    std::vector<transfer::ClumpTransfer> heldOutBakes;
    for (uint32_t frame : heldOut)
        heldOutBakes.push_back(bakeFrame(baker, frame));
    // The noise floor: the first baked frame again, with other ray directions.
    transfer::BakeSettings reseeded = params.bake;
    reseeded.seed = params.bake.seed * 0x9e3779b97f4a7c15ull + 1;
    transfer::TransferBaker other(meanPose.indices, albedo, translucency, reseeded);
    const transfer::ClumpTransfer again = bakeFrame(other, baked[0]);
    out.bakeSeconds = secondsSince(start);

    start = std::chrono::steady_clock::now();
    const bool ground = groundSamples.rows() > 0;
    const uint32_t valuesPerVertex = uint32_t(vertexSamples.rows() / vertexCount);
    // Displacements varying by less than a millimetre say nothing about the transfer.
    out.vertices = fitVertexAppearance(vertexSamples, valuesPerVertex, bakedDisplacements, 1e-3f);
    auto noise = [&](const Eigen::VectorXf& a, const std::vector<float>& b, double& coefficientNoise,
                     double& irradianceNoise) {
        const Eigen::VectorXf bv = asVector(b);
        coefficientNoise = relativeDifference(a.cast<double>(), bv.cast<double>()) / std::sqrt(2.0);
        irradianceNoise =
            relativeDifference(irradiance(a, testSky, out.order), irradiance(bv, testSky, out.order)) / std::sqrt(2.0);
    };
    noise(vertexSamples.col(0), again.vertices.coefficients, out.vertexNoise, out.vertexIrradianceNoise);
    if (ground) {
        noise(groundSamples.col(0), again.ground.coefficients, out.groundNoise, out.groundIrradianceNoise);
        // Modes below the bake's own noise would only reproduce the noise of the baked frames: the
        // truncation stops at the larger of the scene's bound and the measured noise.
        out.ground =
            reduceAppearance(groundSamples, baked, motion.clips, basis.frames,
                             std::max(double(params.appearanceMaxError), out.groundNoise), params.maxAppearanceModes);
        // The run time plays the mean only: where modes would beat the noise they are dropped
        // rather than stored unplayed, and the held-out error below is the mean's. Their gain
        // stays in relativeErrorPerMode.
        out.ground.basis.resize(out.ground.basis.rows(), 0);
        out.ground.coords.resize(0, out.ground.coords.cols());
    }

    // Held-out errors in irradiance under the test sky, summed over the held-out frames.
    double vertexErr = 0.0, meanErr = 0.0, vertexTotal = 0.0, groundErr = 0.0, groundTotal = 0.0;
    const Eigen::VectorXd meanIrradiance = irradiance(vertexSamples.rowwise().mean(), testSky, out.order);
    for (size_t h = 0; h < heldOut.size(); ++h) {
        const Eigen::VectorXd truth = irradiance(asVector(heldOutBakes[h].vertices.coefficients), testSky, out.order);
        const std::vector<glm::vec3> d = displacements(heldOut[h]);
        vertexErr += (irradiance(evaluateVertexAppearance(out.vertices, d), testSky, out.order) - truth).squaredNorm();
        meanErr += (meanIrradiance - truth).squaredNorm();
        vertexTotal += truth.squaredNorm();
        if (ground) {
            const Eigen::VectorXd g = irradiance(asVector(heldOutBakes[h].ground.coefficients), testSky, out.order);
            groundErr +=
                (irradiance(reconstructAppearance(out.ground, heldOut[h]), testSky, out.order) - g).squaredNorm();
            groundTotal += g.squaredNorm();
        }
    }
    out.vertexHeldOutError = vertexTotal > 0.0 ? std::sqrt(vertexErr / vertexTotal) : 0.0;
    out.vertexMeanOnlyError = vertexTotal > 0.0 ? std::sqrt(meanErr / vertexTotal) : 0.0;
    out.groundHeldOutError = groundTotal > 0.0 ? std::sqrt(groundErr / groundTotal) : 0.0;
    out.reduceSeconds = secondsSince(start);
    return out;
}

LibraryLight libraryLight(const ClumpLight& light) {
    LibraryLight out;
    out.order = light.order;
    out.bakedFrames = light.bakedFrames;
    out.vertices = light.vertices;
    out.groundResolution = light.groundResolution;
    out.groundSize = light.groundSize;
    if (light.groundResolution > 0) {
        const AppearanceModel& m = light.ground;
        GroundAppearance& g = out.ground;
        g.mean.assign(m.mean.data(), m.mean.data() + m.mean.size());
        g.bakedFrames = m.bakedFrames;
        g.relativeErrorPerMode = m.relativeErrorPerMode;
    }
    out.vertexNoise = light.vertexNoise;
    out.groundNoise = light.groundNoise;
    out.vertexHeldOutError = light.vertexHeldOutError;
    out.vertexMeanOnlyError = light.vertexMeanOnlyError;
    out.groundHeldOutError = light.groundHeldOutError;
    out.vertexIrradianceNoise = light.vertexIrradianceNoise;
    out.groundIrradianceNoise = light.groundIrradianceNoise;
    return out;
}

} // namespace meadow
