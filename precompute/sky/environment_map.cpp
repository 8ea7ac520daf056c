// HDR environment maps in place of the analytic sky (sky/environment_map.h).
#include "sky/environment_map.h"

#include "core/error.h"
#include "light/latlong.h"
#include "sky/sun.h"

#include <OpenImageIO/imageio.h>
#include <tbb/parallel_for.h>

#include <cassert>
#include <cmath>
#include <sstream>

namespace meadow::sky {
namespace {

[[noreturn]] void fail(const std::filesystem::path& path, const std::string& problem) {
    throw Error("sky map " + path.string() + ": " + problem);
}

std::string number(double value) {
    std::ostringstream out;
    out << value;
    return out.str();
}

} // namespace

EnvironmentMap loadEnvironmentMap(const std::filesystem::path& path) {
    std::error_code ec;
    if (!std::filesystem::exists(path, ec))
        fail(path, "no such file");
    if (std::filesystem::is_directory(path, ec))
        fail(path, "is a folder, not an image");
    if (!std::filesystem::is_regular_file(path, ec))
        fail(path, "is not a regular file (a device or a pipe?), not an image");
    auto in = OIIO::ImageInput::open(path.string());
    if (!in) {
        std::string message = OIIO::geterror();
        fail(path, "cannot read it as an image (" + (message.empty() ? std::string("unknown format") : message) + ")");
    }
    const OIIO::ImageSpec& spec = in->spec();
    if (spec.width < 1 || spec.height < 1 || spec.depth > 1)
        fail(path, "has no pixels, or is a volume (" + std::to_string(spec.width) + " x " +
                       std::to_string(spec.height) + " x " + std::to_string(spec.depth) + ")");
    if (spec.width != 2 * spec.height)
        fail(path, std::to_string(spec.width) + " x " + std::to_string(spec.height) +
                       " is not a 2:1 latitude-longitude panorama");
    // 16K panoramas are the largest in common use; a header claiming more is refused before its
    // pixels are allocated (a few bytes of header could otherwise ask for terabytes).
    if (spec.width > int(kMaxEnvironmentMapWidth))
        fail(path, std::to_string(spec.width) + " x " + std::to_string(spec.height) +
                       " is larger than meadow reads (at most " + std::to_string(kMaxEnvironmentMapWidth) + " x " +
                       std::to_string(kMaxEnvironmentMapWidth / 2) + ")");
    if (spec.nchannels < 3)
        fail(path, "has " + std::to_string(spec.nchannels) + " channel(s); an RGB panorama needs at least 3");

    EnvironmentMap map;
    map.path = path;
    map.width = uint32_t(spec.width);
    map.height = uint32_t(spec.height);
    map.rgb.resize(size_t(map.width) * map.height * 3);
    // Channels 0-2 as float, whatever the file stores (half, float, RGBE, integers).
    if (!in->read_image(0, 0, 0, 3, OIIO::TypeDesc::FLOAT, map.rgb.data())) {
        const std::string message = in->geterror();
        fail(path, "cannot read its pixels (" + message + ")");
    }
    in->close();

    for (size_t k = 0; k < map.rgb.size(); ++k) {
        const float value = map.rgb[k];
        if (std::isfinite(value) && value >= 0.0f)
            continue;
        const size_t texel = k / 3;
        const std::string where = "texel (" + std::to_string(texel % map.width) + ", " +
                                  std::to_string(texel / map.width) + ") channel " + std::to_string(k % 3);
        fail(path, where +
                       (std::isfinite(value) ? " is negative (" + number(value) + ")"
                                             : " is not finite (" + number(value) + ")") +
                       "; radiance must be finite and >= 0");
    }
    return map;
}

std::vector<float> resampleLatLong(uint32_t srcWidth, uint32_t srcHeight, std::span<const float> src, uint32_t dstWidth,
                                   uint32_t dstHeight) {
    assert(srcWidth >= 1 && srcHeight >= 1 && dstWidth >= 1 && dstHeight >= 1);
    assert(src.size() == size_t(srcWidth) * srcHeight * 3);
    std::vector<float> dst(size_t(dstWidth) * dstHeight * 3);
    const double columnsPerPixel = double(srcWidth) / double(dstWidth);
    const double rowsPerPixel = double(srcHeight) / double(dstHeight);
    tbb::parallel_for(uint32_t(0), dstHeight, [&](uint32_t j) {
        const double v0 = double(j) * rowsPerPixel, v1 = double(j + 1) * rowsPerPixel;
        const uint32_t rowBegin = uint32_t(std::floor(v0));
        const uint32_t rowEnd = std::min(srcHeight, uint32_t(std::ceil(v1)));
        for (uint32_t i = 0; i < dstWidth; ++i) {
            const double u0 = double(i) * columnsPerPixel, u1 = double(i + 1) * columnsPerPixel;
            const uint32_t columnBegin = uint32_t(std::floor(u0));
            const uint32_t columnEnd = std::min(srcWidth, uint32_t(std::ceil(u1)));
            glm::dvec3 sum(0.0);
            double total = 0.0;
            for (uint32_t k = rowBegin; k < rowEnd; ++k) {
                // The overlapped part of source row k, as a solid angle per unit azimuth.
                const double a = std::max(v0, double(k)), b = std::min(v1, double(k + 1));
                if (b <= a)
                    continue;
                const double rowWeight =
                    std::cos(M_PI * a / double(srcHeight)) - std::cos(M_PI * b / double(srcHeight));
                for (uint32_t c = columnBegin; c < columnEnd; ++c) {
                    const double overlap = std::min(u1, double(c + 1)) - std::max(u0, double(c));
                    if (overlap <= 0.0)
                        continue;
                    const float* texel = &src[(size_t(k) * srcWidth + c) * 3];
                    const double w = rowWeight * overlap;
                    sum += glm::dvec3(texel[0], texel[1], texel[2]) * w;
                    total += w;
                }
            }
            // Every footprint overlaps at least one source pixel with positive solid angle.
            assert(total > 0.0);
            for (int ch = 0; ch < 3; ++ch)
                dst[(size_t(j) * dstWidth + i) * 3 + size_t(ch)] = float(sum[ch] / total);
        }
    });
    return dst;
}

SkyFrame environmentFrame(const EnvironmentMap& map, double hours, int shOrder, uint32_t imageWidth,
                          uint32_t imageHeight) {
    SkyFrame frame;
    frame.hours = hours;
    const std::vector<glm::dvec3> coefficients = sh::projectLatLong(shOrder, map.width, map.height, map.rgb);
    frame.sh.resize(coefficients.size() * 3);
    for (size_t i = 0; i < coefficients.size(); ++i)
        for (int ch = 0; ch < 3; ++ch)
            frame.sh[i * 3 + size_t(ch)] = float(coefficients[i][ch]);
    frame.image = resampleLatLong(map.width, map.height, map.rgb, imageWidth, imageHeight);

    // Band 1 is (Y1-1, Y10, Y11) ∝ (x, y, z): its luminance vector points at the dominant light.
    frame.sunDirection = glm::vec3(0.0f, 1.0f, 0.0f);
    if (shOrder >= 2) {
        const glm::dvec3 dominant(luminance(coefficients[1]), luminance(coefficients[2]), luminance(coefficients[3]));
        const double length = glm::length(dominant);
        if (length > 1e-9 * std::abs(luminance(coefficients[0])) && length > 0.0)
            frame.sunDirection = glm::vec3(dominant / length);
    }
    return frame;
}

SkyDay buildEnvironmentDay(std::span<const std::filesystem::path> files, const SkyParams& params) {
    if (files.empty())
        throw Error("sky maps: the list of environment maps is empty");
    SkyParams checked = params;
    checked.frames = uint32_t(files.size());
    validateSkyParams(checked);
    SkyDay day;
    day.shOrder = params.shOrder;
    day.imageWidth = params.imageWidth;
    day.imageHeight = params.imageHeight;
    day.frames.reserve(files.size());
    for (size_t i = 0; i < files.size(); ++i) {
        const EnvironmentMap map = loadEnvironmentMap(files[i]);
        day.frames.push_back(environmentFrame(map, 24.0 * double(i) / double(files.size()), params.shOrder,
                                              params.imageWidth, params.imageHeight));
    }
    return day;
}

} // namespace meadow::sky
