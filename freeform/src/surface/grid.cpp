// The bulk evaluator of a 3D double Bézier patch on a parameter grid (position + unit normal).
//
// The basis values B_j^n(v) and their derivatives are tabulated once per grid column; per grid row
// the patch collapses to two curves in v, R_j = sum_i B_i^m(u) b_ij and Q_j = sum_i B_i^m'(u) b_ij,
// so every point costs 3(n+1) multiply-adds per coordinate (f = sum B_j R_j, f_u = sum B_j Q_j,
// f_v = sum B_j' R_j) plus the cross product and one square root. Columns are processed in blocks
// of kBlock in structure-of-arrays form so that every inner loop runs across grid points and
// vectorises; the kernel is compiled for the x86-64 baseline and for x86-64-v3 (AVX2 + FMA), the
// loader picks the clone for the running CPU.

#include <cmath>
#include <limits>
#include <vector>

#include "freeform/core/bernstein.h"
#include "freeform/surface/bezier_surface.h"

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && !defined(FREEFORM_NO_CPU_DISPATCH)
#define FREEFORM_CLONES __attribute__((target_clones("arch=x86-64-v3", "default")))
#else
#define FREEFORM_CLONES
#endif

namespace freeform {

namespace {

constexpr int kBlock = 64;

FREEFORM_CLONES void gridKernel(const double* ctrl, int m, int n, const double* us, int nu, const double* vs, int nv,
                                double* positions, double* normals, unsigned char* fallback, double zeroBound)
{
    const int n1 = n + 1;
    // v basis, column-blocked: bv[j * nv + iv].
    std::vector<double> bv(static_cast<std::size_t>(n1) * nv), dbv(bv.size());
    std::vector<double> tmp(static_cast<std::size_t>(std::max(m, n) + 1)), tmp2(tmp.size()), scratch(tmp.size());
    for (int iv = 0; iv < nv; ++iv) {
        bernsteinAll(n, vs[iv], tmp.data());
        bernsteinDerivativeAll(n, 1, vs[iv], tmp2.data(), scratch.data());
        for (int j = 0; j < n1; ++j) {
            bv[static_cast<std::size_t>(j) * nv + iv] = tmp[j];
            dbv[static_cast<std::size_t>(j) * nv + iv] = tmp2[j];
        }
    }
    std::vector<double> bu(static_cast<std::size_t>(m + 1)), dbu(bu.size());
    std::vector<double> R(static_cast<std::size_t>(3 * n1)), Q(R.size());
    alignas(64) double f[3][kBlock], fu[3][kBlock], fv[3][kBlock];
    const double relative = std::numeric_limits<double>::epsilon(); // squared sqrt(eps)
    const double zero2 = zeroBound * zeroBound;
    for (int iu = 0; iu < nu; ++iu) {
        bernsteinAll(m, us[iu], bu.data());
        if (normals) bernsteinDerivativeAll(m, 1, us[iu], dbu.data(), scratch.data());
        for (int j = 0; j < n1; ++j) {
            double r[3] = {0, 0, 0}, q[3] = {0, 0, 0};
            for (int i = 0; i <= m; ++i) {
                const double* b = ctrl + 3 * (i * n1 + j);
                for (int k = 0; k < 3; ++k) {
                    r[k] += bu[i] * b[k];
                    if (normals) q[k] += dbu[i] * b[k];
                }
            }
            for (int k = 0; k < 3; ++k) {
                R[static_cast<std::size_t>(3 * j + k)] = r[k];
                Q[static_cast<std::size_t>(3 * j + k)] = q[k];
            }
        }
        for (int start = 0; start < nv; start += kBlock) {
            const int count = std::min(kBlock, nv - start);
            for (int k = 0; k < 3; ++k)
                for (int t = 0; t < count; ++t) f[k][t] = fu[k][t] = fv[k][t] = 0;
            for (int j = 0; j < n1; ++j) {
                const double* b = &bv[static_cast<std::size_t>(j) * nv + start];
                const double* db = &dbv[static_cast<std::size_t>(j) * nv + start];
                const double r0 = R[3 * j], r1 = R[3 * j + 1], r2 = R[3 * j + 2];
                for (int t = 0; t < count; ++t) {
                    f[0][t] += b[t] * r0;
                    f[1][t] += b[t] * r1;
                    f[2][t] += b[t] * r2;
                }
                if (normals) {
                    const double q0 = Q[3 * j], q1 = Q[3 * j + 1], q2 = Q[3 * j + 2];
                    for (int t = 0; t < count; ++t) {
                        fu[0][t] += b[t] * q0;
                        fu[1][t] += b[t] * q1;
                        fu[2][t] += b[t] * q2;
                        fv[0][t] += db[t] * r0;
                        fv[1][t] += db[t] * r1;
                        fv[2][t] += db[t] * r2;
                    }
                }
            }
            double* out = positions + 3 * (static_cast<std::size_t>(iu) * nv + start);
            for (int t = 0; t < count; ++t) {
                out[3 * t] = f[0][t];
                out[3 * t + 1] = f[1][t];
                out[3 * t + 2] = f[2][t];
            }
            if (!normals) continue;
            double* nout = normals + 3 * (static_cast<std::size_t>(iu) * nv + start);
            unsigned char* fb = fallback + static_cast<std::size_t>(iu) * nv + start;
            for (int t = 0; t < count; ++t) {
                const double cx = fu[1][t] * fv[2][t] - fu[2][t] * fv[1][t];
                const double cy = fu[2][t] * fv[0][t] - fu[0][t] * fv[2][t];
                const double cz = fu[0][t] * fv[1][t] - fu[1][t] * fv[0][t];
                const double c2 = cx * cx + cy * cy + cz * cz;
                const double u2 = fu[0][t] * fu[0][t] + fu[1][t] * fu[1][t] + fu[2][t] * fu[2][t];
                const double v2 = fv[0][t] * fv[0][t] + fv[1][t] * fv[1][t] + fv[2][t] * fv[2][t];
                const bool bad = !(c2 > relative * u2 * v2) || !(c2 > zero2);
                const double inv = bad ? 0.0 : 1.0 / std::sqrt(c2);
                nout[3 * t] = cx * inv;
                nout[3 * t + 1] = cy * inv;
                nout[3 * t + 2] = cz * inv;
                fb[t] = bad ? 1 : 0;
            }
        }
    }
}

} // namespace

void evaluateBezierPatchGrid(const double* ctrl, int m, int n, const double* us, int nu, const double* vs, int nv,
                             double* positions, double* normals, unsigned char* needFallback, double zeroBound)
{
    gridKernel(ctrl, m, n, us, nu, vs, nv, positions, normals, needFallback, zeroBound);
}

} // namespace freeform
