#include "library_format.h"

#include "core/error.h"
#include "library.h"

#include <cmath>

namespace meadow {

// --- clumps ---------------------------------------------------------------------------------

// `mesh` is the clump as drawn (clumpRenderMesh of m).
void writeClump(ByteWriter& w, const ClumpMotion& m, const Mesh& mesh) {
    w.string(m.clump.name);
    w.u32(m.clump.plants);
    std::vector<float> vertexData;
    vertexData.reserve(mesh.vertices.size() * 8);
    for (const gpu::GpuVertex& v : mesh.vertices)
        for (int i = 0; i < 4; ++i)
            vertexData.push_back(v.positionU[i]);
    for (const gpu::GpuVertex& v : mesh.vertices)
        for (int i = 0; i < 4; ++i)
            vertexData.push_back(v.normalV[i]);
    w.f32s(vertexData);
    w.u32s(mesh.indices);
    w.f32(mesh.boundingRadius);

    const MotionBasis& b = m.basis;
    w.u32(b.frames);
    for (uint32_t modes : b.lodModes)
        w.u32(modes);
    w.u32s(b.vertexBlock);
    w.u32(uint32_t(b.blocks.size()));
    for (const MotionBlock& block : b.blocks) {
        w.u32(block.coordOffset);
        for (uint32_t rank : block.ranks)
            w.u32(rank);
    }
    w.f32s(b.basis);
    w.f32s(b.coords);
    w.f32s(std::vector<float>(b.relativeErrorPerMode.begin(), b.relativeErrorPerMode.end()));

    const MotionGraph& g = m.graph;
    w.u32(g.nodeCount);
    w.u32(g.levelCount);
    w.u32(g.edgeCount);
    w.u32(g.blendFrames);
    w.u8s(g.nodeLevel);
    w.u8s(g.nodeAlive);
    w.u32s(g.naturalNext);
    w.u32s(g.edgeStart);
    w.u32s(g.edgeTarget);
    w.u8s(g.edgeIsTransition);
    w.f32s(g.edgeProbability);
    w.u32s(g.edgeWeight);
    w.f32s(g.futureCost);
    w.u32(g.stronglyConnected ? 1 : 0);
    w.u8s(g.levelStronglyConnected);
    w.u32(g.removedNodes);
    w.u32(g.transitionCount);
    w.u32(g.crossLevelTransitionCount);

    w.u32(uint32_t(m.levels.size()));
    for (const LevelStats& s : m.levels) {
        w.f32(s.meanSpeed);
        w.u32(s.frames);
        w.f32(s.maxPenetration);
        w.f32(float(s.maxKineticEnergy));
        w.f32(float(s.kineticEnergyFirstHalf));
        w.f32(float(s.kineticEnergySecondHalf));
        w.f32(float(s.maxAirDivergence));
    }
}

static LibraryClump readClump(ByteReader& r, const std::string& where) {
    auto fail = [&](const std::string& what) -> Error { return Error(where + ": " + what); };
    LibraryClump c;
    c.name = r.string();
    c.plants = r.u32();
    std::vector<float> vertexData = r.f32s();
    if (vertexData.size() % 8 != 0)
        throw fail("clump " + c.name + ": vertex data is not a whole number of vertices");
    size_t vertices = vertexData.size() / 8;
    c.mesh.vertices.resize(vertices);
    for (size_t v = 0; v < vertices; ++v)
        for (int i = 0; i < 4; ++i) {
            c.mesh.vertices[v].positionU[i] = vertexData[v * 4 + size_t(i)];
            c.mesh.vertices[v].normalV[i] = vertexData[vertices * 4 + v * 4 + size_t(i)];
        }
    c.mesh.indices = r.u32s();
    c.mesh.boundingRadius = r.f32();
    if (c.mesh.indices.size() % 3 != 0 || !(c.mesh.boundingRadius > 0.0f) || !std::isfinite(c.mesh.boundingRadius))
        throw fail("clump " + c.name + ": inconsistent mesh");
    for (uint32_t index : c.mesh.indices)
        if (index >= vertices)
            throw fail("clump " + c.name + ": a triangle index is out of range");
    for (float f : vertexData)
        if (!std::isfinite(f))
            throw fail("clump " + c.name + ": a vertex holds a non-finite value");

    MotionBasis& b = c.motion;
    b.frames = r.u32();
    for (uint32_t& modes : b.lodModes)
        modes = r.u32();
    b.vertexBlock = r.u32s();
    const uint32_t blockCount = r.u32();
    if (blockCount > r.remaining() / (4 * (1 + kLodCount)))
        throw fail("clump " + c.name + ": motion block count " + std::to_string(blockCount) + " exceeds the section");
    b.blocks.resize(blockCount);
    for (MotionBlock& block : b.blocks) {
        block.coordOffset = r.u32();
        for (uint32_t& rank : block.ranks)
            rank = r.u32();
    }
    b.basis = r.f32s();
    b.coords = r.f32s();
    std::vector<float> errors = r.f32s();
    b.relativeErrorPerMode.assign(errors.begin(), errors.end());
    if (b.vertexBlock.size() != vertices)
        throw fail("clump " + c.name + ": motion blocks for " + std::to_string(b.vertexBlock.size()) +
                   " vertices, mesh has " + std::to_string(vertices));
    b.finish(where + ": clump " + c.name);

    MotionGraph& g = c.graph;
    g.nodeCount = r.u32();
    g.levelCount = r.u32();
    g.edgeCount = r.u32();
    g.blendFrames = r.u32();
    g.nodeLevel = r.u8s();
    g.nodeAlive = r.u8s();
    g.naturalNext = r.u32s();
    g.edgeStart = r.u32s();
    g.edgeTarget = r.u32s();
    g.edgeIsTransition = r.u8s();
    g.edgeProbability = r.f32s();
    g.edgeWeight = r.u32s();
    g.futureCost = r.f32s();
    g.stronglyConnected = r.u32() != 0;
    g.levelStronglyConnected = r.u8s();
    g.removedNodes = r.u32();
    g.transitionCount = r.u32();
    g.crossLevelTransitionCount = r.u32();
    const size_t n = g.nodeCount, e = g.edgeCount, l = g.levelCount;
    if (n != c.motion.frames || g.nodeLevel.size() != n || g.nodeAlive.size() != n || g.naturalNext.size() != n ||
        g.edgeStart.size() != n + 1 || g.edgeTarget.size() != e || g.edgeIsTransition.size() != e ||
        g.edgeProbability.size() != e || g.edgeWeight.size() != l * e || g.futureCost.size() != l * n ||
        g.levelStronglyConnected.size() != l || g.edgeStart.back() != e)
        throw fail("clump " + c.name + ": motion graph tables have inconsistent sizes");
    for (size_t i = 0; i < n; ++i)
        if (g.edgeStart[i] > g.edgeStart[i + 1])
            throw fail("clump " + c.name + ": motion graph edge offsets are not ordered");
    for (uint32_t target : g.edgeTarget)
        if (target >= n)
            throw fail("clump " + c.name + ": a motion graph edge leads outside the graph");
    // What the run-time step (motion_step.h) indexes with, besides the edges: the level of a node
    // picks a row of weights, and a node's natural successor is played during blends.
    if (l == 0)
        throw fail("clump " + c.name + ": the motion graph has no wind level");
    for (uint8_t level : g.nodeLevel)
        if (level >= l)
            throw fail("clump " + c.name + ": a motion graph node has wind level " + std::to_string(level) + " of " +
                       std::to_string(l));
    for (uint32_t next : g.naturalNext)
        if (next >= n && next != gpu::kMotionNoFrame)
            throw fail("clump " + c.name + ": a motion graph node's natural successor is outside the graph");

    uint32_t levelCount = r.u32();
    if (levelCount != l)
        throw fail("clump " + c.name + ": simulation statistics for " + std::to_string(levelCount) +
                   " levels, graph has " + std::to_string(l));
    for (uint32_t i = 0; i < levelCount; ++i) {
        LevelStats s;
        s.meanSpeed = r.f32();
        s.frames = r.u32();
        s.maxPenetration = r.f32();
        s.maxKineticEnergy = r.f32();
        s.kineticEnergyFirstHalf = r.f32();
        s.kineticEnergySecondHalf = r.f32();
        s.maxAirDivergence = r.f32();
        c.levels.push_back(s);
    }
    return c;
}

// --- light ---------------------------------------------------------------------------------

static void writeAppearance(ByteWriter& w, const AppearanceModel& m) {
    w.f32s(std::vector<float>(m.mean.data(), m.mean.data() + m.mean.size()));
    w.u32(uint32_t(m.basis.cols()));
    // The basis in half floats: its values are of order 1 / sqrt(n) and the Monte-Carlo noise of
    // the bake (several per cent, see ClumpLight) is far above half precision's 0.05 %.
    w.f16s(std::vector<float>(m.basis.data(), m.basis.data() + m.basis.size()));
    // Frame-major: a frame's coordinates are contiguous, as an instance reads them.
    w.u32(uint32_t(m.coords.cols()));
    w.f32s(std::vector<float>(m.coords.data(), m.coords.data() + m.coords.size()));
    w.u32s(m.bakedFrames);
    w.f32s(std::vector<float>(m.relativeErrorPerMode.begin(), m.relativeErrorPerMode.end()));
}

static AppearanceModel readAppearance(ByteReader& r, size_t values, uint32_t frames,
                                      const std::function<Error(const std::string&)>& fail) {
    AppearanceModel m;
    std::vector<float> mean = r.f32s();
    const uint32_t modes = r.u32();
    std::vector<float> basis = r.f16s();
    const uint32_t coordFrames = r.u32();
    std::vector<float> coords = r.f32s();
    m.bakedFrames = r.u32s();
    std::vector<float> errors = r.f32s();
    if (mean.size() != values || basis.size() != values * modes || coordFrames != frames ||
        coords.size() != size_t(modes) * frames || errors.size() < size_t(modes) + 1)
        throw fail("an appearance model has the wrong size");
    for (const std::vector<float>* v : {&mean, &basis, &coords, &errors})
        for (float x : *v)
            if (!std::isfinite(x))
                throw fail("an appearance model holds a non-finite value");
    for (uint32_t f : m.bakedFrames)
        if (f >= frames)
            throw fail("an appearance model names baked frame " + std::to_string(f) + " of " + std::to_string(frames));
    m.mean = Eigen::Map<const Eigen::VectorXf>(mean.data(), Eigen::Index(values));
    m.basis = Eigen::Map<const Eigen::MatrixXf>(basis.data(), Eigen::Index(values), Eigen::Index(modes));
    m.coords = Eigen::Map<const Eigen::MatrixXf>(coords.data(), Eigen::Index(modes), Eigen::Index(frames));
    m.relativeErrorPerMode.assign(errors.begin(), errors.end());
    return m;
}

void writeLight(ByteWriter& w, const ClumpLight& light) {
    w.u32(uint32_t(light.order));
    w.u32s(light.bakedFrames);
    w.u32(light.vertices.valuesPerVertex);
    // Half floats, as the appearance basis: the bake's noise is far above their 0.05 %.
    w.f16s(light.vertices.coefficients);
    w.u32(light.groundResolution);
    w.f32(light.groundSize);
    if (light.groundResolution > 0)
        writeAppearance(w, light.ground);
    for (double figure : {light.vertexNoise, light.groundNoise, light.vertexHeldOutError, light.vertexMeanOnlyError,
                          light.groundHeldOutError, light.vertexIrradianceNoise, light.groundIrradianceNoise})
        w.f32(float(figure));
}

static ClumpLight readLight(ByteReader& r, const LibraryClump& clump, const std::string& where) {
    auto fail = [&](const std::string& what) { return Error(where + ": clump " + clump.name + ": " + what); };
    ClumpLight light;
    light.order = int(r.u32());
    if (light.order < 1 || light.order > sh::kMaxOrder)
        throw fail("SH order " + std::to_string(light.order) + " is out of range");
    const uint32_t coefficients = uint32_t(sh::coefficientCount(light.order));
    light.bakedFrames = r.u32s();
    for (uint32_t f : light.bakedFrames)
        if (f >= clump.motion.frames)
            throw fail("baked frame " + std::to_string(f) + " is beyond the " + std::to_string(clump.motion.frames) +
                       " motion frames");
    VertexAppearance& v = light.vertices;
    v.vertexCount = uint32_t(clump.mesh.vertices.size());
    v.valuesPerVertex = r.u32();
    if (v.valuesPerVertex != transfer::kSideCount * transfer::kChannelCount * coefficients)
        throw fail("vertex transfer has " + std::to_string(v.valuesPerVertex) + " values per vertex");
    v.coefficients = r.f16s();
    if (v.coefficients.size() != size_t(v.vertexCount) * v.valuesPerVertex * 4)
        throw fail("vertex transfer has the wrong size");
    for (float x : v.coefficients)
        if (!std::isfinite(x))
            throw fail("vertex transfer holds a non-finite value");
    light.groundResolution = r.u32();
    light.groundSize = r.f32();
    if (light.groundResolution > 256 || !(light.groundSize >= 0.0f && light.groundSize < 1000.0f))
        throw fail("the ground grid is " + std::to_string(light.groundResolution) + " points wide");
    if (light.groundResolution > 0)
        light.ground = readAppearance(
            r, size_t(light.groundResolution) * light.groundResolution * transfer::kChannelCount * coefficients,
            clump.motion.frames, fail);
    for (double* figure :
         {&light.vertexNoise, &light.groundNoise, &light.vertexHeldOutError, &light.vertexMeanOnlyError,
          &light.groundHeldOutError, &light.vertexIrradianceNoise, &light.groundIrradianceNoise})
        *figure = r.f32();
    return light;
}

// --- levels of detail -----------------------------------------------------------------------

void writeLods(ByteWriter& w, const std::array<ClumpLod, kLodCount>& lods) {
    for (const ClumpLod& lod : lods) {
        w.u32s(lod.vertices);
        w.u32s(lod.indices);
        const LodError& e = lod.error;
        for (const SurfaceDistance* d : {&e.rest, &e.deformed, &e.light, &e.motion}) {
            w.f32(float(d->hausdorff));
            w.f32(float(d->rms));
        }
        w.u32(e.fullSamples);
        w.u32(e.lodSamples);
    }
}

static void readLods(ByteReader& r, LibraryClump& clump, const std::string& where) {
    auto fail = [&](const std::string& what) { return Error(where + ": clump " + clump.name + ": " + what); };
    const size_t meshVertices = clump.mesh.vertices.size();
    for (uint32_t l = 0; l < kLodCount; ++l) {
        ClumpLod& lod = clump.lods[l];
        lod.vertices = r.u32s();
        lod.indices = r.u32s();
        LodError& e = lod.error;
        for (SurfaceDistance* d : {&e.rest, &e.deformed, &e.light, &e.motion}) {
            d->hausdorff = r.f32();
            d->rms = r.f32();
            if (!std::isfinite(d->hausdorff) || !std::isfinite(d->rms))
                throw fail("LOD " + std::to_string(l) + " has a non-finite error");
        }
        e.fullSamples = r.u32();
        e.lodSamples = r.u32();
        if (lod.vertices.empty() || lod.indices.empty() || lod.indices.size() % 3 != 0)
            throw fail("LOD " + std::to_string(l) + " is empty or not a triangle list");
        for (uint32_t v : lod.vertices)
            if (v >= meshVertices)
                throw fail("LOD " + std::to_string(l) + " names vertex " + std::to_string(v) + " of " +
                           std::to_string(meshVertices));
        for (uint32_t i : lod.indices)
            if (i >= lod.vertices.size())
                throw fail("LOD " + std::to_string(l) + " has a triangle index out of range");
    }
}

// --- sky --------------------------------------------------------------------------------------

static void writeVec3(ByteWriter& w, const glm::vec3& v) {
    w.f32(v.x);
    w.f32(v.y);
    w.f32(v.z);
}

static glm::vec3 readVec3(ByteReader& r) {
    glm::vec3 v;
    v.x = r.f32();
    v.y = r.f32();
    v.z = r.f32();
    return v;
}

void writeSky(ByteWriter& w, const sky::SkyDay& day, bool fromMaps) {
    w.u32(uint32_t(day.shOrder));
    w.u32(day.imageWidth);
    w.u32(day.imageHeight);
    w.u32(fromMaps ? 1 : 0);
    w.u32(uint32_t(day.frames.size()));
    for (const sky::SkyFrame& f : day.frames) {
        w.f32(float(f.hours));
        writeVec3(w, f.sunDirection);
        writeVec3(w, f.sunRadiance);
        writeVec3(w, f.sunIrradiance);
        w.f32s(f.sh);
        w.f32s(f.image);
    }
}

static sky::SkyDay readSky(ByteReader& r, const std::string& where, bool& fromMaps) {
    auto fail = [&](const std::string& what) { return Error(where + ": " + what); };
    sky::SkyDay day;
    day.shOrder = int(r.u32());
    day.imageWidth = r.u32();
    day.imageHeight = r.u32();
    const uint32_t source = r.u32();
    const uint32_t frames = r.u32();
    if (day.shOrder < 1 || day.shOrder > sh::kMaxOrder)
        throw fail("SH order " + std::to_string(day.shOrder) + " is out of range");
    if (day.imageWidth == 0 || day.imageWidth > 4096 || day.imageWidth != 2 * day.imageHeight)
        throw fail("the backdrop image is " + std::to_string(day.imageWidth) + " x " + std::to_string(day.imageHeight));
    if (source > 1 || frames == 0 || frames > 4096)
        throw fail("holds " + std::to_string(frames) + " frames of source " + std::to_string(source));
    fromMaps = source == 1;
    const size_t shValues = size_t(sh::coefficientCount(day.shOrder)) * 3;
    const size_t imageValues = size_t(day.imageWidth) * day.imageHeight * 3;
    double previous = -1.0;
    for (uint32_t i = 0; i < frames; ++i) {
        sky::SkyFrame f;
        f.hours = r.f32();
        f.sunDirection = readVec3(r);
        f.sunRadiance = readVec3(r);
        f.sunIrradiance = readVec3(r);
        f.sh = r.f32s(shValues);
        f.image = r.f32s(imageValues);
        if (f.sh.size() != shValues || f.image.size() != imageValues)
            throw fail("frame " + std::to_string(i) + " has the wrong size");
        bool finite = std::isfinite(f.hours);
        for (int c = 0; c < 3; ++c)
            finite = finite && std::isfinite(f.sunDirection[c]) && std::isfinite(f.sunRadiance[c]) &&
                     std::isfinite(f.sunIrradiance[c]);
        for (float v : f.sh)
            finite = finite && std::isfinite(v);
        for (float v : f.image)
            finite = finite && std::isfinite(v) && v >= 0.0f;
        if (!finite)
            throw fail("frame " + std::to_string(i) + " holds a non-finite or negative value");
        if (!(f.hours > previous && f.hours < 24.0))
            throw fail("frame " + std::to_string(i) + " is not in time order within the day");
        previous = f.hours;
        day.frames.push_back(std::move(f));
    }
    r.expectEnd();
    return day;
}

Library loadLibrary(const std::filesystem::path& path) {
    LibraryFile file = readLibraryFile(path);
    const std::string where = "library " + path.string();
    Library lib;
    lib.formatVersion = file.formatVersion;
    lib.inputHash = file.inputHash;
    lib.fileBytes = file.fileBytes;
    for (const auto& [tag, bytes] : file.sections)
        lib.sections.push_back(tag);

    auto section = [&](const char* tag) -> const std::vector<uint8_t>& {
        auto it = file.sections.find(tag);
        if (it == file.sections.end())
            throw Error(where + ": section '" + tag + "' is missing");
        return it->second;
    };
    const std::vector<uint8_t>& sceneBytes = section("SCNE");
    try {
        lib.scene = nlohmann::json::parse(sceneBytes.begin(), sceneBytes.end());
    } catch (const nlohmann::json::exception& e) {
        throw Error(where + ": section 'SCNE' is not valid JSON: " + e.what());
    }
    // The resolved scene as precompute wrote it; what readers of `scene` rely on is checked here.
    const nlohmann::json& scene = lib.scene;
    if (!scene.is_object() || !scene.contains("name") || !scene["name"].is_string() || !scene.contains("seed") ||
        !scene["seed"].is_number_unsigned() ||
        (scene.contains("field") && (!scene["field"].is_object() || (scene["field"].contains("yawJitter") &&
                                                                     !scene["field"]["yawJitter"].is_number()))))
        throw Error(where + ": section 'SCNE' is not a resolved scene (an object with a name, a seed and a field)");

    {
        ByteReader r(section("ATLS"), where + ": section 'ATLS'");
        lib.atlas.width = r.u32();
        lib.atlas.height = r.u32();
        if (lib.atlas.width == 0 || lib.atlas.height == 0 || lib.atlas.width > 16384 || lib.atlas.height > 16384 ||
            uint64_t(lib.atlas.width) * lib.atlas.height * 4 != r.remaining())
            throw Error(where + ": section 'ATLS' has the wrong size for its atlas");
        lib.atlas.rgba.resize(r.remaining());
        r.bytes(lib.atlas.rgba.data(), lib.atlas.rgba.size());
    }
    {
        ByteReader r(section("CLMP"), where + ": section 'CLMP'");
        uint32_t count = r.u32();
        if (count == 0 || count > 64)
            throw Error(where + ": section 'CLMP' holds " + std::to_string(count) + " clumps");
        for (uint32_t i = 0; i < count; ++i)
            lib.clumps.push_back(readClump(r, where + ": section 'CLMP'"));
        r.expectEnd();
    }

    {
        ByteReader r(section("LITE"), where + ": section 'LITE'");
        if (r.u32() != lib.clumps.size())
            throw Error(where + ": section 'LITE' does not hold one entry per clump");
        for (LibraryClump& clump : lib.clumps)
            clump.light = readLight(r, clump, where + ": section 'LITE'");
        r.expectEnd();
    }
    {
        ByteReader r(section("LODS"), where + ": section 'LODS'");
        if (r.u32() != lib.clumps.size())
            throw Error(where + ": section 'LODS' does not hold one entry per clump");
        for (LibraryClump& clump : lib.clumps)
            readLods(r, clump, where + ": section 'LODS'");
        r.expectEnd();
    }
    {
        ByteReader r(section("SKYD"), where + ": section 'SKYD'");
        lib.sky = readSky(r, where + ": section 'SKYD'", lib.skyFromMaps);
    }

    {
        ByteReader r(section("TFLD"), where + ": section 'TFLD'");
        lib.field = readInstances(r, where + ": section 'TFLD'", uint32_t(lib.clumps.size()));
        r.expectEnd();
    }
    {
        ByteReader r(section("ROCK"), where + ": section 'ROCK'");
        readRocks(r, where + ": section 'ROCK'", lib.placement);
    }
    {
        ByteReader r(section("PLCE"), where + ": section 'PLCE'");
        readPlacement(r, where + ": section 'PLCE'", lib.placement);
    }
    return lib;
}

} // namespace meadow
