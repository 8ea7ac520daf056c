// meadow_far_compare: how well a render with the far field (or any approximation) matches the
// truth, every clump at full detail, over the far field's region (docs/BENCHMARKS.md, The far
// field).
//
//   meadow_far_compare TRUTH TRUTH_LOD APPROX APPROX_LOD REGION_LOD [--reference REF]
//                      [--max-colour C] [--coverage-ratio LO,HI] [--min-ssim S] [--ssim-margin M]
//
// TRUTH and APPROX are renders of one frame; the *_LOD images are the same frames in the LOD view
// (`--debug-lod`), where every clump and rock shows a saturated colour, so plants can be told
// from the ground; REGION_LOD is a LOD view with the far field, whose far-field colour (cyan)
// marks the region, dilated by 2 px to take in the ground between far clumps. Over the region:
//   - mean colour: linear RGB of TRUTH and APPROX, per channel, relative to the truth's
//     (fails above C, default 0.03);
//   - plant coverage: the share of region pixels that are plant in TRUTH_LOD and APPROX_LOD; fails
//     when the approximation's over the truth's lies outside [LO, HI] (default 0.95, 1.05);
//   - SSIM of the luma (Wang et al. 2004, 7x7 windows, sRGB-encoded values), averaged over the
//     windows centred in the region; fails below S, and, with --reference REF (another
//     approximation, the LOD meshes), below SSIM(REF, TRUTH) - M.
// Prints one line of figures; exit 1 on failure, 2 on bad use.
#include <OpenImageIO/imagebuf.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

namespace {

struct Image {
    int width = 0, height = 0;
    std::vector<float> rgb; // sRGB-encoded, 0..1
    float at(int x, int y, int c) const { return rgb[3 * (size_t(y) * size_t(width) + size_t(x)) + size_t(c)]; }
};

bool read(const char* path, Image& image) {
    OIIO::ImageBuf buf(path);
    if (!buf.read(0, 0, true, OIIO::TypeDesc::FLOAT) || buf.nchannels() < 3) {
        std::fprintf(stderr, "far_compare: cannot read %s as an RGB image: %s\n", path, buf.geterror().c_str());
        return false;
    }
    image.width = buf.spec().width;
    image.height = buf.spec().height;
    image.rgb.resize(size_t(image.width) * image.height * 3);
    std::vector<float> pixel(size_t(buf.nchannels()));
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            buf.getpixel(x, y, pixel.data(), int(pixel.size()));
            for (int c = 0; c < 3; ++c)
                image.rgb[3 * (size_t(y) * image.width + x) + size_t(c)] = pixel[size_t(c)];
        }
    return true;
}

float linear(float c) {
    return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

// The far field's colour in the LOD view (far_splat.comp's kFarDebugColor, lit and tonemapped).
bool isFarColour(const Image& image, int x, int y) {
    const float r = image.at(x, y, 0), g = image.at(x, y, 1), b = image.at(x, y, 2);
    return g - r > 0.25f && b - r > 0.25f && std::abs(g - b) < 0.25f;
}

// A clump or rock in the LOD view: saturated (the ground, the haze and the sky are not).
bool isPlant(const Image& image, int x, int y) {
    const float r = image.at(x, y, 0), g = image.at(x, y, 1), b = image.at(x, y, 2);
    const float hi = std::max({r, g, b}), lo = std::min({r, g, b});
    return hi > 0.08f && (hi - lo) / hi > 0.62f;
}

float luma(const Image& image, int x, int y) {
    return 0.2126f * image.at(x, y, 0) + 0.7152f * image.at(x, y, 1) + 0.0722f * image.at(x, y, 2);
}

// Mean SSIM of the luma over 7x7 windows centred on region pixels.
double ssim(const Image& a, const Image& b, const std::vector<uint8_t>& region) {
    constexpr int kHalf = 3;
    constexpr double c1 = 0.01 * 0.01, c2 = 0.03 * 0.03;
    double sum = 0.0;
    size_t windows = 0;
    for (int y = kHalf; y < a.height - kHalf; ++y)
        for (int x = kHalf; x < a.width - kHalf; ++x) {
            if (!region[size_t(y) * a.width + x])
                continue;
            double ma = 0.0, mb = 0.0, aa = 0.0, bb = 0.0, ab = 0.0;
            for (int dy = -kHalf; dy <= kHalf; ++dy)
                for (int dx = -kHalf; dx <= kHalf; ++dx) {
                    const double va = luma(a, x + dx, y + dy), vb = luma(b, x + dx, y + dy);
                    ma += va;
                    mb += vb;
                    aa += va * va;
                    bb += vb * vb;
                    ab += va * vb;
                }
            const double n = double((2 * kHalf + 1) * (2 * kHalf + 1));
            ma /= n;
            mb /= n;
            const double va = aa / n - ma * ma, vb = bb / n - mb * mb, cov = ab / n - ma * mb;
            sum += ((2.0 * ma * mb + c1) * (2.0 * cov + c2)) / ((ma * ma + mb * mb + c1) * (va + vb + c2));
            ++windows;
        }
    return windows ? sum / double(windows) : 0.0;
}

int usage() {
    std::fputs("usage: meadow_far_compare TRUTH TRUTH_LOD APPROX APPROX_LOD REGION_LOD [--reference REF]\n"
               "                          [--max-colour C] [--coverage-ratio LO,HI] [--min-ssim S] [--ssim-margin M]\n",
               stderr);
    return 2;
}

} // namespace

