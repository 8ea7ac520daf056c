#include "io/image_io.h"

#include "core/error.h"

#include <OpenImageIO/imageio.h>
#include <cstdio>
#include <fstream>
#include <unistd.h>

namespace meadow {
namespace {

std::string lowerExtension(const std::filesystem::path& path) {
    std::string ext = path.extension().string();
    for (char& c : ext)
        c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return ext;
}

std::filesystem::path temporaryPath(const std::filesystem::path& path) {
    // Keep the extension so OpenImageIO picks the right format for the temporary file.
    std::filesystem::path tmp = path;
    tmp.replace_filename("." + path.stem().string() + ".partial-" + std::to_string(getpid()) +
                         path.extension().string());
    return tmp;
}

void writeImage(const std::filesystem::path& path, uint32_t width, uint32_t height, OIIO::TypeDesc type,
                const void* pixels) {
    imageKindForPath(path);
    std::filesystem::path tmp = temporaryPath(path);
    auto out = OIIO::ImageOutput::create(tmp.string());
    if (!out)
        throw Error("cannot write image " + path.string() + ": " + OIIO::geterror());
    OIIO::ImageSpec spec(static_cast<int>(width), static_cast<int>(height), 4, type);
    if (type == OIIO::TypeDesc::HALF)
        spec.attribute("compression", "zip");
    spec.attribute("Software", "meadow");
    // meadow's pixels are straight (unassociated) colour with alpha; frames are opaque.
    spec.attribute("oiio:UnassociatedAlpha", 1);
    bool ok = out->open(tmp.string(), spec) && out->write_image(type, pixels) && out->close();
    if (!ok) {
        std::string message = out->geterror();
        out.reset();
        std::error_code ec;
        std::filesystem::remove(tmp, ec);
        throw Error("cannot write image " + path.string() + ": " + message);
    }
    out.reset();
    std::error_code ec;
    std::filesystem::rename(tmp, path, ec);
    if (ec) {
        std::filesystem::remove(tmp, ec);
        throw Error("cannot write image " + path.string() + ": " + ec.message());
    }
}

} // namespace

ImageFileKind imageKindForPath(const std::filesystem::path& path) {
    std::string ext = lowerExtension(path);
    if (ext == ".png")
        return ImageFileKind::Png;
    if (ext == ".exr")
        return ImageFileKind::Exr;
    throw Error("output " + path.string() + ": unsupported image type '" + ext + "' (use .png or .exr)");
}

void writeRgba8(const std::filesystem::path& path, uint32_t width, uint32_t height, std::span<const uint8_t> pixels) {
    if (pixels.size() != size_t(width) * height * 4)
        throw Error("internal: wrong pixel count for " + path.string());
    writeImage(path, width, height, OIIO::TypeDesc::UINT8, pixels.data());
}

void writeRgbaHalf(const std::filesystem::path& path, uint32_t width, uint32_t height,
                   std::span<const uint16_t> pixels) {
    if (pixels.size() != size_t(width) * height * 4)
        throw Error("internal: wrong pixel count for " + path.string());
    writeImage(path, width, height, OIIO::TypeDesc::HALF, pixels.data());
}

std::filesystem::path framePath(const std::filesystem::path& path, uint32_t index, uint32_t count) {
    if (count <= 1)
        return path;
    char number[16];
    std::snprintf(number, sizeof(number), ".%04u", index);
    std::filesystem::path out = path;
    out.replace_filename(path.stem().string() + number + path.extension().string());
    return out;
}

} // namespace meadow
