// Parallel loops for the wind solver. Every loop body writes only its own cells, so the result is
// bit-identical for any number of TBB threads; small grids (coarse multigrid levels) run inline
// because a task costs more than the work.
#pragma once

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace meadow {

// Calls body(begin, end) over slabs [0, count), in parallel when count * cellsPerSlab is large.
template <class Body> void forEachSlab(int count, int cellsPerSlab, const Body& body) {
    constexpr int kParallelCells = 4096;
    if (count * cellsPerSlab < kParallelCells) {
        body(0, count);
        return;
    }
    tbb::parallel_for(tbb::blocked_range<int>(0, count),
                      [&](const tbb::blocked_range<int>& range) { body(range.begin(), range.end()); });
}

} // namespace meadow
