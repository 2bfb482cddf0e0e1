// Output arrays of the warp bindings, reused: a fresh array of tens of MB costs more in page faults (the
// kernel zeroing every page on first touch) than the warp costs to fill it. Freed arrays are kept, a few
// of them, and handed out again for a request of the same size, as Dr.Jit's caching allocator does.
#pragma once

#include <cstddef>
#include <mutex>
#include <vector>

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
        return new float[count];
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
        delete[] drop;
    }

    /// The process's pool (never destroyed: an array may outlive the module's static destructors).
    static BufferPool &instance() {
        static BufferPool *pool = new BufferPool;
        return *pool;
    }

private:
    static constexpr size_t kKept = 4;
    struct Block {
        float *data;
        size_t count;
    };
    std::mutex m_mutex;
    std::vector<Block> m_free;
};

}  // namespace mcval
