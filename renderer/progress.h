// A progress bar on stderr, shown only once a render has run for a second.
#pragma once

#include <chrono>
#include <cstdio>

namespace mcval {

class ProgressBar {
public:
    /// Redraws at most ten times a second, and only after the first second.
    void update(double fraction) {
        const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - m_start).count();
        if (elapsed < 1.0 || (elapsed - m_lastDraw < 0.1 && fraction < 1.0)) return;
        m_lastDraw = elapsed;
        constexpr int kWidth = 40;
        const int filled = static_cast<int>(fraction * kWidth);
        const double eta = fraction > 0.0 ? elapsed * (1.0 - fraction) / fraction : 0.0;
        std::fprintf(stderr, "\rrendering [%.*s%*s] %3d%%  %.1fs elapsed, %.1fs left ", filled,
                     "########################################", kWidth - filled, "",
                     static_cast<int>(fraction * 100.0 + 0.5), elapsed, eta);
        m_drawn = true;
    }
    /// Ends the bar's line, if one was drawn.
    void finish() {
        if (m_drawn) std::fputc('\n', stderr);
    }

private:
    std::chrono::steady_clock::time_point m_start = std::chrono::steady_clock::now();
    double m_lastDraw = 0.0;
    bool m_drawn = false;
};

}  // namespace mcval
