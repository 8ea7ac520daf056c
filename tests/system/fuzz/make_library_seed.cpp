// Writes a small valid library to seed the library fuzzer: the library of SCENE (the micro scene,
// tests/system/robustness/micro.json) with its atlas cut to one texel, so that every section is there in
// some 40 KB instead of 300 (the atlas is the one section whose size no scene key controls).
//   meadow_fuzz_make_seed SCENE OUT
#include "core/error.h"
#include "library/library_file.h"
#include "pipeline/build_library.h"

#include <cstdio>

int main(int argc, char** argv) {
    using namespace meadow;
    if (argc != 3) {
        std::fprintf(stderr, "usage: meadow_fuzz_make_seed SCENE OUT\n");
        return 2;
    }
    try {
        const std::filesystem::path out = argv[2];
        buildLibrary(loadScene(argv[1], "ci", std::nullopt), out, true);
        LibraryFile file = readLibraryFile(out);
        ByteWriter atlas;
        atlas.u32(1);
        atlas.u32(1);
        const uint8_t texel[4] = {0x80, 0xa0, 0x60, 0xff};
        atlas.bytes(texel, 4);
        file.sections["ATLS"] = atlas.take();
        writeLibraryFile(out, file);
        loadLibrary(out); // still valid
        return 0;
    } catch (const Error& e) {
        std::fprintf(stderr, "meadow_fuzz_make_seed: error: %s\n", e.what());
        return 1;
    }
}
