// Starting TBB's worker threads as soon as a process knows it will bake.
//
// TBB loads its runtime and creates its worker threads on the first parallel
// loop of a process: without this, inside the first product's bake, whose
// first milliseconds then run on one thread while the runtime loads (about
// 0.4 ms of CPU, bench/startup_bench.sh) and the worker starts (0.1 ms
// on idle cores, up to 2 ms under load). A 256x64 transmittance table is a
// 13 ms bake: that alone held its 1 -> 2 thread speed-up to 1.15x
// (docs/decisions/fresh-pages.md).
//
// A started worker may also start on the CPU of the thread that created it,
// and stay there, sharing it, while another CPU idles: see worker_start.cpp
// and docs/decisions/fresh-pages.md.
#pragma once

namespace skybake {

// With more than one thread allowed (tbb::global_control): loads the runtime
// on this thread and enqueues a task that does nothing, for which TBB
// creates its workers; they start while this thread goes on, each moved
// once off this thread's CPU if it started there. With one: loads the
// runtime only (TBB would start a worker for an enqueued task even then),
// so that a bake on one thread and one on several are timed alike. Cheap
// after the first call. Called where a bake finds something to compute,
// not at start-up: a process that bakes nothing pays nothing.
void start_workers();

}  // namespace skybake