int main(int argc, char** argv) {
    if (argc < 6)
        return usage();
    double maxColour = 0.03, coverageLow = 0.95, coverageHigh = 1.05, minSsim = 0.0, margin = 0.0;
    const char* referencePath = nullptr;
    for (int i = 6; i < argc; i += 2) {
        if (i + 1 >= argc)
            return usage();
        const std::string option = argv[i];
        if (option == "--reference")
            referencePath = argv[i + 1];
        else if (option == "--max-colour")
            maxColour = std::atof(argv[i + 1]);
        else if (option == "--coverage-ratio") {
            if (std::sscanf(argv[i + 1], "%lf,%lf", &coverageLow, &coverageHigh) != 2)
                return usage();
        } else if (option == "--min-ssim")
            minSsim = std::atof(argv[i + 1]);
        else if (option == "--ssim-margin")
            margin = std::atof(argv[i + 1]);
        else
            return usage();
    }
    Image truth, truthLod, approx, approxLod, regionLod, reference;
    if (!read(argv[1], truth) || !read(argv[2], truthLod) || !read(argv[3], approx) || !read(argv[4], approxLod) ||
        !read(argv[5], regionLod) || (referencePath && !read(referencePath, reference)))
        return 1;
    for (const Image* image : {&truthLod, &approx, &approxLod, &regionLod})
        if (image->width != truth.width || image->height != truth.height) {
            std::fprintf(stderr, "far_compare: the images differ in size\n");
            return 1;
        }
    if (referencePath && (reference.width != truth.width || reference.height != truth.height)) {
        std::fprintf(stderr, "far_compare: the reference differs in size\n");
        return 1;
    }

    // The region: far-field pixels, dilated by 2 px.
    const int w = truth.width, h = truth.height;
    std::vector<uint8_t> region(size_t(w) * h, 0);
    size_t farPixels = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            if (!isFarColour(regionLod, x, y))
                continue;
            ++farPixels;
            for (int dy = -2; dy <= 2; ++dy)
                for (int dx = -2; dx <= 2; ++dx)
                    if (x + dx >= 0 && y + dy >= 0 && x + dx < w && y + dy < h)
                        region[size_t(y + dy) * w + size_t(x + dx)] = 1;
        }
    size_t regionPixels = 0;
    double meanTruth[3] = {0, 0, 0}, meanApprox[3] = {0, 0, 0};
    size_t plantTruth = 0, plantApprox = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            if (!region[size_t(y) * w + x])
                continue;
            ++regionPixels;
            for (int c = 0; c < 3; ++c) {
                meanTruth[c] += linear(truth.at(x, y, c));
                meanApprox[c] += linear(approx.at(x, y, c));
            }
            plantTruth += isPlant(truthLod, x, y);
            plantApprox += isPlant(approxLod, x, y);
        }
    if (farPixels < 50) {
        std::fprintf(stderr, "far_compare: the far field covers %zu pixels of %s: too few to compare\n", farPixels,
                     argv[5]);
        return 1;
    }
    double colourError = 0.0;
    for (int c = 0; c < 3; ++c) {
        meanTruth[c] /= double(regionPixels);
        meanApprox[c] /= double(regionPixels);
        colourError = std::max(colourError, std::abs(meanApprox[c] - meanTruth[c]) / std::max(meanTruth[c], 1e-4));
    }
    const double coverageTruth = double(plantTruth) / double(regionPixels);
    const double coverageApprox = double(plantApprox) / double(regionPixels);
    const double coverageRatio = coverageApprox / std::max(coverageTruth, 1e-4);
    const double s = ssim(approx, truth, region);
    const double sReference = referencePath ? ssim(reference, truth, region) : 0.0;

    std::printf("far_compare: region %zu px (far field %zu px); mean linear RGB truth %.4f %.4f %.4f, approximation "
                "%.4f %.4f %.4f (error %.2f%%, allowed %.2f%%); plant coverage truth %.3f, approximation %.3f "
                "(ratio %.3f, allowed %.2f to %.2f); SSIM %.3f",
                regionPixels, farPixels, meanTruth[0], meanTruth[1], meanTruth[2], meanApprox[0], meanApprox[1],
                meanApprox[2], 100.0 * colourError, 100.0 * maxColour, coverageTruth, coverageApprox, coverageRatio,
                coverageLow, coverageHigh, s);
    if (referencePath)
        std::printf(" (reference %.3f)", sReference);
    std::printf(", allowed from %.3f\n", std::max(minSsim, referencePath ? sReference - margin : 0.0));
    bool ok = colourError <= maxColour && coverageRatio >= coverageLow && coverageRatio <= coverageHigh && s >= minSsim;
    if (referencePath)
        ok = ok && s >= sReference - margin;
    if (!ok)
        std::fprintf(stderr, "far_compare: %s does not match %s over the far field's region\n", argv[3], argv[1]);
    return ok ? 0 : 1;
}
