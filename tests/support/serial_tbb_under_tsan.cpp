// Under ThreadSanitizer every test runs TBB without workers of its own: libtbb (and Embree's BVH
// build on top of it) is not instrumented, so the hand-over of tiles between its workers would be
// reported as races. Passes then run on the calling thread (or the progressive renderer's
// worker), and what TSan checks is pathlab's own synchronisation between its threads.
#if defined(__SANITIZE_THREAD__)
#include <tbb/global_control.h>

namespace {
const tbb::global_control kSerialTbb(tbb::global_control::max_allowed_parallelism, 1);
}  // namespace
#endif
