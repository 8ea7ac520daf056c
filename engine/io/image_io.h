// Writing frames to disk through OpenImageIO. Files appear whole or not at all: pixels go to a
// temporary file beside the target, which is renamed into place once complete.
#pragma once

#include "io/output_path.h"

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>

namespace meadow {

enum class ImageFileKind { Png, Exr };

// The kind an output path asks for, by extension (.png or .exr, any case). Throws meadow::Error
// naming the path for anything else.
ImageFileKind imageKindForPath(const std::filesystem::path& path);

void writeRgba8(const std::filesystem::path& path, uint32_t width, uint32_t height, std::span<const uint8_t> pixels);
void writeRgbaHalf(const std::filesystem::path& path, uint32_t width, uint32_t height,
                   std::span<const uint16_t> pixels);

// Output path of frame `index` of `count`: the path itself for a single frame, otherwise the
// index inserted before the extension ("out.png" -> "out.0003.png").
std::filesystem::path framePath(const std::filesystem::path& path, uint32_t index, uint32_t count);

} // namespace meadow
