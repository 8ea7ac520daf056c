// The sections of a library (library.h lists them), internal to meadow_library: each section's
// writer beside its reader in one file, so that the two cannot drift apart. A reader checks what
// it reads and throws meadow::Error starting with `where` (the file and the section); readers run
// in the order of kSections (library.cpp), so a reader may rely on the sections before it.
#pragma once

#include "library/library.h"
#include "library/library_file.h"

#include <string>
#include <vector>

namespace meadow {

void writeSceneSection(ByteWriter& w, const Library& library); // SCNE
void readSceneSection(ByteReader& r, const std::string& where, Library& library);
void writeAtlasSection(ByteWriter& w, const Library& library); // ATLS
void readAtlasSection(ByteReader& r, const std::string& where, Library& library);
void writeClumpSection(ByteWriter& w, const Library& library); // CLMP
void readClumpSection(ByteReader& r, const std::string& where, Library& library);
void writeLightSection(ByteWriter& w, const Library& library); // LITE, after CLMP
void readLightSection(ByteReader& r, const std::string& where, Library& library);
void writeLodSection(ByteWriter& w, const Library& library); // LODS, after CLMP
void readLodSection(ByteReader& r, const std::string& where, Library& library);
void writeSkySection(ByteWriter& w, const Library& library); // SKYD
void readSkySection(ByteReader& r, const std::string& where, Library& library);
void writeInstanceSection(ByteWriter& w, const Library& library); // TFLD, after CLMP
void readInstanceSection(ByteReader& r, const std::string& where, Library& library);
void writeRockSection(ByteWriter& w, const Library& library); // ROCK
void readRockSection(ByteReader& r, const std::string& where, Library& library);
void writePlacementSection(ByteWriter& w, const Library& library); // PLCE
void readPlacementSection(ByteReader& r, const std::string& where, Library& library);
void writeFarSamplesSection(ByteWriter& w, const Library& library); // FARS, after CLMP and ROCK
void readFarSamplesSection(ByteReader& r, const std::string& where, Library& library);

// Instances (TFLD, and the rocks' in ROCK): position and scale (w, -1 when mirrored), yaw,
// bounding radius, mesh (28 bytes each). The reader checks every value is finite, |scale| is 1 and
// mesh < meshCount.
void writeInstances(ByteWriter& w, const std::vector<gpu::GpuInstance>& instances);
std::vector<gpu::GpuInstance> readInstances(ByteReader& r, const std::string& where, uint32_t meshCount);

} // namespace meadow
