// Sample warps and their densities, exported through the C ABI of mcval_warps.h.
//
// Domains and densities are those of Mitsuba 3's mi.warp. As in its disk and sphere warps, u0 picks the
// azimuth phi = 2 pi u0 and u1 the radius or the polar angle; directions are z up. For every float32 u in
// [0, 1] (u = 1 included, though outside the [0, 1) a sampler is fed) the sample is finite, lies in the
// domain, and its pdf is positive.
//
// One source builds three libraries (see CMakeLists.txt):
//   (no definition)        the correct warps;
//   EXAMPLE_WARPS_SEED     the pdfs of a course report, with wrong normalisation constants;
//   EXAMPLE_WARPS_U_ONE    a cosine-hemisphere sampler that returns NaN at u1 = 1 exactly.
// Each planted mistake is marked "Planted:".

#include "mcval_warps.h"

#include <algorithm>
#include <cmath>

#if defined(EXAMPLE_WARPS_SEED) && defined(EXAMPLE_WARPS_U_ONE)
#error "define at most one of EXAMPLE_WARPS_SEED and EXAMPLE_WARPS_U_ONE"
#endif

namespace {

#if defined(EXAMPLE_WARPS_SEED)
constexpr bool kSeed = true;
#else
constexpr bool kSeed = false;
#endif
#if defined(EXAMPLE_WARPS_U_ONE)
constexpr bool kUOne = true;
#else
constexpr bool kUOne = false;
#endif

constexpr float kPi = 3.14159265358979323846f;
constexpr float kTwoPi = 6.28318530717958647692f;
constexpr float kInvPi = 0.31830988618379067154f;
constexpr float kInvTwoPi = 0.15915494309189533577f;
constexpr float kInvFourPi = 0.07957747154594766788f;
// The largest float below 1.
constexpr float kOneMinusEpsilon = 0x1.fffffep-1f;

// u clamped below 1, so that formulas such as log(1 - u) stay finite should a caller pass u = 1.
float below_one(float u) { return std::min(u, kOneMinusEpsilon); }

// Inverse CDF of the tent density 1 - |x| on [-1, 1], for u in [0, 1).
float interval_to_tent(float u) {
    float x = u < 0.5f ? std::sqrt(2 * u) - 1 : 1 - std::sqrt(2 - 2 * u);
    // u = 0 would give x = -1, where the density is 0.
    return std::max(x, -kOneMinusEpsilon);
}

void store_direction(float *out, float sin_theta, float cos_theta, float phi) {
    out[0] = sin_theta * std::cos(phi);
    out[1] = sin_theta * std::sin(phi);
    out[2] = cos_theta;
}

// The direction whose polar angle has tan^2(theta) = tan2. sin(theta) is computed as tan(theta) cos(theta),
// not sqrt(1 - cos^2(theta)), which cancels near the pole (Beckmann's warp at small alpha lives there).
void store_direction_tan2(float *out, float tan2, float phi) {
    float cos_theta = 1 / std::sqrt(1 + tan2);
    store_direction(out, std::sqrt(tan2) * cos_theta, cos_theta, phi);
}

}  // namespace

