// libFuzzer target: the library loader (precompute/library/library.h loadLibrary, precompute/library/
// library_file.h). Random bytes would almost never get past the checksums, so before loading, the
// target makes every checksum the input's table can reach right (the section checksums, then the
// table's): the fuzzer then explores the sections' contents, which is where the loader's decoding
// is. Checksum mismatches themselves are covered by the corpus (tests/system/robustness).
//
// A library that loads must also be safe to use: the target walks every clump's motion graph with
// the run-time step and evaluates its motion basis, as the renderer's CPU reference would, so an
// inconsistency the loader let through shows as an out-of-bounds access under AddressSanitizer.
#include "core/error.h"
#include "fuzz_input.h"
#include "library/library.h"
#include "library/library_file.h"

#include <cstring>
#include <vector>

namespace {

uint64_t load64(const uint8_t* p) {
    uint64_t v = 0;
    for (int i = 7; i >= 0; --i)
        v = (v << 8) | p[i];
    return v;
}
void store64(uint8_t* p, uint64_t v) {
    for (int i = 0; i < 8; ++i)
        p[i] = uint8_t(v >> (8 * i));
}

// The container's layout (library/library_file.h): a 32-byte header, then 32-byte table entries.
void fixChecksums(std::vector<uint8_t>& file) {
    constexpr size_t kHeader = 32, kEntry = 32;
    if (file.size() < kHeader)
        return;
    const uint32_t count =
        uint32_t(file[12]) | uint32_t(file[13]) << 8 | uint32_t(file[14]) << 16 | uint32_t(file[15]) << 24;
    if (count > (file.size() - kHeader) / kEntry)
        return;
    for (uint32_t i = 0; i < count; ++i) {
        uint8_t* entry = &file[kHeader + i * kEntry];
        const uint64_t offset = load64(entry + 8), size = load64(entry + 16);
        if (offset <= file.size() && size <= file.size() - offset)
            store64(entry + 24, meadow::fnv1a64(file.data() + offset, size));
    }
    store64(&file[24], meadow::fnv1a64(&file[kHeader], size_t(count) * kEntry));
}

void use(const meadow::Library& library) {
    using namespace meadow;
    volatile float sink = 0.0f;
    for (const LibraryClump& clump : library.clumps) {
        const MotionBasis& motion = clump.motion;
        for (uint32_t lod = 0; lod < kLodCount; ++lod)
            for (uint32_t v = 0; v < clump.mesh.vertices.size() && v < 64; ++v)
                for (uint32_t frame = 0; frame < motion.frames && frame < 8; ++frame)
                    sink = sink + motion.displacement(v, frame, lod).x;
        const MotionGraph& graph = clump.graph;
        if (graph.nodeCount == 0)
            continue;
        gpu::GpuMotionState state;
        try {
            state = initialMotionState(graph, 7);
        } catch (const Error&) {
            continue; // no live frame: the renderer refuses such a clump the same way
        }
        const gpu::MotionTables tables = makeMotionTables(graph);
        for (uint32_t step = 0; step < 256; ++step)
            gpu::motionStep(tables, state, step % (graph.levelCount + 1), 7);
        sink = sink + float(state.frame);
        for (const ClumpLod& lod : clump.lods)
            for (uint32_t index : lod.indices)
                sink = sink + clump.mesh.vertices[lod.vertices[index]].positionU[0];
    }
    for (const gpu::GpuInstance& instance : library.field.clumpInstances)
        sink = sink + library.clumps[instance.mesh].mesh.boundingRadius;
    (void)sink;
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    std::vector<uint8_t> file(data, data + size);
    fixChecksums(file);
    const std::filesystem::path path = meadow::fuzz::writeInput("library.mlib", file.data(), file.size());
    try {
        use(meadow::loadLibrary(path));
    } catch (const meadow::Error&) {
    }
    return 0;
}
