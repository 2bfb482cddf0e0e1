// Python bindings: the warps over whole numpy arrays (no Python call per sample).
#include <algorithm>
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
#include "../warp_batch.h"

namespace nb = nanobind;
using namespace mcval;

namespace {

template <size_t Dim>
using PointsIn = nb::ndarray<const float, nb::shape<-1, Dim>, nb::c_contig, nb::device::cpu>;
template <size_t Dim>
using PointsOut = nb::ndarray<nb::numpy, float, nb::shape<-1, Dim>>;
using ValuesOut = nb::ndarray<nb::numpy, float, nb::shape<-1>>;

/// Rows per task: large enough that a task costs far more than scheduling it.
constexpr size_t kRowsPerTask = 1 << 16;

/// Applies a batch warp to every row of `in` in parallel, without the GIL, into a new array of
/// OutDim columns (1: a vector).
template <size_t InDim, size_t OutDim, typename Batch>
auto mapRows(const PointsIn<InDim> &in, Batch batch) {
    const size_t n = in.shape(0);
    float *out = BufferPool::instance().take(std::max<size_t>(n * OutDim, 1));
    const float *src = in.data();
    {
        nb::gil_scoped_release release;
        tbb::parallel_for(tbb::blocked_range<size_t>(0, n, kRowsPerTask), [&](const auto &range) {
            batch(src + range.begin() * InDim, out + range.begin() * OutDim, range.size());
        });
    }
    // The capsule's deleter gets only the pointer: the size travels in a small heap record beside it.
    auto *block = new std::pair<float *, size_t>(out, std::max<size_t>(n * OutDim, 1));
    nb::capsule owner(block, [](void *p) noexcept {
        auto *b = static_cast<std::pair<float *, size_t> *>(p);
        BufferPool::instance().release(b->first, b->second);
        delete b;
    });
    if constexpr (OutDim == 1) return ValuesOut(out, {n}, owner);
    else return PointsOut<OutDim>(out, {n, OutDim}, owner);
}

/// Binds a sampler and its pdf (no extra parameter) under Mitsuba's names.
template <size_t OutDim>
void bindWarp(nb::module_ &m, const char *name, const char *pdfName, WarpBatch sample, WarpBatch pdf) {
    m.def(name, [sample](const PointsIn<2> &u) { return mapRows<2, OutDim>(u, sample); }, nb::arg("u"));
    m.def(pdfName, [pdf](const PointsIn<OutDim> &p) { return mapRows<OutDim, 1>(p, pdf); }, nb::arg("p"));
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
                squareToUniformSquareBatch, squareToUniformSquarePdfBatch);
    bindWarp<2>(m, "square_to_tent", "square_to_tent_pdf", squareToTentBatch, squareToTentPdfBatch);
    bindWarp<2>(m, "square_to_uniform_disk", "square_to_uniform_disk_pdf",
                squareToUniformDiskBatch, squareToUniformDiskPdfBatch);
    bindWarp<3>(m, "square_to_uniform_sphere", "square_to_uniform_sphere_pdf",
                squareToUniformSphereBatch, squareToUniformSpherePdfBatch);
    bindWarp<3>(m, "square_to_uniform_hemisphere", "square_to_uniform_hemisphere_pdf",
                squareToUniformHemisphereBatch, squareToUniformHemispherePdfBatch);
    bindWarp<3>(m, "square_to_cosine_hemisphere", "square_to_cosine_hemisphere_pdf",
                squareToCosineHemisphereBatch, squareToCosineHemispherePdfBatch);

    m.def("square_to_beckmann", [](const PointsIn<2> &u, float alpha) {
        return mapRows<2, 3>(u, [alpha](const float *in, float *out, size_t n) { squareToBeckmannBatch(in, out, n, alpha); });
    }, nb::arg("u"), nb::arg("alpha"));
    m.def("square_to_beckmann_pdf", [](const PointsIn<3> &p, float alpha) {
        return mapRows<3, 1>(p, [alpha](const float *in, float *out, size_t n) { squareToBeckmannPdfBatch(in, out, n, alpha); });
    }, nb::arg("p"), nb::arg("alpha"));
}
