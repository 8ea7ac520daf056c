// meadow sheet: an image sheet of one clump's recorded motion, one row per wind level, so a person
// can judge the motion library at a glance.
#include "app/commands.h"
#include "app/session.h"
#include "core/error.h"
#include "io/image_io.h"
#include "library/clump.h"
#include "render/offscreen.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace meadow {
namespace {

const char* kSheetHelp = R"(usage: meadow sheet SCENE --out FILE.png [options]

Renders one clump of SCENE's library at evenly spaced frames of its recorded motion: one row per
wind level (calm at the top), one column per frame, seen from the side so that the wind blows
from left to right. The clump is reconstructed from its motion basis (mean + U q at LOD0).

With --lods: the clump at each of its five levels of detail instead (columns LOD 0 .. 4), at one
frame of the strongest wind, each LOD with its own motion modes; the second row shows each LOD's
difference from LOD 0, four times amplified.

options:
  --out FILE.png        the sheet
  --lods                levels of detail side by side, and their differences
  --clump K             which clump (default 0)
  --columns N           frames per level (default 6)
  --cell WxH            size of one cell (default 240x240)
  --preset, --seed, --device, --validation, --verbose   as for meadow render
)";

} // namespace

int runSheet(const Args& argv) {
    if (printHelpIfAsked(argv, kSheetHelp))
        return 0;
    CommandSpec spec{"sheet", {"SCENE"}, {"--out", "--clump", "--columns", "--cell"}, {"--lods"}};
    addSceneOptions(spec);
    addEngineOptions(spec);
    ParsedArgs args = parseArgs(spec, argv);
    if (!args.has("--out"))
        throw Error("meadow sheet: --out FILE.png is required");
    std::filesystem::path out = *args.value("--out");
    if (imageKindForPath(out) != ImageFileKind::Png)
        throw Error("meadow sheet: --out " + out.string() + ": sheets are PNG");
    checkOutputWritable(out);
    uint32_t columns = args.u32("--columns", 6, 1, 64);
    auto [cellW, cellH] = args.size("--cell", {240, 240});
    Scene scene = sceneFromArgs(args);
    Library library = ensureLibrary(scene);
    uint32_t clumpIndex = args.u32("--clump", 0, 0, 1000);
    if (clumpIndex >= library.clumps.size())
        throw Error("meadow sheet: --clump " + std::to_string(clumpIndex) + ": the library has " +
                    std::to_string(library.clumps.size()) + " clumps");
    const LibraryClump& clump = library.clumps[clumpIndex];
    const uint32_t levels = clump.graph.levelCount;

    // Frames of each level, in order (clips are consecutive per level).
    std::vector<std::vector<uint32_t>> levelFrames(levels);
    for (uint32_t f = 0; f < clump.motion.frames; ++f)
        levelFrames[clump.graph.nodeLevel[f]].push_back(f);

    Context ctx;
    createContext(ctx, contextOptionsFromArgs(args));
    gpu::GpuInstance one{};
    one.positionScale = glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
    one.boundingRadius = clump.mesh.boundingRadius * 1.5f; // room for the swaying
    FieldScenery scenery{makeTerrainMesh(TerrainParams{0.0f}, glm::vec2(2.0f), 2.0f, 0.5f),
                         library.field.windDirection};
    scenery.sky = library.sky;
    // Side view: the wind blows across the picture, left to right.
    glm::vec3 wind = scene.wind.direction;
    glm::vec3 side = glm::normalize(glm::cross(wind, glm::vec3(0.0f, 1.0f, 0.0f)));
    Camera camera;
    camera.target = glm::vec3(0.0f, 0.42f, 0.0f);
    camera.eye = camera.target + side * 1.7f + glm::vec3(0.0f, 0.2f, 0.0f);
    camera.fovYDegrees = 38.0f;
    FrameState state;
    state.camera = camera;
    state.width = cellW;
    state.height = cellH;
    state.hours = scene.timeOfDay;
    auto place = [&](std::vector<uint8_t>& sheet, uint32_t sheetColumns, uint32_t row, uint32_t column,
                     const std::vector<uint8_t>& pixels) {
        for (uint32_t y = 0; y < cellH; ++y)
            std::memcpy(&sheet[((size_t(row) * cellH + y) * sheetColumns * cellW + size_t(column) * cellW) * 4],
                        &pixels[size_t(y) * cellW * 4], size_t(cellW) * 4);
    };

    if (args.has("--lods")) {
        // One frame of the strongest wind, two thirds into its clip.
        const uint32_t frame = levelFrames[levels - 1][levelFrames[levels - 1].size() * 2 / 3];
        std::vector<uint8_t> sheet(size_t(cellW) * kLodCount * cellH * 2 * 4, 0);
        std::vector<uint8_t> full;
        for (uint32_t l = 0; l < kLodCount; ++l) {
            FieldRenderer renderer =
                createFieldRenderer(ctx,
                                    std::vector<FieldClump>{staticFieldClump(
                                        lodMeshAtFrame(clump.mesh, clump.motion, clump.lods[l], l, frame), 1)},
                                    std::vector<gpu::GpuInstance>{one}, library.atlas, scenery);
            Offscreen offscreen = createOffscreen(ctx, {cellW, cellH});
            renderOffscreenFrame(ctx, renderer, offscreen, state);
            std::vector<uint8_t> pixels = readLdrPixels(ctx, offscreen.targets);
            destroyOffscreen(ctx, offscreen);
            destroyFieldRenderer(ctx, renderer);
            if (l == 0)
                full = pixels;
            std::vector<uint8_t> difference(pixels.size(), 255);
            for (size_t i = 0; i < pixels.size(); ++i)
                if (i % 4 != 3)
                    difference[i] = uint8_t(std::min(255, 4 * std::abs(int(pixels[i]) - int(full[i]))));
            place(sheet, kLodCount, 0, l, pixels);
            place(sheet, kLodCount, 1, l, difference);
        }
        int status = validationExitStatus(ctx);
        destroyContext(ctx);
        writeRgba8(out, cellW * kLodCount, cellH * 2, sheet);
        std::fprintf(stderr, "meadow: LOD sheet of clump %s (frame %u) written to %s\n", clump.name.c_str(), frame,
                     out.string().c_str());
        return status;
    }

    std::vector<uint8_t> sheet(size_t(cellW) * columns * cellH * levels * 4, 0);
    {
        FieldRenderer renderer = createFieldRenderer(ctx, std::vector<FieldClump>{staticFieldClump(clump.mesh, 1)},
                                                     std::vector<gpu::GpuInstance>{one}, library.atlas, scenery);
        Offscreen offscreen = createOffscreen(ctx, {cellW, cellH});
        for (uint32_t level = 0; level < levels; ++level) {
            const std::vector<uint32_t>& frames = levelFrames[level];
            for (uint32_t c = 0; c < columns && !frames.empty(); ++c) {
                uint32_t frame = frames[size_t(c) * frames.size() / columns];
                // The posed mesh over the renderer's (static) clump vertices.
                Mesh posed = meshAtFrame(clump.mesh, clump.motion, frame);
                // (A static clump of one LOD: its LOD vertices are the mesh's, in order.)
                std::vector<gpu::GpuLodVertex> vertices(posed.vertices.size());
                for (uint32_t v = 0; v < vertices.size(); ++v)
                    vertices[v] = {posed.vertices[v].positionU, posed.vertices[v].normalV, gpu::uvec4(0u, 0u, v, 0u)};
                uploadToBuffer(ctx, renderer.lodVertices, vertices.data(), vertices.size() * sizeof(gpu::GpuLodVertex));
                renderOffscreenFrame(ctx, renderer, offscreen, state);
                place(sheet, columns, level, c, readLdrPixels(ctx, offscreen.targets));
            }
        }
        destroyOffscreen(ctx, offscreen);
        destroyFieldRenderer(ctx, renderer);
    }
    int status = validationExitStatus(ctx);
    destroyContext(ctx);
    writeRgba8(out, cellW * columns, cellH * levels, sheet);
    std::fprintf(stderr, "meadow: motion sheet of clump %s (%u levels x %u frames) written to %s\n", clump.name.c_str(),
                 levels, columns, out.string().c_str());
    return status;
}

} // namespace meadow
