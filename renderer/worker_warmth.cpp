#include "worker_warmth.h"

#include <atomic>
#include <chrono>
#include <cstdint>

#include <tbb/task_arena.h>

namespace mcval {

namespace {
std::atomic<uint64_t> gGeneration{0};  ///< changes whenever a render starts or ends
}  // namespace

void workersStart() { gGeneration.fetch_add(1, std::memory_order_relaxed); }

void keepWorkersWarm(int milliseconds) {
    const uint64_t generation = gGeneration.fetch_add(1, std::memory_order_relaxed) + 1;
    const auto until = std::chrono::steady_clock::now() + std::chrono::milliseconds(milliseconds);
    // Fire and forget: a worker picks it up (the caller does not wait), and spins until the deadline or
    // the next render's start, whichever comes first.
    tbb::this_task_arena::enqueue([generation, until] {
        while (gGeneration.load(std::memory_order_relaxed) == generation && std::chrono::steady_clock::now() < until) {
        }
    });
}

}  // namespace mcval
