// meadow_far_compare: how well a render with the far field matches a reference over the far
// field's region (docs/BENCHMARKS.md, The far field).
//
//   meadow_far_compare TRUTH TRUTH_LOD APPROX APPROX_LOD [--region LOD_VIEW]... [--reference REF]
//                      [--max-colour C] [--coverage-ratio LO,HI] [--min-ssim S] [--ssim-margin M]
//                      [--lods FIRST,LAST]
//
// TRUTH and APPROX are renders of one frame; the *_LOD images are the same frames in the LOD view
// (`--debug-lod`), where every clump and rock shows one of six known colours (LODs 0 to 4 and the
// far field), so plants can be told from the ground. TRUTH and TRUTH_LOD may be rendered a whole
// number of times larger (supersampled): they are brought down by averaging. The region is every
// pixel that shows the far field's colour in APPROX_LOD, TRUTH_LOD (the far field's clumps drawn as
// LOD 0 meshes with --far-lod0 show it too) or any --region LOD view: where the far field is, or
// should be. --lods FIRST,LAST widens it to the colours of LODs FIRST to LAST (5: the far field):
// 0,5 is every plant pixel of either image, 1,3 where the approximation draws LODs 1 to 3 (a --lod0
// truth shows only LOD 0). Over the region:
//   - mean colour: linear RGB of TRUTH and APPROX, per channel, relative to the truth's
//     (fails above C, default 0.03);
//   - plant coverage: the share of region pixels that are plant in TRUTH_LOD and APPROX_LOD; fails
//     when the approximation's over the truth's lies outside [LO, HI] (default 0.95, 1.05);
//   - SSIM of the luma (Wang et al. 2004, 7x7 windows, sRGB-encoded values), averaged over the
//     windows centred in the region; fails below S, and, with --reference REF (another
//     approximation, the LOD meshes), below SSIM(REF, TRUTH) - M.
// Prints one line of figures, the mean colour's error taken apart too: the signed error per channel
// as the sum of its parts over the pixels that are plant in both images, in the approximation only,
// in the truth only, and the rest (so that a difference in the plants' colour can be told from one
// in where they cover). Exit 1 on failure, 2 on bad use.
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

// The LOD view's colours (instance.frag's kLodColors, far_splat.comp's kFarDebugColor) as linear
// radiance at display brightness, the sheet's far side at 0.6 of it: after the tonemapper's ACES fit
// and sRGB encoding (tonemap.comp) they are the only colours a clump or rock shows in that view (no
// haze falls on plants). A pixel within kPlantTolerance of one of them, in every channel, is plant;
// the ground, its haze and the sky are not. (A saturation threshold told them apart before, and
// missed the front of LOD 0's red: (0.90, 0.50, 0.39) after the tonemapper.)
constexpr float kLodViewColours[6][3] = {{0.9f, 0.15f, 0.1f}, {0.95f, 0.75f, 0.1f}, {0.2f, 0.8f, 0.2f},
                                         {0.1f, 0.6f, 0.95f}, {0.7f, 0.3f, 0.9f},   {0.05f, 0.9f, 0.85f}};
constexpr float kPlantTolerance = 0.03f;

float displayed(float linearRadiance) {
    const float x = linearRadiance;
    const float aces = std::clamp((x * (2.51f * x + 0.03f)) / (x * (2.43f * x + 0.59f) + 0.14f), 0.0f, 1.0f);
    return aces <= 0.0031308f ? aces * 12.92f : 1.055f * std::pow(aces, 1.0f / 2.4f) - 0.055f;
}

// Whether the pixel shows one of kLodViewColours[first .. last], either side.
bool showsLodColour(const Image& image, int x, int y, int first, int last) {
    for (int i = first; i <= last; ++i)
        for (const float side : {1.0f, 0.6f}) {
            bool near = true;
            for (int c = 0; c < 3; ++c)
                near = near && std::abs(image.at(x, y, c) - displayed(kLodViewColours[i][c] * side)) <= kPlantTolerance;
            if (near)
                return true;
        }
    return false;
}

