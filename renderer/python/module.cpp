// Python bindings: the warps over whole numpy arrays (no Python call per sample).
#include <cstddef>
#include <cstring>
#include <utility>

#include <nanobind/nanobind.h>
#include <nanobind/stl/string.h>
#include <nanobind/stl/vector.h>
#include <nanobind/ndarray.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "../integrators/registry.h"
#include "buffer_pool.h"
#include "../warp.h"

namespace nb = nanobind;
using namespace mcval;

namespace {

template <size_t Dim>
using PointsIn = nb::ndarray<const float, nb::shape<-1, Dim>, nb::c_contig, nb::device::cpu>;
template <size_t Dim>
using PointsOut = nb::ndarray<nb::numpy, float, nb::shape<-1, Dim>>;
using ValuesOut = nb::ndarray<nb::numpy, float, nb::shape<-1>>;

template <size_t Dim>
auto load(const float *row) {
    if constexpr (Dim == 2) return Vec2f(row[0], row[1]);
    else return Vec3f(row[0], row[1], row[2]);
}

inline void store(float *row, const Vec2f &v) { row[0] = v.x; row[1] = v.y; }
inline void store(float *row, const Vec3f &v) { row[0] = v.x; row[1] = v.y; row[2] = v.z; }
inline void store(float *row, float v) { row[0] = v; }

constexpr size_t dimOf(const Vec2f &) { return 2; }
constexpr size_t dimOf(const Vec3f &) { return 3; }
constexpr size_t dimOf(float) { return 1; }

/// Applies f to every row of `in` in parallel, without the GIL, into a new array.
template <size_t InDim, typename F>
auto mapRows(const PointsIn<InDim> &in, F f) {
    using Result = decltype(f(load<InDim>(nullptr)));
    constexpr size_t outDim = dimOf(Result{});
    const size_t n = in.shape(0);
    float *out = BufferPool::instance().take(n * outDim);
    const float *src = in.data();
    {
        nb::gil_scoped_release release;
        tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 1 << 14), [&](const auto &range) {
            for (size_t i = range.begin(); i != range.end(); ++i)
                store(out + i * outDim, f(load<InDim>(src + i * InDim)));
        });
    }
    // The capsule's deleter gets only the pointer: the size travels in a small heap record beside it.
    auto *block = new std::pair<float *, size_t>(out, n * outDim);
    nb::capsule owner(block, [](void *p) noexcept {
        auto *b = static_cast<std::pair<float *, size_t> *>(p);
        BufferPool::instance().release(b->first, b->second);
        delete b;
    });
    if constexpr (outDim == 1) return ValuesOut(out, {n}, owner);
    else return PointsOut<outDim>(out, {n, outDim}, owner);
}

/// A warp function as a type of its own, so that mapRows inlines it (through a function pointer every
/// sample would be an indirect call, and the loop could not be vectorised).
template <auto F>
struct Fn {
    template <typename... A>
    auto operator()(const A &...a) const { return F(a...); }
};

/// Binds a sampler and its pdf (no extra parameter) under Mitsuba's names.
template <size_t OutDim, typename Sample, typename Pdf>
void bindWarp(nb::module_ &m, const char *name, const char *pdfName, Sample sample, Pdf pdf) {
    m.def(name, [sample](const PointsIn<2> &u) { return mapRows<2>(u, sample); }, nb::arg("u"));
    m.def(pdfName, [pdf](const PointsIn<OutDim> &p) { return mapRows<OutDim>(p, pdf); }, nb::arg("p"));
}

}  // namespace

void bindRender(nb::module_ &m);  // render_binding.cpp

NB_MODULE(mcval_renderer, m) {
    m.doc() = "The mcval renderer: render(scene, ...), and the sample warps over numpy arrays of shape "
              "(N, 2) or (N, 3), float32.";
    bindRender(m);
    m.def("integrators", &integratorNames,
          "The names of the integrators this build registered, sorted (render()'s `integrator` choices).");

    bindWarp<2>(m, "square_to_uniform_square", "square_to_uniform_square_pdf",
                Fn<squareToUniformSquare>{}, Fn<squareToUniformSquarePdf>{});
    bindWarp<2>(m, "square_to_tent", "square_to_tent_pdf", Fn<squareToTent>{}, Fn<squareToTentPdf>{});
    bindWarp<2>(m, "square_to_uniform_disk", "square_to_uniform_disk_pdf",
                Fn<squareToUniformDisk>{}, Fn<squareToUniformDiskPdf>{});
    bindWarp<3>(m, "square_to_uniform_sphere", "square_to_uniform_sphere_pdf",
                Fn<squareToUniformSphere>{}, Fn<squareToUniformSpherePdf>{});
    bindWarp<3>(m, "square_to_uniform_hemisphere", "square_to_uniform_hemisphere_pdf",
                Fn<squareToUniformHemisphere>{}, Fn<squareToUniformHemispherePdf>{});
    bindWarp<3>(m, "square_to_cosine_hemisphere", "square_to_cosine_hemisphere_pdf",
                Fn<squareToCosineHemisphere>{}, Fn<squareToCosineHemispherePdf>{});

    m.def("square_to_beckmann", [](const PointsIn<2> &u, float alpha) {
        return mapRows<2>(u, [alpha](const Vec2f &s) { return squareToBeckmann(s, alpha); });
    }, nb::arg("u"), nb::arg("alpha"));
    m.def("square_to_beckmann_pdf", [](const PointsIn<3> &p, float alpha) {
        return mapRows<3>(p, [alpha](const Vec3f &v) { return squareToBeckmannPdf(v, alpha); });
    }, nb::arg("p"), nb::arg("alpha"));
}
