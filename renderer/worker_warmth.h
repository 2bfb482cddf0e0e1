// Worker threads kept spinning for a short while after a render, as OpenMP runtimes keep theirs
// (KMP_BLOCKTIME, 200 ms by default), so that a render called soon after does not start without them.
// Waking a sleeping thread takes a small virtual machine longer than a short render lasts: on this
// project's 2-core machine a 128^2, 16-spp render took 4.4 ms straight after another and 7.5 ms after
// 30 ms of other work, the single-thread time, its worker arriving only at the end.
#pragma once

namespace mcval {

/// Stops the spinning of the workers kept warm by an earlier render: a render is starting.
void workersStart();
/// Keeps one worker thread spinning for up to `milliseconds`, or until the next workersStart().
void keepWorkersWarm(int milliseconds);

}  // namespace mcval
