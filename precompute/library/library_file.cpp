#include "library/library_file.h"

#include "core/error.h"

#include <cstring>
#include <fstream>
#include <glm/gtc/packing.hpp>
#include <unistd.h>

namespace meadow {
namespace {

constexpr char kMagic[8] = {'M', 'E', 'A', 'D', 'O', 'W', 'L', 'B'};
constexpr size_t kHeaderBytes = 8 + 4 + 4 + 8 + 8;
constexpr size_t kEntryBytes = 4 + 4 + 8 + 8 + 8;
constexpr uint32_t kMaxSections = 4096;

uint32_t loadU32(const uint8_t* p) {
    return uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24;
}
uint64_t loadU64(const uint8_t* p) {
    return uint64_t(loadU32(p)) | uint64_t(loadU32(p + 4)) << 32;
}

uint32_t tagValue(const std::string& tag) {
    if (tag.size() != 4)
        throw Error("internal: library section tag '" + tag + "' is not four characters");
    return loadU32(reinterpret_cast<const uint8_t*>(tag.data()));
}

} // namespace

uint64_t fnv1a64(const void* data, size_t size, uint64_t hash) {
    const auto* p = static_cast<const uint8_t*>(data);
    for (size_t i = 0; i < size; ++i) {
        hash ^= p[i];
        hash *= 0x100000001b3ull;
    }
    return hash;
}

void ByteWriter::u32(uint32_t v) {
    for (int i = 0; i < 4; ++i)
        data_.push_back(static_cast<uint8_t>(v >> (8 * i)));
}
void ByteWriter::u64(uint64_t v) {
    u32(static_cast<uint32_t>(v));
    u32(static_cast<uint32_t>(v >> 32));
}
void ByteWriter::f32(float v) {
    uint32_t bits;
    std::memcpy(&bits, &v, 4);
    u32(bits);
}
void ByteWriter::bytes(const void* data, size_t size) {
    const auto* p = static_cast<const uint8_t*>(data);
    data_.insert(data_.end(), p, p + size);
}

void ByteWriter::string(const std::string& s) {
    u32(static_cast<uint32_t>(s.size()));
    bytes(s.data(), s.size());
}
void ByteWriter::u8s(const std::vector<uint8_t>& v) {
    u32(static_cast<uint32_t>(v.size()));
    bytes(v.data(), v.size());
}
void ByteWriter::u32s(const std::vector<uint32_t>& v) {
    u32(static_cast<uint32_t>(v.size()));
    for (uint32_t x : v)
        u32(x);
}
void ByteWriter::f32s(const std::vector<float>& v) {
    u32(static_cast<uint32_t>(v.size()));
    for (float x : v)
        f32(x);
}

void ByteWriter::f16s(const std::vector<float>& v) {
    u32(static_cast<uint32_t>(v.size()));
    for (float x : v) {
        const uint16_t h = glm::packHalf1x16(x);
        const uint8_t b[2] = {uint8_t(h & 0xff), uint8_t(h >> 8)};
        bytes(b, 2);
    }
}

size_t ByteReader::checkedCount(size_t elementSize, size_t maxCount) {
    size_t count = u32();
    if (count > maxCount || count > remaining() / elementSize)
        throw Error(context_ + ": an array of " + std::to_string(count) + " elements at offset " + std::to_string(at_) +
                    " does not fit (corrupt file)");
    return count;
}
std::string ByteReader::string() {
    std::string s(checkedCount(1, 1 << 20), '\0');
    bytes(s.data(), s.size());
    return s;
}
std::vector<uint8_t> ByteReader::u8s(size_t maxCount) {
    std::vector<uint8_t> v(checkedCount(1, maxCount));
    bytes(v.data(), v.size());
    return v;
}
std::vector<uint32_t> ByteReader::u32s(size_t maxCount) {
    std::vector<uint32_t> v(checkedCount(4, maxCount));
    for (uint32_t& x : v)
        x = u32();
    return v;
}
std::vector<float> ByteReader::f32s(size_t maxCount) {
    std::vector<float> v(checkedCount(4, maxCount));
    for (float& x : v)
        x = f32();
    return v;
}

std::vector<float> ByteReader::f16s(size_t maxCount) {
    std::vector<float> v(checkedCount(2, maxCount));
    for (float& x : v) {
        uint8_t b[2];
        bytes(b, 2);
        x = glm::unpackHalf1x16(uint16_t(b[0] | (b[1] << 8)));
    }
    return v;
}

uint32_t ByteReader::u32() {
    uint8_t b[4];
    bytes(b, 4);
    return loadU32(b);
}
uint64_t ByteReader::u64() {
    uint8_t b[8];
    bytes(b, 8);
    return loadU64(b);
}
float ByteReader::f32() {
    uint32_t bits = u32();
    float v;
    std::memcpy(&v, &bits, 4);
    return v;
}
void ByteReader::bytes(void* out, size_t size) {
    if (size > remaining())
        throw Error(context_ + ": truncated (needs " + std::to_string(size) + " more bytes at offset " +
                    std::to_string(at_) + ")");
    if (size == 0)
        return; // `out` may be the null data() of an empty vector, which memcpy must not get
    std::memcpy(out, data_.data() + at_, size);
    at_ += size;
}
void ByteReader::expectEnd() const {
    if (remaining() != 0)
        throw Error(context_ + ": " + std::to_string(remaining()) + " unexpected trailing bytes");
}

void writeLibraryFile(const std::filesystem::path& path, const LibraryFile& library) {
    ByteWriter table;
    std::vector<uint8_t> payload;
    uint64_t offset = kHeaderBytes + kEntryBytes * library.sections.size();
    for (const auto& [tag, bytes] : library.sections) {
        uint64_t padded = (offset + 7) & ~7ull;
        payload.resize(payload.size() + (padded - offset), 0);
        offset = padded;
        table.u32(tagValue(tag));
        table.u32(0);
        table.u64(offset);
        table.u64(bytes.size());
        table.u64(fnv1a64(bytes.data(), bytes.size()));
        payload.insert(payload.end(), bytes.begin(), bytes.end());
        offset += bytes.size();
    }
    std::vector<uint8_t> tableBytes = table.take();
    ByteWriter header;
    header.bytes(kMagic, 8);
    header.u32(library.formatVersion);
    header.u32(static_cast<uint32_t>(library.sections.size()));
    header.u64(library.inputHash);
    header.u64(fnv1a64(tableBytes.data(), tableBytes.size()));
    std::vector<uint8_t> headerBytes = header.take();

    std::filesystem::path tmp = path;
    tmp += ".partial-" + std::to_string(getpid());
    {
        std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
        if (!out)
            throw Error("cannot write library " + path.string() + ": cannot create " + tmp.string());
        out.write(reinterpret_cast<const char*>(headerBytes.data()), std::streamsize(headerBytes.size()));
        out.write(reinterpret_cast<const char*>(tableBytes.data()), std::streamsize(tableBytes.size()));
        out.write(reinterpret_cast<const char*>(payload.data()), std::streamsize(payload.size()));
        out.close();
        if (!out) {
            std::error_code ec;
            std::filesystem::remove(tmp, ec);
            throw Error("cannot write library " + path.string() + ": write failed (disk full?)");
        }
    }
    std::error_code ec;
    std::filesystem::rename(tmp, path, ec);
    if (ec) {
        std::filesystem::remove(tmp, ec);
        throw Error("cannot write library " + path.string() + ": " + ec.message());
    }
}

LibraryFile readLibraryFile(const std::filesystem::path& path) {
    const std::string where = "library " + path.string();
    // A folder opens as a stream too, and a device (/dev/zero) never ends: refuse both before reading.
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec))
        throw Error(where + ": is a folder, not a library file");
    if (std::filesystem::exists(path, ec) && !std::filesystem::is_regular_file(path, ec))
        throw Error(where + ": is not a regular file (a device?)");
    std::ifstream in(path, std::ios::binary);
    if (!in)
        throw Error(where + ": cannot open");
    std::vector<uint8_t> file((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (file.size() < kHeaderBytes)
        throw Error(where + ": too short to be a meadow library (" + std::to_string(file.size()) + " bytes)");
    if (std::memcmp(file.data(), kMagic, 8) != 0)
        throw Error(where + ": not a meadow library (bad magic)");
    LibraryFile lib;
    lib.fileBytes = file.size();
    lib.formatVersion = loadU32(&file[8]);
    if (lib.formatVersion != kLibraryFormatVersion)
        throw Error(where + ": format version " + std::to_string(lib.formatVersion) + ", this meadow reads version " +
                    std::to_string(kLibraryFormatVersion) + " (rebuild it with meadow precompute)");
    uint32_t count = loadU32(&file[12]);
    lib.inputHash = loadU64(&file[16]);
    uint64_t tableChecksum = loadU64(&file[24]);
    if (count > kMaxSections || kHeaderBytes + uint64_t(count) * kEntryBytes > file.size())
        throw Error(where + ": section table is truncated or corrupt (" + std::to_string(count) + " sections)");
    const uint8_t* table = &file[kHeaderBytes];
    if (fnv1a64(table, count * kEntryBytes) != tableChecksum)
        throw Error(where + ": section table checksum mismatch (corrupt file)");
    for (uint32_t i = 0; i < count; ++i) {
        const uint8_t* e = table + i * kEntryBytes;
        std::string tag(reinterpret_cast<const char*>(e), 4);
        uint64_t offset = loadU64(e + 8), size = loadU64(e + 16), checksum = loadU64(e + 24);
        if (offset > file.size() || size > file.size() - offset)
            throw Error(where + ": section '" + tag + "' lies outside the file (truncated?)");
        if (fnv1a64(&file[offset], size) != checksum)
            throw Error(where + ": section '" + tag + "' checksum mismatch (corrupt file)");
        if (!lib.sections
                 .emplace(tag, std::vector<uint8_t>(file.begin() + std::ptrdiff_t(offset),
                                                    file.begin() + std::ptrdiff_t(offset + size)))
                 .second)
            throw Error(where + ": section '" + tag + "' appears twice");
    }
    return lib;
}

bool peekLibraryInputHash(const std::filesystem::path& path, uint64_t& inputHash) {
    std::ifstream in(path, std::ios::binary);
    uint8_t header[kHeaderBytes];
    if (!in.read(reinterpret_cast<char*>(header), kHeaderBytes))
        return false;
    if (std::memcmp(header, kMagic, 8) != 0 || loadU32(header + 8) != kLibraryFormatVersion)
        return false;
    inputHash = loadU64(header + 16);
    return true;
}

} // namespace meadow