bool isPlant(const Image& image, int x, int y) {
    return showsLodColour(image, x, y, 0, 5);
}

float encode(float c) {
    return c <= 0.0031308f ? c * 12.92f : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
}

// A supersampled render brought down by `k`: each k x k block's mean linear radiance, sRGB-encoded.
Image reduce(const Image& image, int k) {
    Image small;
    small.width = image.width / k;
    small.height = image.height / k;
    small.rgb.resize(size_t(small.width) * size_t(small.height) * 3);
    for (int y = 0; y < small.height; ++y)
        for (int x = 0; x < small.width; ++x)
            for (int c = 0; c < 3; ++c) {
                double sum = 0.0;
                for (int dy = 0; dy < k; ++dy)
                    for (int dx = 0; dx < k; ++dx)
                        sum += linear(image.at(k * x + dx, k * y + dy, c));
                small.rgb[3 * (size_t(y) * small.width + x) + size_t(c)] = encode(float(sum / double(k * k)));
            }
    return small;
}

// Per pixel of the image brought down by `k`, the share of its k x k block that is plant.
std::vector<float> plantShare(const Image& lodView, int k) {
    const int w = lodView.width / k, h = lodView.height / k;
    std::vector<float> share(size_t(w) * size_t(h));
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            int plants = 0;
            for (int dy = 0; dy < k; ++dy)
                for (int dx = 0; dx < k; ++dx)
                    plants += isPlant(lodView, k * x + dx, k * y + dy);
            share[size_t(y) * w + x] = float(plants) / float(k * k);
        }
    return share;
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
    std::fputs("usage: meadow_far_compare TRUTH TRUTH_LOD APPROX APPROX_LOD [--region LOD_VIEW]... [--reference REF]\n"
               "                          [--max-colour C] [--coverage-ratio LO,HI] [--min-ssim S] [--ssim-margin M]\n"
               "                          [--lods FIRST,LAST]\n",
               stderr);
    return 2;
}

} // namespace

