// Keeps the UI responsive next to the render threads on few cores: every other thread of the
// process that carries the process's own name (the progressive renderer's worker and TBB's
// workers; not Mesa's llvmpipe threads, which rasterise the UI) is set to a lower priority.
// Linux only (/proc/self/task, per-thread nice); a no-op elsewhere. Lowering needs no privilege.
#pragma once

namespace pathlab::ui {

// Sets nice `niceness` on those threads; call now and then (new worker threads appear lazily).
// Returns how many threads were changed.
int lowerRenderThreadPriority(int niceness);

}  // namespace pathlab::ui
