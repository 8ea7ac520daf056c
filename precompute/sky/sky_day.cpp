// A day of analytic sky frames, each projected to SH and rendered into a small lat-long image
// (sky/sky_day.h).
#include "sky/sky_day.h"

#include "core/error.h"
#include "light/latlong.h"
#include "sky/sun.h"

#include <tbb/parallel_for.h>

#include <cassert>
#include <cmath>
#include <sstream>

namespace meadow::sky {
namespace {

std::string number(double value) {
    std::ostringstream out;
    out << value;
    return out.str();
}

// What every frame of one SkyParams shares: quadrature nodes with their basis values, the SH
// integral of the (constant) ground, and the sub-pixel directions of the image.
struct FrameTables {
    int order = 0;
    int count = 0;                       // coefficientCount(order)
    std::vector<sh::SphereSample> upper; // the sky's hemisphere
    std::vector<double> upperBasis;      // upper.size() x count
    std::vector<double> lowerIntegral;   // ∫_{y<0} Y_i dω
    uint32_t width = 0, height = 0;
    std::vector<glm::dvec3> pixelDirections; // 4 per pixel, row-major
};

// The sky's SH come from its analytic radiance, not from the small image: 24 Gauss–Legendre
// nodes in cos(theta) over the upper hemisphere x 48 azimuths. Splitting the sphere at the
// horizon keeps the rule from straddling the sky/ground jump, and the smooth Perez distribution
// then converges to well below 0.1 % of c00 at order <= 8 (tests/precompute/sky compare it with the image).
constexpr int kUpperNodes = 24, kUpperAzimuths = 48;

FrameTables makeTables(const SkyParams& params) {
    FrameTables t;
    t.order = params.shOrder;
    t.count = sh::coefficientCount(t.order);
    t.upper = sh::quadratureSamples(kUpperNodes, kUpperAzimuths, 0.0, 1.0);
    t.upperBasis.resize(t.upper.size() * size_t(t.count));
    for (size_t k = 0; k < t.upper.size(); ++k)
        sh::evaluate(t.order, t.upper[k].direction, &t.upperBasis[k * size_t(t.count)]);
    // The ground is constant: its coefficients are its radiance times ∫_{y<0} Y, which an
    // order + 1 node rule integrates exactly (Y is a polynomial of degree < order).
    t.lowerIntegral = sh::project(t.order, sh::quadratureSamples(t.order + 1, 2 * t.order + 1, -1.0, 0.0),
                                  [](const glm::dvec3&) { return 1.0; });

    // Image pixels: the mean over each pixel's footprint by a 2 x 2 Gauss–Legendre rule in
    // (cos theta, azimuth), whose four weights within a pixel are equal.
    t.width = params.imageWidth;
    t.height = params.imageHeight;
    t.pixelDirections.resize(size_t(t.width) * t.height * 4);
    const double offset = 1.0 / std::sqrt(3.0);
    for (uint32_t j = 0; j < t.height; ++j) {
        const double top = latLongRowTopCosine(j, t.height), bottom = latLongRowTopCosine(j + 1, t.height);
        for (uint32_t i = 0; i < t.width; ++i)
            for (int a = 0; a < 2; ++a)
                for (int b = 0; b < 2; ++b) {
                    const double y = 0.5 * (top + bottom) + (a == 0 ? -offset : offset) * 0.5 * (top - bottom);
                    const double phi = M_PI / double(t.width) * (2.0 * double(i) + 1.0 + (b == 0 ? -offset : offset));
                    const double sinTheta = std::sqrt(std::max(0.0, 1.0 - y * y));
                    t.pixelDirections[(size_t(j) * t.width + i) * 4 + size_t(a * 2 + b)] =
                        glm::dvec3(sinTheta * std::sin(phi), y, sinTheta * std::cos(phi));
                }
    }
    return t;
}

SkyFrame buildFrame(const SkyParams& params, const FrameTables& tables, double hours) {
    SkyFrame frame;
    frame.hours = hours;
    const glm::dvec3 sun = sunDirection(params.latitudeDegrees, params.dayOfYear, hours);
    const DaylightSky sky = makeDaylightSky(sun, params.dayOfYear, params.daylight);
    const glm::dvec3 sunIrradiance = sky.sunRadiance * sunSolidAngle();
    frame.sunDirection = glm::vec3(sun);
    frame.sunRadiance = glm::vec3(sky.sunRadiance);
    frame.sunIrradiance = glm::vec3(sunIrradiance);

    std::vector<glm::dvec3> coefficients(size_t(tables.count), glm::dvec3(0.0));
    for (size_t k = 0; k < tables.upper.size(); ++k) {
        const glm::dvec3 weighted = skyRadiance(sky, tables.upper[k].direction) * tables.upper[k].weight;
        const double* basis = &tables.upperBasis[k * size_t(tables.count)];
        for (int i = 0; i < tables.count; ++i)
            coefficients[size_t(i)] += weighted * basis[i];
    }
    // The sun as a delta of weight sunIrradiance (sh::directionalLight), and the ground.
    double sunBasis[sh::kMaxOrder * sh::kMaxOrder];
    sh::evaluate(tables.order, sun, sunBasis);
    frame.sh.resize(size_t(tables.count) * 3);
    for (int i = 0; i < tables.count; ++i) {
        const glm::dvec3 c =
            coefficients[size_t(i)] + sky.ground * tables.lowerIntegral[size_t(i)] + sunIrradiance * sunBasis[i];
        for (int ch = 0; ch < 3; ++ch)
            frame.sh[size_t(i) * 3 + size_t(ch)] = float(c[ch]);
    }

    frame.image.resize(size_t(tables.width) * tables.height * 3);
    for (size_t p = 0; p < size_t(tables.width) * tables.height; ++p) {
        glm::dvec3 sum(0.0);
        for (size_t s = 0; s < 4; ++s)
            sum += skyRadiance(sky, tables.pixelDirections[p * 4 + s]);
        for (int ch = 0; ch < 3; ++ch)
            frame.image[p * 3 + size_t(ch)] = float(0.25 * sum[ch]);
    }
    return frame;
}

} // namespace

SkyParams skyParamsForPreset(const std::string& preset) {
    SkyParams params;
    if (preset == "full")
        return params;
    if (preset == "ci") {
        params.frames = 48;
        return params;
    }
    throw Error("sky: unknown preset '" + preset + "' (expected ci or full)");
}

void validateSkyParams(const SkyParams& params) {
    const auto fail = [](const std::string& what, const std::string& value, const std::string& rule) {
        throw Error("sky: " + what + " is " + value + "; " + rule);
    };
    if (!(std::abs(params.latitudeDegrees) <= 90.0))
        fail("latitude", number(params.latitudeDegrees), "it must be within -90..90 degrees");
    if (!(params.dayOfYear >= 1.0 && params.dayOfYear < 367.0))
        fail("day of year", number(params.dayOfYear), "it must be within 1..366");
    if (!(params.daylight.turbidity >= 1.7 && params.daylight.turbidity <= 10.0))
        fail("turbidity", number(params.daylight.turbidity), "Preetham's sky model is fitted for 1.7..10");
    if (!(params.daylight.groundAlbedo >= 0.0 && params.daylight.groundAlbedo <= 1.0))
        fail("ground albedo", number(params.daylight.groundAlbedo), "it must be within 0..1");
    if (!(params.daylight.nightLuminance >= 0.0 && std::isfinite(params.daylight.nightLuminance)))
        fail("night luminance", number(params.daylight.nightLuminance), "it must be a finite value >= 0 cd/m^2");
    if (params.frames < 1)
        fail("the frame count", "0", "a day needs at least one frame");
    if (params.imageHeight < 1 || params.imageWidth != 2 * params.imageHeight)
        fail("the image size", std::to_string(params.imageWidth) + "x" + std::to_string(params.imageHeight),
             "a lat-long image must be 2:1 and not empty");
    if (params.shOrder < 1 || params.shOrder > sh::kMaxOrder)
        fail("the SH order", std::to_string(params.shOrder), "it must be within 1.." + std::to_string(sh::kMaxOrder));
}

SkyFrame buildSkyFrame(const SkyParams& params, double hours) {
    validateSkyParams(params);
    return buildFrame(params, makeTables(params), hours);
}

SkyDay buildSkyDay(const SkyParams& params) {
    validateSkyParams(params);
    const FrameTables tables = makeTables(params);
    SkyDay day;
    day.shOrder = params.shOrder;
    day.imageWidth = params.imageWidth;
    day.imageHeight = params.imageHeight;
    day.frames.resize(params.frames);
    tbb::parallel_for(uint32_t(0), params.frames, [&](uint32_t i) {
        day.frames[i] = buildFrame(params, tables, 24.0 * double(i) / double(params.frames));
    });
    return day;
}

} // namespace meadow::sky
