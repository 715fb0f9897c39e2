// CPU-dispatched instantiations of the batch curve evaluator (see curve/batch.h).
//
// Each kernel is compiled twice: for the x86-64 baseline and for x86-64-v3 (AVX2 + FMA); the
// dynamic loader picks the clone for the running CPU. Other targets get the baseline only.

#include "freeform/curve/batch.h"

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && !defined(FREEFORM_NO_CPU_DISPATCH)
#define FREEFORM_CLONES __attribute__((target_clones("arch=x86-64-v3", "default")))
#else
#define FREEFORM_CLONES
#endif

namespace freeform {

namespace {
#define FREEFORM_BATCH(Scalar, Dim)                                                                  \
    FREEFORM_CLONES void batch_##Scalar##_##Dim(const Scalar* ctrl, int n, const Scalar* ts,          \
                                                std::size_t count, Scalar* out)                      \
    {                                                                                                \
        detail::bezierBatchKernel<Scalar, Dim>(ctrl, n, ts, count, out);                             \
    }
FREEFORM_BATCH(float, 2)
FREEFORM_BATCH(float, 3)
FREEFORM_BATCH(double, 2)
FREEFORM_BATCH(double, 3)
#undef FREEFORM_BATCH
} // namespace

template <>
void evaluateBezierBatch<float, 2>(const float* c, int n, const float* t, std::size_t k, float* o) { batch_float_2(c, n, t, k, o); }
template <>
void evaluateBezierBatch<float, 3>(const float* c, int n, const float* t, std::size_t k, float* o) { batch_float_3(c, n, t, k, o); }
template <>
void evaluateBezierBatch<double, 2>(const double* c, int n, const double* t, std::size_t k, double* o) { batch_double_2(c, n, t, k, o); }
template <>
void evaluateBezierBatch<double, 3>(const double* c, int n, const double* t, std::size_t k, double* o) { batch_double_3(c, n, t, k, o); }

} // namespace freeform