extern "C" {

void square_to_uniform_square(const float *u, float *out, size_t n) {
    std::copy(u, u + 2 * n, out);
}

void square_to_uniform_square_pdf(const float *p, float *pdf, size_t n) {
    for (size_t i = 0; i < n; ++i) {
        float x = p[2 * i], y = p[2 * i + 1];
        pdf[i] = x >= 0 && x <= 1 && y >= 0 && y <= 1 ? 1.f : 0.f;
    }
}

void square_to_tent(const float *u, float *out, size_t n) {
    for (size_t i = 0; i < 2 * n; ++i)
        out[i] = interval_to_tent(below_one(u[i]));
}

void square_to_tent_pdf(const float *p, float *pdf, size_t n) {
    for (size_t i = 0; i < n; ++i) {
        float x = std::abs(p[2 * i]), y = std::abs(p[2 * i + 1]);
        pdf[i] = x <= 1 && y <= 1 ? (1 - x) * (1 - y) : 0.f;
    }
}

void square_to_uniform_disk(const float *u, float *out, size_t n) {
    for (size_t i = 0; i < n; ++i) {
        float phi = kTwoPi * u[2 * i], r = std::sqrt(below_one(u[2 * i + 1]));
        out[2 * i] = r * std::cos(phi);
        out[2 * i + 1] = r * std::sin(phi);
    }
}

void square_to_uniform_disk_pdf(const float *p, float *pdf, size_t n) {
    // Planted: the report gives the disk's density as pi; the disk's area is pi, so it is 1 / pi.
    constexpr float density = kSeed ? kPi : kInvPi;
    for (size_t i = 0; i < n; ++i) {
        float x = p[2 * i], y = p[2 * i + 1];
        pdf[i] = x * x + y * y <= 1 ? density : 0.f;
    }
}

void square_to_uniform_sphere(const float *u, float *out, size_t n) {
    for (size_t i = 0; i < n; ++i) {
        float phi = kTwoPi * u[2 * i], u1 = u[2 * i + 1];
        // z = 1 - 2 u1; sin(theta) = sqrt(1 - z^2) = 2 sqrt(u1 (1 - u1)), without cancellation at the poles.
        store_direction(out + 3 * i, 2 * std::sqrt(u1 * (1 - u1)), 1 - 2 * u1, phi);
    }
}

void square_to_uniform_sphere_pdf(const float *, float *pdf, size_t n) {
    // Planted: the report gives pi / 4; the sphere's solid angle is 4 pi, so it is 1 / (4 pi).
    constexpr float density = kSeed ? kPi / 4 : kInvFourPi;
    std::fill(pdf, pdf + n, density);
}

void square_to_uniform_hemisphere(const float *u, float *out, size_t n) {
    for (size_t i = 0; i < n; ++i) {
        float phi = kTwoPi * u[2 * i], u1 = u[2 * i + 1];
        // z = 1 - u1; sin(theta) = sqrt(1 - z^2) = sqrt(u1 (2 - u1)).
        store_direction(out + 3 * i, std::sqrt(u1 * (2 - u1)), 1 - u1, phi);
    }
}

void square_to_uniform_hemisphere_pdf(const float *p, float *pdf, size_t n) {
    // Planted: the report gives pi / 2; the hemisphere's solid angle is 2 pi, so it is 1 / (2 pi).
    constexpr float density = kSeed ? kPi / 2 : kInvTwoPi;
    for (size_t i = 0; i < n; ++i)
        pdf[i] = p[3 * i + 2] >= 0 ? density : 0.f;
}

void square_to_cosine_hemisphere(const float *u, float *out, size_t n) {
    for (size_t i = 0; i < n; ++i) {
        float phi = kTwoPi * u[2 * i];
        // Planted: u1 is not kept below 1. At u1 = 1, tan^2(theta) = 1 / 0 = inf and the sample is
        // (NaN, NaN, 0); every u1 in [0, 1) gives the same sample as the correct warp.
        float u1 = kUOne ? u[2 * i + 1] : below_one(u[2 * i + 1]);
        // cos^2(theta) = 1 - u1, as Malley's method (a uniform disk sample lifted to the hemisphere) gives;
        // that is, tan^2(theta) = u1 / (1 - u1).
        store_direction_tan2(out + 3 * i, u1 / (1 - u1), phi);
    }
}

void square_to_cosine_hemisphere_pdf(const float *p, float *pdf, size_t n) {
    // Planted: the report gives pi cos(theta); the integral of cos(theta) over the hemisphere is pi, so
    // it is cos(theta) / pi.
    constexpr float scale = kSeed ? kPi : kInvPi;
    for (size_t i = 0; i < n; ++i) {
        float z = p[3 * i + 2];
        pdf[i] = z > 0 ? scale * z : 0.f;
    }
}

void square_to_beckmann(const float *u, float *out, size_t n, float alpha) {
    for (size_t i = 0; i < n; ++i) {
        float phi = kTwoPi * u[2 * i];
        // tan^2(theta_m) has the CDF 1 - exp(-tan^2 / alpha^2); u1 below 1 keeps its inverse finite.
        float tan2 = -alpha * alpha * std::log1p(-below_one(u[2 * i + 1]));
        store_direction_tan2(out + 3 * i, tan2, phi);
    }
}

void square_to_beckmann_pdf(const float *p, float *pdf, size_t n, float alpha) {
    // D(m) cos(theta_m) = exp(-tan^2 / alpha^2) / (pi alpha^2 cos^4) * cos.
    float alpha2 = alpha * alpha;
    for (size_t i = 0; i < n; ++i) {
        float x = p[3 * i], y = p[3 * i + 1], z = p[3 * i + 2];
        if (!(z > 0)) {
            pdf[i] = 0.f;
            continue;
        }
        float cos2 = z * z;
        // tan^2 from x^2 + y^2 rather than 1 - z^2, which cancels near the pole.
        float e = std::exp(-(x * x + y * y) / cos2 / alpha2);
        // Near the horizon e underflows to 0 before cos^3 does: return 0 there, not 0 / 0.
        pdf[i] = e > 0 ? e / (kPi * alpha2 * cos2 * z) : 0.f;
    }
}

}  // extern "C"
