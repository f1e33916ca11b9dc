// Linked into every test executable of a ThreadSanitizer build (SONARSIM_TSAN, .ci/tsan.sh): TBB algorithms
// run on the thread that calls them. libtbb comes uninstrumented from Debian, so TSan cannot see the
// synchronisation by which a parallel_for hands its body to TBB's worker threads and joins them again, and it
// reports every parallel loop as a race (hundreds of reports per test, all of this kind). Without TBB worker
// threads, everything our own threads share is checked exactly: the render worker and its queue, results and
// cancel flag, frames read on one thread while the next renders on another, sessions, mesh caches.
#include <tbb/global_control.h>

namespace {
const tbb::global_control serial_tbb(tbb::global_control::max_allowed_parallelism, 1);
} // namespace
