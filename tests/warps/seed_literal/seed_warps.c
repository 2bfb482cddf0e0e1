/* The warps of a student's report (CS440 Homework 3, section 2, "Monte Carlo Sampling"; the seed document
 * of issue 40), transcribed literally, their mistakes included, through the C ABI of include/mcval_warps.h.
 * The report's x and y are the uniforms u[0] and u[1]; float32, as in Nori. Every function quotes the
 * equations it transcribes. What the harness must find (tests/warps/test_seed_literal.py):
 *   tent        a uniform triangle, with the triangle's pdf: judged by its name, not against itself;
 *   disk        returns (r, theta), not a point of the disk; its pdf pi is pi^2 too large (1/pi);
 *   sphere      right sampler; pdf pi/4, pi^2 too large (1/(4 pi));
 *   hemisphere  right sampler; pdf pi/2, pi^2 too large (1/(2 pi)), and also below the horizon;
 *   cosine      right sampler; pdf pi cos, pi^2 too large (cos/pi);
 *   beckmann    sqrt of alpha^2 log(1 - y) <= 0: NaN for every y > 0; its pdf is no density at all.
 * The report exports no uniform square. */
#include <math.h>

#include "mcval_warps.h"

static const float kPi = 3.14159265358979323846f;
/* The report's epsilon is not given; this is the harness's own slack on unit length. */
static const float kEpsilon = 1e-5f;

static void store_direction(float *out, float theta, float phi) {
    /* (10), (13), (16), (19): Return(sin(theta) cos(phi), sin(theta) sin(phi), cos(theta)) */
    out[0] = sinf(theta) * cosf(phi);
    out[1] = sinf(theta) * sinf(phi);
    out[2] = cosf(theta);
}

static float norm2_minus_one(const float *v) { return v[0] * v[0] + v[1] * v[1] + v[2] * v[2] - 1; }

/* 2.1 (1)-(3) */
void square_to_tent(const float *s, float *out, size_t n) {
    for (size_t i = 0; i < n; ++i) {
        float x = s[2 * i], y = s[2 * i + 1];
        float u = sqrtf(1 - x);      /* (1) */
        float v = y * (1 - (1 - u)); /* (2) */
        /* (3): (-1, 0) + (1 - u) * (2, 0) + v * (1, 1) */
        out[2 * i] = -1 + (1 - u) * 2 + v * 1;
        out[2 * i + 1] = 0 + (1 - u) * 0 + v * 1;
    }
}

/* 2.1 (4)-(5): the edges (s, t) = (v1, v2), (v2, v3), (v3, v1) of the triangle of (3); 0 where res_i has
 * both signs (the report's "res_i + 1" read as res_{i+1}), else 1. */
void square_to_tent_pdf(const float *p, float *pdf, size_t n) {
    static const float v[3][2] = {{-1, 0}, {1, 0}, {0, 1}};
    for (size_t k = 0; k < n; ++k) {
        float px = p[2 * k], py = p[2 * k + 1];
        int positive = 0, negative = 0;
        for (int i = 0; i < 3; ++i) {
            const float *s = v[i], *t = v[(i + 1) % 3];
            float res = (px - t[0]) * (s[1] - t[1]) - (s[0] - t[0]) * (py - t[1]); /* (4) */
            positive |= res > 0;
            negative |= res < 0;
        }
        pdf[k] = positive && negative ? 0 : 1; /* (5) */
    }
}

/* 2.2 (6)-(7) */
void square_to_uniform_disk(const float *s, float *out, size_t n) {
    for (size_t i = 0; i < n; ++i) {
        float x = s[2 * i], y = s[2 * i + 1];
        float theta = 2 * kPi * x, r = sqrtf(y); /* (6) */
        out[2 * i] = r;                          /* (7): Return(r, theta) */
        out[2 * i + 1] = theta;
    }
}

/* 2.2 (8) */
void square_to_uniform_disk_pdf(const float *p, float *pdf, size_t n) {
    for (size_t i = 0; i < n; ++i) {
        float x = p[2 * i], y = p[2 * i + 1];
        pdf[i] = x * x + y * y <= 1 ? kPi : 0;
    }
}

/* 2.3 (9)-(10) */
void square_to_uniform_sphere(const float *s, float *out, size_t n) {
    for (size_t i = 0; i < n; ++i) {
        float x = s[2 * i], y = s[2 * i + 1];
        store_direction(out + 3 * i, acosf(1 - 2 * x), 2 * kPi * y); /* (9) */
    }
}

/* 2.3 (11) */
void square_to_uniform_sphere_pdf(const float *p, float *pdf, size_t n) {
    for (size_t i = 0; i < n; ++i)
        pdf[i] = norm2_minus_one(p + 3 * i) <= kEpsilon ? kPi / 4 : 0;
}

/* 2.4 (12)-(13) */
void square_to_uniform_hemisphere(const float *s, float *out, size_t n) {
    for (size_t i = 0; i < n; ++i) {
        float x = s[2 * i], y = s[2 * i + 1];
        store_direction(out + 3 * i, acosf(1 - x), 2 * kPi * y); /* (12) */
    }
}

/* 2.4 (14) */
void square_to_uniform_hemisphere_pdf(const float *p, float *pdf, size_t n) {
    for (size_t i = 0; i < n; ++i)
        pdf[i] = norm2_minus_one(p + 3 * i) <= kEpsilon ? kPi / 2 : 0;
}

/* 2.5 (15)-(16) */
void square_to_cosine_hemisphere(const float *s, float *out, size_t n) {
    for (size_t i = 0; i < n; ++i) {
        float x = s[2 * i], y = s[2 * i + 1];
        store_direction(out + 3 * i, acosf(sqrtf(1 - x)), 2 * kPi * y); /* (15) */
    }
}

/* 2.5 (17) */
void square_to_cosine_hemisphere_pdf(const float *p, float *pdf, size_t n) {
    for (size_t i = 0; i < n; ++i) {
        const float *v = p + 3 * i;
        pdf[i] = norm2_minus_one(v) <= kEpsilon && v[2] > 0 ? kPi * v[2] : 0;
    }
}

/* 2.6 (18)-(19) */
void square_to_beckmann(const float *s, float *out, size_t n, float alpha) {
    for (size_t i = 0; i < n; ++i) {
        float x = s[2 * i], y = s[2 * i + 1];
        float theta = atanf(sqrtf(alpha * alpha * logf(1 - y))), phi = 2 * kPi * x; /* (18) */
        store_direction(out + 3 * i, theta, phi);
    }
}

/* 2.6 (20), with the report's m read as its v */
void square_to_beckmann_pdf(const float *p, float *pdf, size_t n, float alpha) {
    for (size_t i = 0; i < n; ++i) {
        const float *v = p + 3 * i;
        pdf[i] = kPi * (expf(powf(tanf(acosf(v[0])), 2) / (alpha * alpha)) / (alpha * alpha) * powf(v[2], 3));
    }
}
