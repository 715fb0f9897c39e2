// The bounds of the part tessellation's grids (brep/part_mesh.h, docs/cad.md "Tessellation"): a
// rational patch's cells' certified bounds (their own sub-nets; ruled patches without their height;
// cones and surfaces of revolution from their curves), and the search for the grid with the fewest
// cells within a target. (A grid's cells and the slopes over them: part_mesh_grid.cpp.)

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <tuple>

#include "freeform/core/bernstein.h" // kMaxDegree
#include "part_mesh_internal.h"

namespace freeform::part_mesh {
namespace {

/// A patch of degree 1 in v whose weights do not change along v (w_i0 = w_i1): a cylinder, a cone,
/// a surface of linear extrusion. Its points are S(u, v) = C(u) + v D(u), with C the rational
/// curve of row 0 and D the curve of the differences P_i1 - P_i0, both with the weights w_i.
bool ruledInV(const RationalPatch& p)
{
    if (p.degreeV() != 1) return false;
    for (int i = 0; i <= p.degreeU(); ++i)
        if (p.weight(i, 0) != p.weight(i, 1)) return false;
    return true;
}

} // namespace

template <int D>
double curveBound(const Eigen::Matrix<double, D, 1>* x, const double* w, int m)
{
    Eigen::AlignedBox<double, D> box;
    for (int i = 0; i <= m; ++i) box.extend(x[i]);
    const Eigen::Matrix<double, D, 1> c = box.center();
    const double rho = 0.5 * box.diagonal().norm();
    double wmin = w[0], wmax = w[0], hh = 0, ww = 0;
    for (int i = 0; i <= m; ++i) {
        wmin = std::min(wmin, w[i]);
        wmax = std::max(wmax, w[i]);
        if (i + 2 > m) continue;
        hh = std::max(hh, (w[i + 2] * (x[i + 2] - c) - 2 * w[i + 1] * (x[i + 1] - c) + w[i] * (x[i] - c)).norm());
        ww = std::max(ww, std::abs(w[i + 2] - 2 * w[i + 1] + w[i]));
    }
    const double scale = double(m) * (m - 1) / 8;
    return (hh * scale + rho * ww * scale) / wmin + (wmax - wmin) / wmin * rho;
}
template double curveBound<2>(const Eigen::Vector2d*, const double*, int);
template double curveBound<3>(const Eigen::Vector3d*, const double*, int);

void endWeightsEqual(double* w, int m)
{
    if (m < 1) return;
    // (A square root for the arcs' degree 2, which the grid searches ask for thousands of times.)
    const double q = w[0] / w[m];
    const double ratio = m == 1 ? q : m == 2 ? std::sqrt(q) : std::pow(q, 1.0 / m);
    double factor = 1;
    for (int i = 1; i <= m; ++i) w[i] *= (factor *= ratio);
    w[m] = w[0];
}

double revolutionCellBound(const RationalPatch& cell)
{
    if (cell.degreeU() != 2) return kInf;
    const int n = cell.degreeV();
    // The row with the longest chord gives the axis (its plane's normal) and the centre.
    int jr = 0;
    double longest = -1;
    for (int j = 0; j <= n; ++j) {
        const double len = (cell.controlPoint(2, j) - cell.controlPoint(0, j)).squaredNorm();
        if (len > longest) longest = len, jr = j;
    }
    const Eigen::Vector3d p0 = cell.controlPoint(0, jr), p1 = cell.controlPoint(1, jr), p2 = cell.controlPoint(2, jr);
    Eigen::Vector3d a = (p1 - p0).cross(p2 - p0);
    if (!(a.norm() > 0)) return kInf;
    a.normalize();
    // A circular arc's middle control point is where its end tangents meet: the centre lies on the
    // line from it through the chord's midpoint M, at M - (d^2 / h^2) (P1 - M).
    const Eigen::Vector3d mid = 0.5 * (p0 + p2);
    const double h2 = (p1 - mid).squaredNorm(), d2 = (mid - p0).squaredNorm();
    if (!(h2 > 0)) return kInf;
    const Eigen::Vector3d centre = mid - (d2 / h2) * (p1 - mid);
    double z[kMaxDegree + 1], r[kMaxDegree + 1], beta[kMaxDegree + 1];
    for (int j = 0; j <= n; ++j) {
        const Eigen::Vector3d q = cell.controlPoint(0, j) - centre;
        z[j] = a.dot(q);
        r[j] = (q - z[j] * a).norm();
        beta[j] = cell.weight(0, j);
    }
    if (!(r[jr] > 0)) return kInf;
    Eigen::Vector3d c[3];
    double alpha[3];
    for (int i = 0; i <= 2; ++i) {
        const Eigen::Vector3d q = cell.controlPoint(i, jr) - centre;
        c[i] = (q - a.dot(q) * a) / r[jr];
        alpha[i] = cell.weight(i, jr) / cell.weight(0, jr);
    }
    // What the fit leaves: the points' distance from A + z_j a + r_j c_i, the weights' from
    // alpha_i beta_j (relative).
    double eps = 0, eta = 0;
    Eigen::AlignedBox3d net;
    for (int i = 0; i <= 2; ++i)
        for (int j = 0; j <= n; ++j) {
            const Eigen::Vector3d p = cell.controlPoint(i, j);
            net.extend(p);
            eps = std::max(eps, (p - (centre + z[j] * a + r[j] * c[i])).norm());
            eta = std::max(eta, std::abs(cell.weight(i, j) / (alpha[i] * beta[j]) - 1));
        }
    if (!(eta < 1e-6)) return kInf;
    Eigen::Vector2d profile[kMaxDegree + 1];
    double rmax = 0;
    for (int j = 0; j <= n; ++j) {
        profile[j] = {r[j], z[j]};
        rmax = std::max(rmax, r[j]);
    }
    const double cmax = std::max({c[0].norm(), c[1].norm(), c[2].norm()});
    // |S - S^| <= eps + 2 eta rho / (1 - eta) for the surface S^ of the fit, at both the triangle's
    // corners and the surface point: twice that, with room.
    endWeightsEqual(alpha, 2);
    endWeightsEqual(beta, n);
    return rmax * curveBound<3>(c, alpha, 2) + cmax * curveBound<2>(profile, beta, n) + 2 * eps +
           5 * eta * 0.5 * net.diagonal().norm();
}

double conicalCellBound(const RationalPatch& column, double va, double vb)
{
    const int m = column.degreeU();
    if (column.degreeV() != 1 || m < 1) return kInf;
    Eigen::Vector3d d[kMaxDegree + 1], p[kMaxDegree + 1];
    double w[kMaxDegree + 1];
    for (int i = 0; i <= m; ++i) {
        if (column.weight(i, 0) != column.weight(i, 1)) return kInf;
        p[i] = column.controlPoint(i, 0);
        d[i] = column.controlPoint(i, 1) - p[i];
        w[i] = column.weight(i, 0);
    }
    // The apex: P_i0 + s D_i the same point for every i, s by least squares against row 0.
    double num = 0, den = 0;
    for (int i = 1; i <= m; ++i) {
        num += (p[i] - p[0]).dot(d[i] - d[0]);
        den += (d[i] - d[0]).squaredNorm();
    }
    if (!(den > 0)) return kInf;
    const double s = -num / den, lambda = -s;
    const double ta = lambda + va, tb = lambda + vb;
    if (!std::isfinite(s) || ta * tb < 0) return kInf;
    Eigen::Vector3d apex = Eigen::Vector3d::Zero();
    for (int i = 0; i <= m; ++i) apex += p[i] + s * d[i];
    apex /= m + 1;
    double r = 0;
    for (int i = 0; i <= m; ++i) r = std::max(r, (p[i] + s * d[i] - apex).norm());
    endWeightsEqual(w, m);
    return std::max(std::abs(ta), std::abs(tb)) * curveBound<3>(d, w, m) + 2 * r;
}

namespace {

/// The bound of the cell [va, vb] of a column (a patch ruled in v, cut to the cell's u range),
/// which does not grow with the cell's height. With C_a = C + va D (the row at va), a parameter
/// triangle with corners (u_k, v_k) in the cell and a point of it with barycentrics l_k,
/// (u, v) = sum l_k (u_k, v_k), the mesh point T = sum l_k S(u_k, v_k) and the surface point S(u, v)
/// differ by
///   [sum l_k C_a(u_k) - C_a(u)] + sum l_k (v_k - va) (D(u_k) - D(u)).
/// The first bracket is within curveBound of the row (R_C - C_a(u), with R_C the weight-scaled
/// combination sum m_k C_a(u_k), m_k = l_k w(u_k) / sum l_k w(u_k), is at most e, and
/// sum (l_k - m_k) (C_a(u_k) - c) at most q rho). D is a convex combination of the differences
/// P_i1 - P_i0, so D(u_k) - D(u) is at most twice their box's half diagonal (`spread`, 0 on a
/// cylinder). The parameter point lies in the same triangle, so the pairing is the patch bound's.
/// On a cone, conicalCellBound is smaller where the column is narrow: this takes the smaller where
/// `curves` (no trim runs through the cell: see TrimZones).
double ruledCellBound(const RationalPatch& column, double va, double vb, bool curves, double* rowPart = nullptr)
{
    const int m = column.degreeU();
    Eigen::Vector3d row[kMaxDegree + 1];
    double w[kMaxDegree + 1];
    Eigen::AlignedBox3d differences;
    for (int i = 0; i <= m; ++i) {
        const Eigen::Vector3d d = column.controlPoint(i, 1) - column.controlPoint(i, 0);
        row[i] = column.controlPoint(i, 0) + va * d;
        w[i] = column.weight(i, 0);
        differences.extend(d);
    }
    const double spread = 0.5 * differences.diagonal().norm();
    const double rowTerms = curveBound<3>(row, w, m);
    if (rowPart) *rowPart = std::max(*rowPart, rowTerms);
    const double ruled = rowTerms + 2 * (vb - va) * spread;
    return curves ? std::min(ruled, conicalCellBound(column, va, vb)) : ruled;
}

/// Whether a search tries the whole net's bound alone before both of the net's bounds in one
/// pass (rationalBounds): the first costs one pass more where the whole net's bound is over the
/// target, the second the frame's share of the pass (on a fillet's degree (6, 10) cell about as
/// much as the rest) where it is within. Kept per search, by what the whole net's bound did in
/// the search's cells so far (within the target in half of linkrods.step's fillet cells, in one
/// of ten of screw.step's). Either way the bound is the same.
struct NetOdds {
    int within = 1, over = 0;
    bool wholeFirst() const { return within >= over; }
};

/// A cell's bound from its own sub-net, and where no trim runs through it (`curves`) the smaller of
/// that and the bounds from its curves. A search that asks only whether the bound is within
/// `enough` gets the first of the cheaper bounds that is (the revolution's where it applies, the
/// whole net's without the frame): the same answer.
double ownCellBound(const RationalPatch& cell, bool curves, double enough = 0, NetOdds* odds = nullptr)
{
    // (revolutionCellBound asks for degree 2 along the circles: computed once, where it may apply.)
    const double revolution = curves && cell.degreeU() == 2 ? revolutionCellBound(cell) : kInf;
    std::optional<double> own; // the net's full bound, where the search below computed it
    if (enough > 0) {
        if (revolution <= enough) return revolution;
        NetOdds none;
        NetOdds& o = odds ? *odds : none;
        if (o.wholeFirst()) {
            const double whole = rationalWholeNetBound(cell, 1, 1);
            ++(whole <= enough ? o.within : o.over);
            if (whole <= enough) return whole;
        } else {
            const RationalBounds net = rationalBounds(cell, 1, 1);
            ++(net.wholeNet <= enough ? o.within : o.over);
            if (net.wholeNet <= enough) return net.wholeNet;
            own = net.framed;
        }
    }
    const double net = own ? *own : rationalTessellationErrorBound(cell, 1, 1);
    if (!curves) return net;
    // (The transposed copy only where v has degree 2 too.)
    return std::min({net, revolution, cell.degreeV() == 2 ? revolutionCellBound(cell.transposed()) : kInf});
}

/// Where a search's last grid failed: the centre of its first cell over the limit, in the patch's
/// [0, 1]^2. The next grid checks the cell holding it first.
struct FailHint {
    bool set = false;
    double u = 0, v = 0;
};

/// The largest bound of the cells of an nu x nv grid on the patch. `general`: each cell's bound
/// from its own sub-net, rationalTessellationErrorBound of the cell's patch with its own centre and
/// radius, so the weights' share, (radius) x (weight differences), shrinks with the cell instead of
/// staying the whole patch's radius (a tall cylinder's quarter turn: a thousand cells fewer); on a
/// patch ruled along one side (ruledInV) the smaller of that and ruledCellBound, which leaves the
/// height out. Not `general` (a patch ruled in v): ruledCellBound alone, no cell cut along v, and
/// `rowPart` receives the largest of its row terms e + q rho, which more rows along v do not shrink.
/// Cells that no trim runs through (`zones`) also take the bounds from curves (revolution, cone).
///
/// With a `limit`, the scan stops at the first cell whose bound is over it and returns that bound:
/// whether the grid is within the limit is all a search asks, and the answer is the same. With a
/// `hint` too, the cell holding the last failed grid's first cell over the limit is checked first
/// (the grids a search tries fail mostly where the patch bends most): its sub-net is cut by the same
/// splits as the scan's, so its bound is the scan's to the bit, and a grid over the limit is mostly
/// found so at one cell. On screw.step, half the cells the searches bounded were in grids that failed.
double cellsBound(const RationalPatch& p, int nu, int nv, const TrimZones& zones, bool general = true, double* rowPart = nullptr,
                  double limit = kInf, FailHint* hint = nullptr, NetOdds* odds = nullptr)
{
    if (general && p.degreeU() == 1 && !ruledInV(p) && ruledInV(p.transposed())) {
        FailHint t;
        if (hint) t = {hint->set, hint->v, hint->u};
        const double bound = cellsBound(p.transposed(), nv, nu, zones.transposed(), true, nullptr, limit, hint ? &t : nullptr, odds);
        if (hint) *hint = {t.set, t.v, t.u};
        return bound;
    }
    const bool ruled = !general || ruledInV(p);
    if (rowPart) *rowPart = 0;
    double worst = 0;
    auto cellBound = [&](const RationalPatch& column, const RationalPatch& cell, int i, int j) {
        const bool curves = !zones.meets(double(i) / nu, double(i + 1) / nu, double(j) / nv, double(j + 1) / nv);
        // (With a limit, only whether each cell is within it counts; without, only whether it is
        // over the largest so far, and by how much: a cheaper bound within that leaves the
        // largest as it is, so the result is the same number.)
        double bound = general ? ownCellBound(cell, curves, limit < kInf ? limit : worst, odds) : kInf;
        if (ruled) bound = std::min(bound, ruledCellBound(column, double(j) / nv, double(j + 1) / nv, curves, rowPart));
        return bound;
    };
    // The column i and (when general) its cell j, as the scan below cuts them: split off the rest
    // one after the other, in place (splitOffU: splitU's points, without an allocation per cell).
    RationalPatch rest = p, column = p, restV = p, cell = p;
    auto columnOf = [&](int i) {
        rest = p;
        for (int k = 0; k <= i; ++k) {
            if (k + 1 < nu) rest.splitOffU(1.0 / (nu - k), column);
            else std::swap(column, rest);
        }
    };
    auto cellOf = [&](int j) {
        restV = column;
        for (int k = 0; k <= j; ++k) {
            if (k + 1 < nv) restV.splitOffV(1.0 / (nv - k), cell);
            else std::swap(cell, restV);
        }
    };
    if (hint && hint->set && limit < kInf && !rowPart) {
        const int i = std::clamp(static_cast<int>(hint->u * nu), 0, nu - 1), j = std::clamp(static_cast<int>(hint->v * nv), 0, nv - 1);
        columnOf(i);
        if (general) cellOf(j);
        const double bound = cellBound(column, general ? cell : column, i, j);
        if (bound > limit) return bound;
    }
    rest = p;
    for (int i = 0; i < nu; ++i) {
        if (i + 1 < nu) rest.splitOffU(1.0 / (nu - i), column);
        else std::swap(column, rest);
        if (general) restV = column;
        for (int j = 0; j < nv; ++j) {
            if (general) {
                if (j + 1 < nv) restV.splitOffV(1.0 / (nv - j), cell);
                else std::swap(cell, restV);
                worst = std::max(worst, cellBound(column, cell, i, j));
            } else {
                worst = std::max(worst, cellBound(column, column, i, j));
            }
            if (worst > limit) {
                if (hint) *hint = {true, (i + 0.5) / nu, (j + 0.5) / nv};
                return worst;
            }
        }
    }
    return worst;
}

/// The fewest columns n in [1, cap] for which `probe(n)` (the grid's bound, or over the target a
/// cell's bound over it) is within `target`, where the grids pass from some n on (the bound falls
/// as the columns narrow) and n = `failed` fails: the answer doubling and bisection give, from
/// fewer probes. A column's bound falls about as the square of its width (a circle's chords), so a
/// probe's bound b at n puts the answer near n sqrt(b / target): the next probe is there, but at
/// least a quarter of the open range on (no crawl where a share of the bound does not shrink), and
/// after a failed probe with no pass yet at most four times as far (a grid that passes is scanned
/// whole). `guess` > 0 (a like patch's answer, SearchHints): the first probe, and the next one
/// beside it. The answer is confirmed as bisection confirms it: n passes and n - 1 fails. Returns
/// cap + 1 where none passes. On screw.step it takes the ruled searches from 1.25 M instructions
/// to 0.74 M.
template <class Probe>
int fewestColumns(int cap, double target, int failed, double failedBound, int guess, Probe&& probe)
{
    auto estimate = [&](int n, double b) {
        const double e = std::ceil(n * std::sqrt(b / target));
        return e < cap ? static_cast<int>(e) : cap + 1;
    };
    int lo = failed, hi = cap + 1; // lo failed; hi passed (cap + 1: none yet)
    bool guessed = guess > failed && guess <= cap;
    int next = guessed ? guess : estimate(failed, failedBound);
    while (hi - lo > 1) {
        const int n = std::clamp(next, lo + 1, hi - 1);
        const double b = probe(n);
        if (b <= target) {
            hi = n;
            next = guessed ? n - 1 : std::min(estimate(n, b), hi - std::max(1, (hi - lo) / 4));
        } else {
            lo = n;
            next = guessed                 ? n + 1
                   : hi > cap ? std::min(std::max(estimate(n, b), n + 1), 4 * n)
                              : std::max(estimate(n, b), lo + (hi - lo) / 4);
        }
        guessed = false;
    }
    return hi;
}

/// cellsBound on a patch ruled in v with the ruled bound alone.
double ruledGridBound(const RationalPatch& p, int nu, int nv, const TrimZones& zones, double* rowPart = nullptr, double limit = kInf)
{
    return cellsBound(p, nu, nv, zones, false, rowPart, limit);
}

/// On a patch ruled in v, the grid with the fewest cells whose ruled bounds are within target,
/// if it has fewer cells than `best` (else `best`): per count along v (up to 8: the height enters
/// only through the differences' spread, which the cells' own bounds handle better where it
/// dominates), the fewest along u (fewestColumns). Where the rows alone are over the target at
/// the most columns allowed, no count along v helps and the search stops.
/// `prior`: a like patch's answers per count of rows (SearchHints); `found` receives this one's.
std::array<int, 2> fewestRuled(const RationalPatch& p, double target, std::array<int, 2> best, const TrimZones& zones,
                               const std::vector<int>* prior = nullptr, std::vector<int>* found = nullptr)
{
    long bestCells = static_cast<long>(best[0]) * best[1];
    for (int nv = 1; nv <= 8 && nv < bestCells; ++nv) {
        if (found) found->resize(static_cast<std::size_t>(nv) + 1, 0);
        const int cap = static_cast<int>(std::min<long>(4096, (bestCells - 1) / nv));
        if (cap < 1) break;
        // After one row, the most columns allowed first (fewer than one row needed, mostly): where
        // they fail, fewer fail too (the doubling would end there), and where their rows alone are
        // over the target, more rows cannot help either (the scan stops at the first cell over it:
        // rowPart is then that of the rows before).
        double rowPart = 0;
        if (nv > 1 && !(ruledGridBound(p, cap, nv, zones, &rowPart, target) <= target)) {
            if (rowPart > target) break;
            continue;
        }
        // One column first (a ruled face needs a circle's chords, few), then from its bound.
        const double one = ruledGridBound(p, 1, nv, zones, &rowPart);
        FailHint hint;
        const int guess = prior && static_cast<std::size_t>(nv) < prior->size() ? (*prior)[static_cast<std::size_t>(nv)] : 0;
        const int hi = one <= target ? 1 : fewestColumns(cap, target, 1, one, guess, [&](int n) {
            return cellsBound(p, n, nv, zones, false, nullptr, target, &hint);
        });
        if (found && hi <= cap) (*found)[static_cast<std::size_t>(nv)] = hi;
        if (hi > cap) {
            // Whether the rows alone are over the target at the most columns: from its whole scan.
            if (cap > 1) ruledGridBound(p, cap, nv, zones, &rowPart);
            if (rowPart > target) break;
            continue;
        }
        if (static_cast<long>(hi) * nv < bestCells) {
            bestCells = static_cast<long>(hi) * nv;
            best = {hi, nv};
        }
    }
    return best;
}

} // namespace

bool TrimZones::meets(double u0, double u1, double v0, double v1) const
{
    for (const Eigen::AlignedBox2d& b : boxes)
        if (b.min().x() < u1 && b.max().x() > u0 && b.min().y() < v1 && b.max().y() > v0) return true;
    return false;
}

TrimZones TrimZones::transposed() const
{
    TrimZones t;
    for (const Eigen::AlignedBox2d& b : boxes)
        t.boxes.emplace_back(Eigen::Vector2d(b.min().y(), b.min().x()), Eigen::Vector2d(b.max().y(), b.max().x()));
    return t;
}

namespace {

/// How a patch is ruled, found once per patch (not per cell probed): in v, or in u (then its
/// transposed copy, kept), or neither.
struct RuledForm {
    bool inV = false;
    std::optional<RationalPatch> transposed; // ruled in u: the patch transposed
    explicit RuledForm(const RationalPatch& p) : inV(ruledInV(p))
    {
        if (inV) return;
        RationalPatch t = p.transposed();
        if (ruledInV(t)) transposed = std::move(t);
    }
};

/// The bound of the cell [u0, u1] x [v0, v1] of a patch (`ruled`: its RuledForm), the column
/// [u0, u1] already cut from it: the smallest of the cell's own (ownCellBound) and the ruled one.
/// `cell` holds the cell's net afterwards (kept from call to call: no allocation per cell).
double cellOfColumn(const RuledForm& ruled, const RationalPatch& column, double u0, double u1, double v0, double v1,
                    const TrimZones& zones, RationalPatch& cell, double enough = 0, NetOdds* odds = nullptr)
{
    const bool curves = !zones.meets(u0, u1, v0, v1);
    column.pieceVInto(v0, v1, cell);
    double bound = ownCellBound(cell, curves, enough, odds);
    if (ruled.inV) {
        bound = std::min(bound, ruledCellBound(column, v0, v1, curves));
    } else if (ruled.transposed) {
        bound = std::min(bound, ruledCellBound(ruled.transposed->pieceU(v0, v1), u0, u1, curves));
    }
    return bound;
}

} // namespace

std::vector<double> unevenColumns(const std::vector<const RationalPatch*>& patches, const std::vector<int>& rows,
                                  const std::vector<const TrimZones*>& zones, double target, int even, double& bound)
{
    // The largest bound of the column [x0, x1]'s cells, over every patch and its rows, or the
    // first over the target; the row that was over it last time first (as cellsBound's hint).
    // The search asks only whether a column is within the target (`probe`: any bound that is
    // decides); the columns kept are bounded in full at the end.
    std::size_t hintPatch = patches.size();
    int hintRow = 0;
    RationalPatch strip = *patches.front(), cell = strip; // the column's and the cell's nets, reused
    std::vector<RuledForm> ruled;
    NetOdds odds, keptOdds; // (the probes', and the columns kept: their cells against other limits)
    for (const RationalPatch* p : patches) ruled.emplace_back(*p);
    // (Not a probe: the largest bound of the columns kept, `bound`, so far. A cell's cheaper bound
    // within the largest so far leaves it as it is, as in cellsBound.)
    auto column = [&](double x0, double x1, bool probe = true) {
        double worst = 0;
        auto cellAt = [&](std::size_t b, int j) {
            return cellOfColumn(ruled[b], strip, x0, x1, double(j) / rows[b], double(j + 1) / rows[b], *zones[b], cell,
                                probe ? target : std::max(bound, worst), probe ? &odds : &keptOdds);
        };
        if (hintPatch < patches.size()) {
            patches[hintPatch]->pieceUInto(x0, x1, strip);
            const double bound = cellAt(hintPatch, hintRow);
            if (bound > target) return bound;
        }
        for (std::size_t b = 0; b < patches.size(); ++b) {
            patches[b]->pieceUInto(x0, x1, strip);
            for (int j = 0; j < rows[b]; ++j) {
                worst = std::max(worst, cellAt(b, j));
                if (worst > target) {
                    hintPatch = b, hintRow = j;
                    return worst;
                }
            }
        }
        return worst;
    };
    const double step = 1.0 / even;
    std::vector<double> breaks{0};
    bound = 0;
    double x = 0, last = 0; // last: the width of the column before
    while (x < 1) {
        // Only fewer columns than the even ones are kept: with `even - 1` so far (or more) none
        // can be; with `even - 2`, only a last one that reaches the end.
        const int columns = static_cast<int>(breaks.size()) - 1;
        if (columns >= even - 1) return {};
        // The column's end lies in [lo, hi): a column to lo passes (none yet where lo = x), one
        // to hi does not (where hi < 1). The width of the column before is tried first, and a
        // tenth of the even width more: columns side by side mostly allow about the same, and
        // where the first passes and the second does not, the search is done.
        double lo = x, hi = 1;
        if (even >= 8 && last > 0 && x + last < 1) {
            if (column(x, x + last) <= target) {
                lo = x + last;
                const double wider = lo + 0.1 * step;
                if (wider < 1) {
                    if (column(x, wider) > target) hi = wider;
                    else lo = wider;
                }
            } else {
                hi = x + last;
            }
        }
        if (hi == 1 && column(x, 1) <= target) {
            breaks.push_back(1);
            break;
        }
        if (columns >= even - 2) return {}; // the rest does not fit in one column
        // A width that passes (from the even columns', or half the failed one, halved while it
        // does not), then doubled while it passes, then bisected to a tenth of the even width.
        if (lo == x) {
            double w = hi - x > step ? step : 0.5 * (hi - x);
            while (column(x, x + w) > target) {
                hi = x + w;
                w *= 0.5;
                if (w < 1e-3 * step) return {};
            }
            lo = x + w;
        }
        for (double t = x + 2 * (lo - x); t < hi; t = x + 2 * (lo - x)) {
            if (column(x, t) > target) {
                hi = t;
                break;
            }
            lo = t;
        }
        while (hi - lo > 0.1 * step) {
            const double mid = 0.5 * (lo + hi);
            if (column(x, mid) <= target) lo = mid;
            else hi = mid;
        }
        breaks.push_back(lo);
        last = lo - x;
        x = lo;
    }
    for (std::size_t k = 0; k + 1 < breaks.size(); ++k) bound = std::max(bound, column(breaks[k], breaks[k + 1], false));
    return breaks;
}

/// A patch whose weights differ (where the cells' own bounds beat the whole net's).
bool weighted(const RationalPatch& p)
{
    const double w0 = p.weight(0, 0);
    for (int i = 0; i <= p.degreeU(); ++i)
        for (int j = 0; j <= p.degreeV(); ++j)
            if (p.weight(i, j) != w0) return true;
    return false;
}

/// The certified bound of the patch's nu x nv grid: the smaller of the whole net's bound and the
/// cells' own (up to 4096 cells).
double gridBound(const RationalPatch& p, int nu, int nv, bool local, const TrimZones& zones)
{
    const double whole = rationalTessellationErrorBound(p, nu, nv);
    if (!local) return whole;
    NetOdds odds;
    if (nu * nv <= 4096) return std::min(whole, cellsBound(p, nu, nv, zones, true, nullptr, kInf, nullptr, &odds));
    // A ruled patch's search may go past 4096 cells (fewestRuled): its rows of cells are few.
    if (nv <= 64 && ruledInV(p)) return std::min(whole, ruledGridBound(p, nu, nv, zones));
    if (nu <= 64 && ruledInV(p.transposed())) return std::min(whole, ruledGridBound(p.transposed(), nv, nu, zones.transposed()));
    return whole;
}

std::array<double, 6> SearchHints::cornerDistances(const RationalPatch& p)
{
    const int m = p.degreeU(), n = p.degreeV();
    const Eigen::Vector3d c[4] = {p.controlPoint(0, 0), p.controlPoint(m, 0), p.controlPoint(0, n), p.controlPoint(m, n)};
    return {(c[0] - c[1]).norm(), (c[0] - c[2]).norm(), (c[0] - c[3]).norm(),
            (c[1] - c[2]).norm(), (c[1] - c[3]).norm(), (c[2] - c[3]).norm()};
}

const SearchHints::Answers* SearchHints::like(const RationalPatch& p) const
{
    const std::array<double, 6> d = cornerDistances(p);
    const double size = *std::max_element(d.begin(), d.end());
    for (const Seen& s : seen_) {
        if (s.degreeU != p.degreeU() || s.degreeV != p.degreeV()) continue;
        bool same = true;
        for (std::size_t k = 0; k < d.size() && same; ++k) same = std::abs(d[k] - s.corners[k]) <= 1e-9 * size;
        for (int i = 0, x = 0; i <= p.degreeU() && same; ++i)
            for (int j = 0; j <= p.degreeV() && same; ++j, ++x)
                same = std::abs(p.weight(i, j) - s.weights[static_cast<std::size_t>(x)]) <= 1e-12 * s.weights[static_cast<std::size_t>(x)];
        if (same) return &s.answers;
    }
    return nullptr;
}

void SearchHints::add(const RationalPatch& p, Answers answers)
{
    Seen s{p.degreeU(), p.degreeV(), {}, cornerDistances(p), std::move(answers)};
    for (int i = 0; i <= p.degreeU(); ++i)
        for (int j = 0; j <= p.degreeV(); ++j) s.weights.push_back(p.weight(i, j));
    seen_.push_back(std::move(s));
}

/// The grid with the fewest cells whose bound is at most target: from the whole net's bound
/// (rationalAdaptiveSegments), then, on a weighted patch of at most 1024 such cells, the fewest
/// cells whose own bounds are within it.
std::array<int, 2> patchSegments(const RationalPatch& p, double target, const TrimZones& zones, SearchHints* hints)
{
    std::array<int, 2> best = rationalAdaptiveSegments(p, target);
    if (!weighted(p)) return best;
    const SearchHints::Answers* prior = hints ? hints->like(p) : nullptr;
    SearchHints::Answers found;
    if (ruledInV(p)) {
        best = fewestRuled(p, target, best, zones, prior ? &prior->ruled : nullptr, &found.ruled);
    } else if (ruledInV(p.transposed())) {
        const std::array<int, 2> t =
            fewestRuled(p.transposed(), target, {best[1], best[0]}, zones.transposed(), prior ? &prior->ruled : nullptr, &found.ruled);
        best = {t[1], t[0]};
    }
    if (best[0] * best[1] <= 1024) {
        // Per count along the shorter side, the fewest cells along the other by bisection (the cells'
        // bound falls as they narrow).
        const std::array<int, 2> upper = best;
        const int a = upper[0] <= upper[1] ? 0 : 1, b = 1 - a; // a: the axis with fewer cells
        FailHint hint;
        NetOdds odds;
        auto bound = [&](int na, int nb) {
            return a == 0 ? cellsBound(p, na, nb, zones, true, nullptr, target, &hint, &odds)
                          : cellsBound(p, nb, na, zones, true, nullptr, target, &hint, &odds);
        };
        for (int na = 1; na <= upper[a] && na < best[0] * best[1]; ++na) {
            // Only nb <= cap can beat the best so far: the same result as searching up to upper[b].
            const int cap = std::min(upper[b], (best[0] * best[1] - 1) / na);
            int lo = 1, hi = cap;
            // A like patch's answer first: where it passes and one fewer fails, two probes are the
            // search (and the grid of cap cells, which passes where fewer do, is not scanned);
            // otherwise bisection goes on from what they showed.
            const std::size_t k = static_cast<std::size_t>(na);
            bool passes = false; // whether hi is known to pass
            if (const int g = prior && k < prior->sides.size() ? prior->sides[k] : 0; g >= lo && g < hi) {
                if (bound(na, g) <= target) {
                    hi = g;
                    passes = true;
                    if (g > lo) {
                        if (bound(na, g - 1) > target) lo = g;
                        else hi = g - 1;
                    }
                } else {
                    lo = g + 1;
                }
            }
            if (!passes && bound(na, cap) > target) continue;
            while (lo < hi) {
                const int mid = lo + (hi - lo) / 2;
                if (bound(na, mid) <= target) hi = mid;
                else lo = mid + 1;
            }
            if (found.sides.size() <= k) found.sides.resize(k + 1, 0);
            found.sides[k] = lo;
            if (na * lo < best[0] * best[1]) {
                best[static_cast<std::size_t>(a)] = na;
                best[static_cast<std::size_t>(b)] = lo;
            }
        }
    }
    // The first patch of its kind gives the start for those like it.
    if (hints && !prior) hints->add(p, std::move(found));
    return best;
}

} // namespace freeform::part_mesh
