// The library container: one binary file per scene (docs/ARCHITECTURE.md, The library).
//
// Layout, all integers little-endian whatever the machine:
//   header   magic "MEADOWLB" (8 bytes), u32 formatVersion, u32 sectionCount, u64 inputHash,
//            u64 tableChecksum (FNV-1a 64 of the section table)
//   table    sectionCount x { u32 tag (four characters), u32 reserved (0), u64 offset, u64 size,
//            u64 checksum (FNV-1a 64 of the section's bytes) }
//   payload  the sections' bytes, each starting on an 8-byte boundary
// `inputHash` identifies what the library was built from (scene, preset, seed, format), so a
// cache can tell a stale library from a current one without decoding it.
// Reading validates everything and throws meadow::Error naming the file and the problem.
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace meadow {

inline constexpr uint32_t kLibraryFormatVersion = 9;

uint64_t fnv1a64(const void* data, size_t size, uint64_t seed = 0xcbf29ce484222325ull);

struct LibraryFile {
    uint32_t formatVersion = kLibraryFormatVersion;
    uint64_t inputHash = 0;
    std::map<std::string, std::vector<uint8_t>> sections; // tag (4 characters) -> bytes
    uint64_t fileBytes = 0;                               // set by readLibraryFile
};

// Writes atomically: a temporary file beside `path`, renamed into place when complete.
void writeLibraryFile(const std::filesystem::path& path, const LibraryFile& library);
LibraryFile readLibraryFile(const std::filesystem::path& path);
// Only the header's input hash, or nothing if the file is missing or not a library.
bool peekLibraryInputHash(const std::filesystem::path& path, uint64_t& inputHash);

// Little-endian encoding of plain values into section bytes, and decoding with bounds checks.
class ByteWriter {
  public:
    void u32(uint32_t v);
    void u64(uint64_t v);
    void f32(float v);
    void bytes(const void* data, size_t size);
    void string(const std::string& s);
    // A u32 count, then the elements.
    void u8s(const std::vector<uint8_t>& v);
    void u32s(const std::vector<uint32_t>& v);
    void f32s(const std::vector<float>& v);
    // Stored as IEEE half floats (about 3 significant digits): for bulk data whose own error is
    // far larger, such as Monte-Carlo light transfer. Values must be finite and within +-65504.
    void f16s(const std::vector<float>& v);
    std::vector<uint8_t> take() { return std::move(data_); }

  private:
    std::vector<uint8_t> data_;
};

class ByteReader {
  public:
    ByteReader(const std::vector<uint8_t>& data, std::string context) : data_(data), context_(std::move(context)) {}
    uint32_t u32();
    uint64_t u64();
    float f32();
    void bytes(void* out, size_t size);
    std::string string();
    // A u32 count, then the elements; throws if the count exceeds `maxCount` or the data left.
    std::vector<uint8_t> u8s(size_t maxCount = ~size_t(0));
    std::vector<uint32_t> u32s(size_t maxCount = ~size_t(0));
    std::vector<float> f32s(size_t maxCount = ~size_t(0));
    std::vector<float> f16s(size_t maxCount = ~size_t(0));
    size_t remaining() const { return data_.size() - at_; }
    // Throws unless every byte was consumed.
    void expectEnd() const;

  private:
    size_t checkedCount(size_t elementSize, size_t maxCount);
    const std::vector<uint8_t>& data_;
    std::string context_;
    size_t at_ = 0;
};

} // namespace meadow
