// The near raster's per-triangle arithmetic (shaders/shared/near_raster.h), shared by the shaders
// and the CPU reference: exact quotients without integer division, row spans that agree with the
// edge test at every pixel, and the top-left rule that covers each pixel of a shared edge once.
#include "near_raster.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <map>
#include <random>
#include <utility>
#include <vector>

using namespace meadow;

namespace {

// The pixels a set-up triangle covers, by the spans near_raster.comp walks.
std::vector<std::pair<int, int>> coveredBySpans(const gpu::NearTriangle& t) {
    std::vector<std::pair<int, int>> pixels;
    if (!t.drawn)
        return pixels;
    gpu::NearEdge e0 = gpu::nearEdgeStart(t.x1, t.y1, t.x2, t.y2, t.rowLo, t.sub);
    gpu::NearEdge e1 = gpu::nearEdgeStart(t.x2, t.y2, t.x0, t.y0, t.rowLo, t.sub);
    gpu::NearEdge e2 = gpu::nearEdgeStart(t.x0, t.y0, t.x1, t.y1, t.rowLo, t.sub);
    for (int row = t.rowLo;; ++row) {
        const int lo = gpu::nearSpanLow(e2, gpu::nearSpanLow(e1, gpu::nearSpanLow(e0, t.colLo)));
        const int hi = gpu::nearSpanHigh(e2, gpu::nearSpanHigh(e1, gpu::nearSpanHigh(e0, t.colHi)));
        for (int col = lo; col <= hi; ++col) {
            // The weights the shader interpolates with: every one at least 0, summing to the area.
            const int w0 = gpu::nearEdgeValue(e0, col), w1 = gpu::nearEdgeValue(e1, col),
                      w2 = gpu::nearEdgeValue(e2, col);
            EXPECT_GE(w0, 0);
            EXPECT_GE(w1, 0);
            EXPECT_GE(w2, 0);
            EXPECT_EQ(int64_t(w0) + w1 + w2, int64_t(t.area));
            pixels.push_back({t.originX + col, t.originY + row});
        }
        if (row >= t.rowHi)
            break;
        e0 = gpu::nearEdgeNextRow(e0);
        e1 = gpu::nearEdgeNextRow(e1);
        e2 = gpu::nearEdgeNextRow(e2);
    }
    return pixels;
}

// The same by testing every pixel of the picture against the three edges in 64-bit arithmetic.
std::vector<std::pair<int, int>> coveredByEdgeTest(const gpu::NearTriangle& t, int width, int height) {
    std::vector<std::pair<int, int>> pixels;
    if (!t.drawn)
        return pixels;
    const int64_t xs[3] = {t.x0, t.x1, t.x2}, ys[3] = {t.y0, t.y1, t.y2};
    for (int py = 0; py < height; ++py)
        for (int px = 0; px < width; ++px) {
            const int64_t cx = int64_t(px - t.originX) * t.sub + t.sub / 2,
                          cy = int64_t(py - t.originY) * t.sub + t.sub / 2;
            bool inside = true;
            for (int i = 0; i < 3; ++i) {
                const int a = (i + 1) % 3, b = (i + 2) % 3;
                const int64_t dx = xs[b] - xs[a], dy = ys[b] - ys[a];
                const int64_t e = dx * (cy - ys[a]) - dy * (cx - xs[a]);
                const bool topLeft = dy < 0 || (dy == 0 && dx > 0);
                inside = inside && (e > 0 || (e == 0 && topLeft));
            }
            if (inside)
                pixels.push_back({px, py});
        }
    return pixels;
}

} // namespace

TEST(NearRaster, QuotientIsExactWithoutIntegerDivision) {
    std::mt19937 rng(7);
    std::uniform_int_distribution<int> numerator(-(1 << 29), 1 << 29), divisor(1, 1 << 22), small(1, 64);
    for (int i = 0; i < 200000; ++i) {
        const int a = numerator(rng), b = i % 2 ? divisor(rng) : small(rng);
        int64_t want = a / b;
        if (want * b > a)
            --want;
        ASSERT_EQ(gpu::nearQuotient(a, b), want) << a << " / " << b;
    }
}

// Random triangles of every size the raster takes, on each subpixel grid, some reaching off the
// picture (where the set-up's shifts must floor negative coordinates): the spans cover exactly the
// pixels the edge test does.
TEST(NearRaster, SpansCoverExactlyThePixelsTheEdgeTestCovers) {
    std::mt19937 rng(11);
    const int width = 96, height = 64;
    size_t covered = 0;
    for (int sub : {256, 64, 16, 8}) {
        const float reach = float(gpu::kNearMaxSpan / uint32_t(sub)) * 0.45f; // boxes within the grid's limit
        std::uniform_real_distribution<float> centre(-10.0f, 106.0f), offset(-reach, reach), unit(0.0f, 1.0f);
        for (int i = 0; i < 3000; ++i) {
            const float size = unit(rng) < 0.5f ? 3.0f : 1.0f;
            const gpu::vec2 c(centre(rng), centre(rng) * 0.7f);
            const gpu::vec2 p0 = c + gpu::vec2(offset(rng), offset(rng)) * (size / reach) * (unit(rng) * 40.0f);
            const gpu::vec2 p1 = c + gpu::vec2(offset(rng), offset(rng)) * (unit(rng) < 0.2f ? 1.0f : 0.05f);
            const gpu::vec2 p2 = c + gpu::vec2(offset(rng), offset(rng)) * (unit(rng) < 0.2f ? 1.0f : 0.05f);
            const gpu::NearTriangle t = gpu::nearSetUp(p0, p1, p2, width, height, sub);
            const auto spans = coveredBySpans(t), tested = coveredByEdgeTest(t, width, height);
            ASSERT_EQ(spans, tested) << "sub " << sub << ", triangle " << i;
            covered += spans.size();
        }
    }
    EXPECT_GT(covered, 100000u); // the triangles do cover pixels
}

