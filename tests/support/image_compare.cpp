// meadow_image_compare: compares a rendered image with its golden through OpenImageIO, or checks
// that an image is not blank. Used by the golden and window tests.
//
//   meadow_image_compare ACTUAL EXPECTED --fail-threshold T --fail-percent P [--diff DIFF]
//     fails when more than P percent of pixels differ by more than T (0-1) in any channel, or
//     when the sizes differ; writes a difference image (x8) to DIFF on failure.
//   meadow_image_compare IMAGE --not-blank [--size WxH]
//     fails when the image is one flat colour (standard deviation < 1/255) or of another size.
#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

namespace {

int usage() {
    std::fputs("usage: meadow_image_compare ACTUAL EXPECTED --fail-threshold T --fail-percent P [--diff DIFF]\n"
               "       meadow_image_compare IMAGE --not-blank [--size WxH]\n",
               stderr);
    return 2;
}

bool readImage(OIIO::ImageBuf& buf, const char* path) {
    buf.reset(path);
    if (!buf.read(0, 0, true, OIIO::TypeDesc::FLOAT)) {
        std::fprintf(stderr, "image_compare: cannot read %s: %s\n", path, buf.geterror().c_str());
        return false;
    }
    return true;
}

} // namespace

int main(int argc, char** argv) {
    if (argc < 3)
        return usage();
    if (std::strcmp(argv[2], "--not-blank") == 0) {
        OIIO::ImageBuf image;
        if (!readImage(image, argv[1]))
            return 1;
        if (argc == 5 && std::strcmp(argv[3], "--size") == 0) {
            int w = 0, h = 0;
            if (std::sscanf(argv[4], "%dx%d", &w, &h) != 2)
                return usage();
            if (image.spec().width != w || image.spec().height != h) {
                std::fprintf(stderr, "image_compare: %s is %dx%d, expected %dx%d\n", argv[1], image.spec().width,
                             image.spec().height, w, h);
                return 1;
            }
        }
        auto stats = OIIO::ImageBufAlgo::computePixelStats(image);
        float maxDev = 0.0f;
        for (int c = 0; c < std::min(3, image.nchannels()); ++c)
            maxDev = std::max(maxDev, stats.stddev[size_t(c)]);
        std::printf("image_compare: %s %dx%d, largest channel standard deviation %.4f\n", argv[1], image.spec().width,
                    image.spec().height, double(maxDev));
        if (maxDev < 1.0f / 255.0f) {
            std::fprintf(stderr, "image_compare: %s is blank (one flat colour)\n", argv[1]);
            return 1;
        }
        return 0;
    }

    float threshold = -1.0f, percent = -1.0f;
    const char* diffPath = nullptr;
    for (int i = 3; i + 1 < argc; i += 2) {
        if (std::strcmp(argv[i], "--fail-threshold") == 0)
            threshold = std::strtof(argv[i + 1], nullptr);
        else if (std::strcmp(argv[i], "--fail-percent") == 0)
            percent = std::strtof(argv[i + 1], nullptr);
        else if (std::strcmp(argv[i], "--diff") == 0)
            diffPath = argv[i + 1];
        else
            return usage();
    }
    if (threshold < 0.0f || percent < 0.0f)
        return usage();
    OIIO::ImageBuf actual, expected;
    if (!readImage(actual, argv[1]) || !readImage(expected, argv[2]))
        return 1;
    if (actual.spec().width != expected.spec().width || actual.spec().height != expected.spec().height ||
        actual.nchannels() != expected.nchannels()) {
        std::fprintf(stderr, "image_compare: %s is %dx%dx%d but the golden %s is %dx%dx%d\n", argv[1],
                     actual.spec().width, actual.spec().height, actual.nchannels(), argv[2], expected.spec().width,
                     expected.spec().height, expected.nchannels());
        return 1;
    }
    auto result = OIIO::ImageBufAlgo::compare(actual, expected, threshold, threshold);
    double pixels = double(actual.spec().width) * actual.spec().height;
    double failedPercent = 100.0 * double(result.nfail) / pixels;
    std::printf("image_compare: mean error %.5f, RMS %.5f, max %.4f, %.3f%% of pixels over %.4f (allowed %.3f%%)\n",
                result.meanerror, result.rms_error, result.maxerror, failedPercent, double(threshold), double(percent));
    if (failedPercent <= double(percent))
        return 0;
    if (diffPath) {
        OIIO::ImageBuf diff = OIIO::ImageBufAlgo::absdiff(actual, expected);
        diff = OIIO::ImageBufAlgo::mul(diff, 8.0f);
        if (!diff.write(diffPath))
            std::fprintf(stderr, "image_compare: cannot write %s\n", diffPath);
        else
            std::fprintf(stderr, "image_compare: difference (x8) written to %s\n", diffPath);
    }
    std::fprintf(stderr, "image_compare: %s differs from the golden %s\n", argv[1], argv[2]);
    return 1;
}
