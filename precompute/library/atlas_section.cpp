#include "library/sections.h"

#include "core/error.h"

namespace meadow {

void writeAtlasSection(ByteWriter& w, const Library& library) {
    w.u32(library.atlas.width);
    w.u32(library.atlas.height);
    w.bytes(library.atlas.rgba.data(), library.atlas.rgba.size());
}

void readAtlasSection(ByteReader& r, const std::string& where, Library& library) {
    RgbaImage& atlas = library.atlas;
    atlas.width = r.u32();
    atlas.height = r.u32();
    if (atlas.width == 0 || atlas.height == 0 || atlas.width > 16384 || atlas.height > 16384 ||
        uint64_t(atlas.width) * atlas.height * 4 != r.remaining())
        throw Error(where + " has the wrong size for its atlas");
    atlas.rgba.resize(r.remaining());
    r.bytes(atlas.rgba.data(), atlas.rgba.size());
}

} // namespace meadow
