// The sections of a scene's library that precompute writes and loadLibrary reads (library.h lists
// them): each section's writer beside its reader, so that the two cannot drift apart. The field's
// sections (instances, rocks, placement) are in library_field.h. Kept apart from the stages that
// build a library, so that a program that only loads one (the bench, meadow_bench_runner) links none
// of them.
#pragma once

#include "clump_light.h"
#include "clump_lod.h"
#include "clump_motion.h"
#include "core/library_file.h"
#include "mesh.h"
#include "sky/sky_day.h"

#include <array>

namespace meadow {

// Section CLMP, one clump: `mesh` is the clump as drawn (clumpRenderMesh of m).
void writeClump(ByteWriter& w, const ClumpMotion& m, const Mesh& mesh);
// Section LITE, one clump's light transfer.
void writeLight(ByteWriter& w, const ClumpLight& light);
// Section LODS, one clump's levels of detail.
void writeLods(ByteWriter& w, const std::array<ClumpLod, kLodCount>& lods);
// Section SKYD.
void writeSky(ByteWriter& w, const sky::SkyDay& day, bool fromMaps);

} // namespace meadow
