#include "library/library.h"

#include "core/error.h"
#include "library/sections.h"

namespace meadow {
namespace {

struct SectionCodec {
    const char* tag;
    void (*write)(ByteWriter&, const Library&);
    void (*read)(ByteReader&, const std::string&, Library&);
};

// In reading order: a section's reader may rely on those before it (the clumps first).
constexpr SectionCodec kSections[] = {
    {"SCNE", writeSceneSection, readSceneSection},
    {"ATLS", writeAtlasSection, readAtlasSection},
    {"CLMP", writeClumpSection, readClumpSection},
    {"LITE", writeLightSection, readLightSection},
    {"LODS", writeLodSection, readLodSection},
    {"SKYD", writeSkySection, readSkySection},
    {"TFLD", writeInstanceSection, readInstanceSection},
    {"ROCK", writeRockSection, readRockSection},
    {"PLCE", writePlacementSection, readPlacementSection},
    {"FARS", writeFarSamplesSection, readFarSamplesSection},
};

} // namespace

Library loadLibrary(const std::filesystem::path& path) {
    LibraryFile file = readLibraryFile(path);
    const std::string where = "library " + path.string();
    Library library;
    library.formatVersion = file.formatVersion;
    library.inputHash = file.inputHash;
    library.fileBytes = file.fileBytes;
    for (const auto& [tag, bytes] : file.sections)
        library.sections.push_back(tag);
    for (const SectionCodec& section : kSections) {
        auto it = file.sections.find(section.tag);
        if (it == file.sections.end())
            throw Error(where + ": section '" + section.tag + "' is missing");
        const std::string sectionWhere = where + ": section '" + section.tag + "'";
        ByteReader r(it->second, sectionWhere);
        section.read(r, sectionWhere, library);
    }
    return library;
}

void writeLibrary(const std::filesystem::path& path, const Library& library, uint64_t inputHash) {
    LibraryFile file;
    file.inputHash = inputHash;
    for (const SectionCodec& section : kSections) {
        ByteWriter w;
        section.write(w, library);
        file.sections[section.tag] = w.take();
    }
    writeLibraryFile(path, file);
}

} // namespace meadow
