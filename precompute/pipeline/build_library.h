// The precompute's run: a scene in, its library out (library/library.h), through every stage in
// the order of the data flow (docs/ARCHITECTURE.md): sky, plants, motion, light, levels of detail,
// placement, rocks. And the cache of built libraries, one file per scene, preset and inputs.
#pragma once

#include "library/library.h"
#include "scene/scene.h"

#include <cstdint>
#include <filesystem>

namespace meadow {

// What the library of `scene` would be built from, hashed: scene, preset, seed, format, and the
// bytes of the files it imports.
uint64_t libraryInputHash(const Scene& scene);

// Builds the library of `scene` in memory. Progress goes to stderr unless `quiet`. Deterministic.
Library buildLibrary(const Scene& scene, bool quiet = false);

// Builds the library of `scene` and writes it to `path` (atomically).
void buildLibrary(const Scene& scene, const std::filesystem::path& path, bool quiet = false);

// Where the library of `scene` is cached: $MEADOW_CACHE_DIR, else $XDG_CACHE_HOME/meadow, else
// ~/.cache/meadow; the file name holds the scene name, preset and input hash.
std::filesystem::path cachedLibraryPath(const Scene& scene);

// The cached library of `scene`, built first if missing, stale or corrupt (never trusted).
Library ensureLibrary(const Scene& scene, bool quiet = false);

// The cached library of `scene` as it is: throws meadow::Error naming the path and the command that
// builds it when there is none, or when it was built from other inputs. For programs that run
// libraries but cannot build them (the bench runner); everything else calls ensureLibrary.
Library loadCachedLibrary(const Scene& scene);

} // namespace meadow