// A fan of triangles around a point and a strip of slivers: the pixels of their union are each
// covered once, the shared edges (horizontal, vertical and slanted) neither doubled nor dropped.
TEST(NearRaster, TrianglesSharingAnEdgeCoverEachPixelOnce) {
    const int width = 64, height = 64;
    for (int sub : {256, 16}) {
        std::map<std::pair<int, int>, int> count;
        const gpu::vec2 centre(31.5f, 32.0f); // on a pixel centre's row, between two columns
        const gpu::vec2 ring[8] = {{10, 10}, {32, 6}, {54, 10}, {58, 32}, {54, 54}, {32, 58}, {10, 54}, {6, 32}};
        size_t area = 0;
        for (int i = 0; i < 8; ++i) {
            const gpu::NearTriangle t = gpu::nearSetUp(centre, ring[i], ring[(i + 1) % 8], width, height, sub);
            ASSERT_TRUE(t.drawn);
            for (const auto& p : coveredBySpans(t))
                ++count[p];
            area += size_t(t.area);
        }
        for (const auto& [pixel, n] : count)
            EXPECT_EQ(n, 1) << "pixel " << pixel.first << "," << pixel.second << ", sub " << sub;
        // The union is the octagon: its pixel count is its area in pixels, within its outline.
        const double pixels = double(area) / 2.0 / double(sub * sub);
        EXPECT_NEAR(double(count.size()), pixels, 0.1 * pixels);
    }
    // Slivers: a strip of triangles a tenth of a pixel wide meeting along slanted edges.
    std::map<std::pair<int, int>, int> count;
    for (int i = 0; i < 40; ++i) {
        const float x = 5.0f + 0.1f * float(i);
        for (const auto& [a, b, c] :
             {std::tuple{gpu::vec2(x, 2.0f), gpu::vec2(x + 0.1f, 2.0f), gpu::vec2(x + 20.0f, 60.0f)},
              std::tuple{gpu::vec2(x + 0.1f, 2.0f), gpu::vec2(x + 20.1f, 60.0f), gpu::vec2(x + 20.0f, 60.0f)}})
            for (const auto& p : coveredBySpans(gpu::nearSetUp(a, b, c, width, height, 64)))
                ++count[p];
    }
    EXPECT_GT(count.size(), 100u);
    for (const auto& [pixel, n] : count)
        EXPECT_EQ(n, 1) << "sliver pixel " << pixel.first << "," << pixel.second;
}

TEST(NearRaster, SetUpRefusesWhatItCannotDrawExactly) {
    // Degenerate: all three on a line.
    EXPECT_FALSE(gpu::nearSetUp({1, 1}, {5, 5}, {9, 9}, 64, 64, 256).drawn);
    // Wholly off the picture.
    EXPECT_FALSE(gpu::nearSetUp({-20, 1}, {-10, 5}, {-15, 9}, 64, 64, 256).drawn);
    // A box wider than kNearMaxSpan subpixels at this grid (64 px at 1/256).
    EXPECT_FALSE(gpu::nearSetUp({0, 0}, {70, 1}, {3, 9}, 128, 64, 256).drawn);
    EXPECT_TRUE(gpu::nearSetUp({0, 0}, {70, 1}, {3, 9}, 128, 64, 64).drawn);
    // Not a number, and far beyond the picture: refused before any integer conversion.
    EXPECT_FALSE(gpu::nearSetUp({0, 0}, {1e9f, 1}, {3, 9}, 64, 64, 16).drawn);
    EXPECT_FALSE(gpu::nearSetUp({0, 0}, {std::nanf(""), 1}, {3, 9}, 64, 64, 16).drawn);
    // Either winding draws the same pixels.
    const auto a = coveredBySpans(gpu::nearSetUp({2, 3}, {30, 7}, {9, 40}, 64, 64, 64));
    const auto b = coveredBySpans(gpu::nearSetUp({2, 3}, {9, 40}, {30, 7}, 64, 64, 64));
    EXPECT_EQ(a, b);
    EXPECT_GT(a.size(), 300u);
    // The grids by projected radius.
    EXPECT_EQ(gpu::nearSubpixelFor(3.0f), 256);
    EXPECT_EQ(gpu::nearSubpixelFor(30.0f), 64);
    EXPECT_EQ(gpu::nearSubpixelFor(150.0f), 16);
    EXPECT_EQ(gpu::nearSubpixelFor(250.0f), 8);
}