int main(int argc, char** argv) {
    if (argc < 5)
        return usage();
    double maxColour = 0.03, coverageLow = 0.95, coverageHigh = 1.05, minSsim = 0.0, margin = 0.0;
    int firstLod = 5, lastLod = 5; // the LOD view colours that make the region: the far field's
    const char* referencePath = nullptr;
    std::vector<const char*> regionPaths;
    for (int i = 5; i < argc; i += 2) {
        if (i + 1 >= argc)
            return usage();
        const std::string option = argv[i];
        if (option == "--reference")
            referencePath = argv[i + 1];
        else if (option == "--region")
            regionPaths.push_back(argv[i + 1]);
        else if (option == "--max-colour")
            maxColour = std::atof(argv[i + 1]);
        else if (option == "--coverage-ratio") {
            if (std::sscanf(argv[i + 1], "%lf,%lf", &coverageLow, &coverageHigh) != 2)
                return usage();
        } else if (option == "--lods") {
            if (std::sscanf(argv[i + 1], "%d,%d", &firstLod, &lastLod) != 2 || firstLod < 0 || lastLod > 5 ||
                firstLod > lastLod)
                return usage();
        } else if (option == "--min-ssim")
            minSsim = std::atof(argv[i + 1]);
        else if (option == "--ssim-margin")
            margin = std::atof(argv[i + 1]);
        else
            return usage();
    }
    Image truthFull, truthLod, approx, approxLod, reference;
    if (!read(argv[1], truthFull) || !read(argv[2], truthLod) || !read(argv[3], approx) || !read(argv[4], approxLod) ||
        (referencePath && !read(referencePath, reference)))
        return 1;
    std::vector<Image> regionLods(regionPaths.size());
    for (size_t i = 0; i < regionPaths.size(); ++i)
        if (!read(regionPaths[i], regionLods[i]))
            return 1;
    // The truth may be rendered k times larger (supersampled): it is brought down to the size of the
    // others, its colour averaged and its coverage the share of plant in each block.
    const int k = approx.width > 0 ? truthFull.width / approx.width : 0;
    if (k < 1 || truthFull.width != k * approx.width || truthFull.height != k * approx.height ||
        truthLod.width != truthFull.width || truthLod.height != truthFull.height) {
        std::fprintf(stderr, "far_compare: the truth and its LOD view must be the approximation's size or a whole "
                             "multiple of it\n");
        return 1;
    }
    bool sameSize = approxLod.width == approx.width && approxLod.height == approx.height;
    for (const Image& image : regionLods)
        sameSize = sameSize && image.width == approx.width && image.height == approx.height;
    if (!sameSize || (referencePath && (reference.width != approx.width || reference.height != approx.height))) {
        std::fprintf(stderr, "far_compare: the images differ in size\n");
        return 1;
    }
    const Image truth = k == 1 ? truthFull : reduce(truthFull, k);
    const std::vector<float> truthPlant = plantShare(truthLod, k), approxPlant = plantShare(approxLod, 1);

    // The region: where any of the LOD views shows the chosen LODs' colours (by default the far
    // field's; the truth's: anywhere in the block).
    const int w = approx.width, h = approx.height;
    std::vector<uint8_t> region(size_t(w) * h, 0);
    size_t shownPixels = 0; // of the approximation's LOD view
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const bool shown = showsLodColour(approxLod, x, y, firstLod, lastLod);
            shownPixels += shown;
            bool inRegion = shown;
            for (const Image& image : regionLods)
                inRegion = inRegion || showsLodColour(image, x, y, firstLod, lastLod);
            for (int dy = 0; dy < k && !inRegion; ++dy)
                for (int dx = 0; dx < k && !inRegion; ++dx)
                    inRegion = showsLodColour(truthLod, k * x + dx, k * y + dy, firstLod, lastLod);
            region[size_t(y) * w + x] = inRegion;
        }
    double plantTruth = 0.0, plantApprox = 0.0;
    // The region's pixels in four parts: plant in both images (their colour is the plants' alone,
    // without coverage), plant in the approximation only, in the truth only, and the rest (neither,
    // or a supersampled truth's block part plant). The region's sums are the parts' summed; each
    // part's share of the mean colour's error is printed.
    enum Part { kBoth, kApproxOnly, kTruthOnly, kRest, kParts };
    double partTruth[kParts][3] = {}, partApprox[kParts][3] = {};
    size_t partPixels[kParts] = {};
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            if (!region[size_t(y) * w + x])
                continue;
            plantTruth += truthPlant[size_t(y) * w + x];
            plantApprox += approxPlant[size_t(y) * w + x];
            const float inTruth = truthPlant[size_t(y) * w + x], inApprox = approxPlant[size_t(y) * w + x];
            const Part part = inTruth == 1.0f && inApprox == 1.0f   ? kBoth
                              : inTruth == 0.0f && inApprox == 1.0f ? kApproxOnly
                              : inTruth == 1.0f && inApprox == 0.0f ? kTruthOnly
                                                                    : kRest;
            ++partPixels[part];
            for (int c = 0; c < 3; ++c) {
                partTruth[part][c] += linear(truth.at(x, y, c));
                partApprox[part][c] += linear(approx.at(x, y, c));
            }
        }
    size_t regionPixels = 0;
    double meanTruth[3] = {0, 0, 0}, meanApprox[3] = {0, 0, 0};
    for (int part = 0; part < kParts; ++part) {
        regionPixels += partPixels[part];
        for (int c = 0; c < 3; ++c) {
            meanTruth[c] += partTruth[part][c];
            meanApprox[c] += partApprox[part][c];
        }
    }
    if (shownPixels < 50) {
        std::fprintf(stderr,
                     "far_compare: LODs %d to %d (5: the far field) cover %zu pixels of %s: too few to compare\n",
                     firstLod, lastLod, shownPixels, argv[4]);
        return 1;
    }
    if (plantTruth == 0.0 || plantApprox == 0.0) {
        std::fprintf(stderr, "far_compare: no plant pixel in the region of %s: not a LOD view of this build?\n",
                     plantTruth == 0 ? argv[2] : argv[4]);
        return 1;
    }
    double colourError = 0.0;
    for (int c = 0; c < 3; ++c) {
        meanTruth[c] /= double(regionPixels);
        meanApprox[c] /= double(regionPixels);
        colourError = std::max(colourError, std::abs(meanApprox[c] - meanTruth[c]) / std::max(meanTruth[c], 1e-4));
    }
    const double coverageTruth = plantTruth / double(regionPixels);
    const double coverageApprox = plantApprox / double(regionPixels);
    const double coverageRatio = coverageApprox / std::max(coverageTruth, 1e-4);
    const double s = ssim(approx, truth, region);
    const double sReference = referencePath ? ssim(reference, truth, region) : 0.0;

    const std::string shown =
        firstLod == 5 ? "far field" : "LODs " + std::to_string(firstLod) + " to " + std::to_string(lastLod);
    std::printf("far_compare: region %zu px (%s %zu px); mean linear RGB truth %.4f %.4f %.4f, approximation "
                "%.4f %.4f %.4f (error %.2f%%, allowed %.2f%%); plant coverage truth %.3f, approximation %.3f "
                "(ratio %.3f, allowed %.2f to %.2f); SSIM %.3f",
                regionPixels, shown.c_str(), shownPixels, meanTruth[0], meanTruth[1], meanTruth[2], meanApprox[0],
                meanApprox[1], meanApprox[2], 100.0 * colourError, 100.0 * maxColour, coverageTruth, coverageApprox,
                coverageRatio, coverageLow, coverageHigh, s);
    if (referencePath)
        std::printf(" (reference %.3f)", sReference);
    std::printf(", allowed from %.3f", std::max(minSsim, referencePath ? sReference - margin : 0.0));
    if (partPixels[kBoth] > 0) {
        const size_t n = partPixels[kBoth];
        std::printf("; where both show plants (%zu px) truth %.4f %.4f %.4f, approximation %.4f %.4f %.4f", n,
                    partTruth[kBoth][0] / double(n), partTruth[kBoth][1] / double(n), partTruth[kBoth][2] / double(n),
                    partApprox[kBoth][0] / double(n), partApprox[kBoth][1] / double(n),
                    partApprox[kBoth][2] / double(n));
    }
    // The mean colour's signed error per channel, relative to the truth's mean, as the sum of the
    // parts' (approximation less truth, summed over the part, over the truth's sum): where it comes
    // from, plant colour or coverage.
    std::printf("; the error's parts, R G B in %% of the truth's mean:");
    const char* partNames[kParts] = {"plant in both", "plant in the approximation only", "plant in the truth only",
                                     "the rest"};
    for (int part = 0; part < kParts; ++part) {
        std::printf("%s %s (%zu px)", part ? "," : "", partNames[part], partPixels[part]);
        for (int c = 0; c < 3; ++c)
            std::printf(" %+.2f", 100.0 * (partApprox[part][c] - partTruth[part][c]) /
                                      std::max(meanTruth[c] * double(regionPixels), 1e-9));
    }
    std::printf("\n");
    bool ok = colourError <= maxColour && coverageRatio >= coverageLow && coverageRatio <= coverageHigh && s >= minSsim;
    if (referencePath)
        ok = ok && s >= sReference - margin;
    if (!ok)
        std::fprintf(stderr, "far_compare: %s does not match %s over the region\n", argv[3], argv[1]);
    return ok ? 0 : 1;
}
