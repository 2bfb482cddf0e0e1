// Output arrays of the warp bindings, reused: a fresh array of tens of MB costs more in page faults (the
// kernel zeroing every page on first touch) than the warp costs to fill it. Freed arrays are kept, a few
// of them, and handed out again for a request of the same size, as Dr.Jit's caching allocator does.
#pragma once

#include <cstddef>
#include <cstdlib>
#include <mutex>
#include <new>
#include <vector>

#include <sys/mman.h>

namespace mcval {

class BufferPool {
public:
    /// A buffer of `count` floats, reused if one of that size was released; never shared while alive.
    float *take(size_t count) {
        {
            std::lock_guard<std::mutex> lock(m_mutex);
            for (size_t i = 0; i < m_free.size(); ++i)
                if (m_free[i].count == count) {
                    float *p = m_free[i].data;
                    m_free.erase(m_free.begin() + static_cast<std::ptrdiff_t>(i));
                    return p;
                }
        }
        return allocate(count);
    }

    /// Gives a buffer back (the array that owned it is gone); beyond kKept buffers the oldest is freed.
    void release(float *data, size_t count) {
        float *drop = nullptr;
        {
            std::lock_guard<std::mutex> lock(m_mutex);
            m_free.push_back({data, count});
            if (m_free.size() > kKept) {
                drop = m_free.front().data;
                m_free.erase(m_free.begin());
            }
        }
        std::free(drop);
    }

    /// The process's pool (never destroyed: an array may outlive the module's static destructors).
    static BufferPool &instance() {
        static BufferPool *pool = new BufferPool;
        return *pool;
    }

private:
    static constexpr size_t kKept = 4;
    static constexpr size_t kHugePage = size_t(2) << 20;

    /// Buffers of a huge page or more sit on huge pages where the kernel has them (it does so on request
    /// only, as numpy asks for its own large arrays): a warp streams through tens of MB, and on 4 KiB
    /// pages every 4 KiB costs a TLB miss.
    static float *allocate(size_t count) {
        const size_t bytes = count * sizeof(float);
        if (bytes < kHugePage) {
            if (void *p = std::malloc(bytes)) return static_cast<float *>(p);
            throw std::bad_alloc();
        }
        const size_t rounded = (bytes + kHugePage - 1) / kHugePage * kHugePage;
        void *p = std::aligned_alloc(kHugePage, rounded);
        if (p == nullptr) throw std::bad_alloc();
#ifdef MADV_HUGEPAGE
        madvise(p, rounded, MADV_HUGEPAGE);  // advice only: without huge pages the buffer works the same
#endif
        return static_cast<float *>(p);
    }

    struct Block {
        float *data;
        size_t count;
    };
    std::mutex m_mutex;
    std::vector<Block> m_free;
};

}  // namespace mcval
