// The edge samples of the part tessellation (brep/part_mesh.h, docs/cad.md "Tessellation"): how far
// a polygon side's stretch of surface lies from its trim (EdgeUse::deviation), and the samples of
// an edge, shared by the faces that use it (sampleEdge).

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <utility>
#include <vector>

#include "freeform/core/bernstein.h" // kMaxDegree
#include "part_mesh_internal.h"

namespace freeform::part_mesh {
namespace {

/// A side over its deviation target is cut in half only while its bound less the snap's part is
/// over this share of the target (so a trim outside the face's box, whose snap alone passes the
/// target, gets a bound a little over that part instead of samples up to the cap).
constexpr double kCuttable = 0.05;

/// A Bézier piece of a trim, cut from its pieces without allocating: degree p, homogeneous control
/// points (w x, w y, w). The cuts are BezierCurve::split's de Casteljau steps, to the bit.
struct CutPiece {
    int p = 0;
    std::array<Eigen::Vector3d, kMaxDegree + 1> h;

    int degree() const { return p; }
    double weight(int i) const { return h[static_cast<std::size_t>(i)].z(); }
    Eigen::Vector2d controlPoint(int i) const { return h[static_cast<std::size_t>(i)].head<2>() / weight(i); }
    /// Keeps the part over [t, 1]: in place, the de Casteljau triangle's right side is left in h.
    void keepAfter(double t)
    {
        for (int k = 1; k <= p; ++k) level(k, t);
    }
    /// Keeps the part over [0, t]: the triangle's left side, the first point of each level.
    void keepBefore(double t)
    {
        std::array<Eigen::Vector3d, kMaxDegree + 1> left;
        left[0] = h[0];
        for (int k = 1; k <= p; ++k) {
            level(k, t);
            left[static_cast<std::size_t>(k)] = h[0];
        }
        std::copy_n(left.begin(), p + 1, h.begin()); // (not all kMaxDegree + 1)
    }

private:
    /// Level k of the de Casteljau triangle at t, in place over h[0 .. p - k].
    void level(int k, double t)
    {
        const double s = 1 - t;
        for (std::size_t i = 0; i <= static_cast<std::size_t>(p - k); ++i) h[i] = s * h[i] + t * h[i + 1];
    }
};

/// A bound on how far the trim's pieces (consecutive, from pa to pb) lie from the chord from pa to
/// pb, in the form the face's bound needs: a continuous pairing of every trim point with a chord
/// point, each pair within the bound (so every point between the chord and the trim, which the
/// straight segments between pairs sweep, is within it of the trim; docs/cad.md, "The bound").
///
/// Where every control point projects onto the chord (not beyond its ends), the pairing is the
/// projection, and a piece's distance from the chord's line is sum w_i B_i h_i / sum w_i B_i with
/// h_i its control points' distances. With H the larger end distance and H' the largest interior
/// one, that is at most H + (H' - H) f, where f bounds the interior points' share of the weight:
/// the ends' Bernstein polynomials sum to at least 2^(1-p), so
/// f <= a (1 - x) / (a (1 - x) + b x), x = 2^(1-p), a the largest interior weight and b the smaller
/// end weight. On a circular arc with equal end weights this is its sagitta exactly; on a
/// polynomial quadratic, half its control point's distance. Otherwise, the control points'
/// largest distance from the chord (the pieces lie in their hull).
struct SideDeviation {
    double distance = 0;      // along `normal` when alongNormal, else in any direction
    double slack = 0;         // alongNormal: and at most this much along the chord
    bool alongNormal = false;
    Eigen::Vector2d normal = Eigen::Vector2d::Zero();
};
SideDeviation sideDeviation(const std::vector<CutPiece>& cut, const Eigen::Vector2d& pa,
                            const Eigen::Vector2d& pb)
{
    const Eigen::Vector2d d = pb - pa;
    const double len2 = d.squaredNorm();
    double hull = 0, line = 0, over = 0;
    const Eigen::Vector2d n = len2 > 0 ? Eigen::Vector2d(Eigen::Vector2d(-d.y(), d.x()) / std::sqrt(len2)) : Eigen::Vector2d::Zero();
    for (const CutPiece& piece : cut) {
        const int p = piece.degree();
        double ends = 0, interior = 0, wIn = 0;
        const double wEnd = std::min(piece.weight(0), piece.weight(p));
        for (int i = 0; i <= p; ++i) {
            const Eigen::Vector2d q = piece.controlPoint(i) - pa;
            const double t = len2 > 0 ? q.dot(d) / len2 : 0.0;
            over = std::max({over, -t, t - 1});
            hull = std::max(hull, (q - std::clamp(t, 0.0, 1.0) * d).norm());
            const double h = std::abs(q.dot(n));
            if (i == 0 || i == p) {
                ends = std::max(ends, h);
            } else {
                interior = std::max(interior, h);
                wIn = std::max(wIn, piece.weight(i));
            }
        }
        double bound = ends;
        if (interior > ends) {
            const double x = std::ldexp(1.0, 1 - p);
            const double share = wIn * (1 - x) / (wIn * (1 - x) + wEnd * x);
            bound = ends + (interior - ends) * std::min(1.0, share);
        }
        line = std::max(line, bound);
    }
    // Control points a hair past the chord's ends (rounding, where a piece ends at pa or pb): the
    // pairing clamps to the end, a tangential part of at most that much.
    const double slack = std::max(over, 0.0) * std::sqrt(len2);
    if (len2 > 0 && over <= 1e-6 && line + slack < hull) return {line, slack, true, n};
    return {hull, 0, false, n};
}

} // namespace

double EdgeUse::deviation(double ta, double tb, double enough, double* moved, bool* tightest) const
{
    if (tightest) *tightest = true;
    const MappedCurve<2>& c = trim->curve;
    const double ca = trimParameter(ta), cb = trimParameter(tb);
    const double lo = std::min(ca, cb), hi = std::max(ca, cb);
    // The trim's Bézier pieces over [lo, hi], cut by de Casteljau (no knot insertion: a cut a
    // hair from a knot would leave a span too short for its ratios); a periodic trim is
    // unrolled and, where [lo, hi] runs over the end of its period, taken in two pieces.
    // (One buffer per thread: the samples of an edge bound thousands of sides.)
    thread_local std::vector<CutPiece> cut;
    cut.clear();
    auto addPiece = [&](double s0, double s1) {
        const std::vector<double>& b = c.nurbs.breakpoints();
        const std::size_t first = static_cast<std::size_t>(
            std::max<std::ptrdiff_t>(0, std::upper_bound(b.begin(), b.end(), s0) - b.begin() - 1));
        for (std::size_t k = first; k + 1 < b.size() && b[k] < s1; ++k) {
            const double w = b[k + 1] - b[k];
            const double a = std::clamp((s0 - b[k]) / w, 0.0, 1.0), e = std::clamp((s1 - b[k]) / w, 0.0, 1.0);
            if (!(e > a)) continue;
            CutPiece& piece = cut.emplace_back();
            piece.p = c.nurbs.degree();
            const auto hom = c.nurbs.homogeneousPiece(k); // (in place)
            for (int i = 0; i <= piece.p; ++i) piece.h[static_cast<std::size_t>(i)] = hom.col(i);
            if (a > 0) piece.keepAfter(a);
            const double e2 = a > 0 ? (e - a) / (1 - a) : e;
            if (e2 < 1) piece.keepBefore(e2);
        }
    };
    const double s0 = trimNurbsParameter(lo);
    double s1 = trimNurbsParameter(hi);
    if (c.map.kind == ParameterMap::Kind::Identity && c.map.period > 0) {
        s1 = s0 + (hi - lo);
        const double end = c.nurbs.domainEnd();
        if (s1 > end) {
            addPiece(s0, end);
            addPiece(c.nurbs.domainStart(), std::min(end, s1 - c.map.period));
        } else {
            addPiece(s0, s1);
        }
    } else {
        if (!(s1 > s0)) return kInf;
        addPiece(s0, s1);
    }
    const Eigen::Vector2d pa = trimPoint(ca), pb = trimPoint(cb);
    const Eigen::Vector2d d = pb - pa;
    const SideDeviation dev = sideDeviation(cut, pa, pb);
    Eigen::Vector2d qlo = pa.cwiseMin(pb), qhi = pa.cwiseMax(pb);
    for (const CutPiece& piece : cut)
        for (int i = 0; i <= piece.degree(); ++i) {
            qlo = qlo.cwiseMin(piece.controlPoint(i));
            qhi = qhi.cwiseMax(piece.controlPoint(i));
        }
    const auto [u1, u2] = grid->mu.slopes(qlo.x(), qhi.x());
    const auto [v1, v2] = grid->mv.slopes(qlo.y(), qhi.y());
    // The surface's slopes over the side's box (the cell it lies in, once cut at its crossings).
    const Eigen::Vector2d ra = grid->toS(pa), rb = grid->toS(pb);
    const Eigen::Vector2d slo = grid->toS(qlo).cwiseMin(ra).cwiseMin(rb), shi = grid->toS(qhi).cwiseMax(ra).cwiseMax(rb);
    const auto [lu, lv] = grid->slopesOver(slo, shi);
    // The maps bend the file chord's image off the chord from ra to rb by at most u2 dx^2 / 8
    // along s and v2 dy^2 / 8 along r (monotone maps: inside the chord's box, so every point
    // projects onto the chord). Only the part across the chord counts: the circle that ends a
    // cylinder (an iso line, dy = 0, the chord along s) stays on its line.
    const Eigen::Vector2d chord = rb - ra;
    const double length = chord.norm(), bendS = 0.125 * u2 * d.x() * d.x(), bendR = 0.125 * v2 * d.y() * d.y();
    double rest = length > 0 ? (lu * std::abs(chord.y()) + lv * std::abs(chord.x())) * (bendS * std::abs(chord.y()) + bendR * std::abs(chord.x())) /
                                   (length * length)
                             : lu * bendS + lv * bendR;
    // The snap moves the side's ends (pa, pb are the trim's points there): its points move by
    // a convex combination of the two moves.
    const Eigen::Vector2d snapA = (grid->snap(ra) - ra).cwiseAbs(), snapB = (grid->snap(rb) - rb).cwiseAbs();
    const double snapped = lu * std::max(snapA.x(), snapB.x()) + lv * std::max(snapA.y(), snapB.y());
    rest += snapped;
    if (moved) *moved = snapped;
    // A pair's parameters differ by (du, dv): its surface points by at most lu |du| + lv |dv|.
    // The trim against the file chord: along the chord's normal where the pairing is the
    // projection, any direction otherwise; the maps scale u by at most u1 and v by v1.
    const double anyWay = std::hypot(lu * u1, lv * v1);
    if (!dev.alongNormal) return anyWay * dev.distance + rest;
    const double perAxis = (lu * u1 * std::abs(dev.normal.x()) + lv * v1 * std::abs(dev.normal.y())) * dev.distance + anyWay * dev.slack + rest;
    // Where the maps are the identity (planes, B-splines), the pairs differ along n itself and
    // the slope along n is bounded from the cell's net directly (exact on a plane, where
    // |n_u| lu + |n_v| lv would be up to sqrt 2 times it); not where the slopes' bound is
    // already `enough`.
    if (!(u1 == 1 && v1 == 1 && u2 == 0 && v2 == 0)) return perAxis;
    if (perAxis <= enough) {
        if (tightest) *tightest = false;
        return perAxis;
    }
    return std::min(perAxis, grid->slopeAlong(slo, shi, dev.normal) * dev.distance + anyWay * dev.slack + rest);
}

namespace {

/// Where the use's trim crosses the grid line `line` of `axis` between ta and tb, the side from ta
/// lying `below` it: the bracket [lo, hi] shrunk until its ends are neighbouring doubles (their
/// middle returned) or a point lands on the line, as bisection would end. Regula falsi with the
/// Illinois rule (the end that stays twice has its value halved); after a step that did not halve
/// the bracket, a step just past the root the last secant points to (twice its distance, and a
/// few units in the last place more), so that the far end closes in too; where that does not
/// halve the bracket either, a halving. Per crossing, bisection took 49 of the trim's points on
/// screw.step, regula falsi alone 19 (its far end stayed until halved), and this takes 7.8 (6.9 on
/// linkrods.step, against 15.5). The crossing found is the same up to the last bits (where the
/// trim's computed coordinate is not monotone within them, or lands on the line).
double crossingParameter(const EdgeUse& use, double ta, double tb, const Eigen::Vector2d& rawA, const Eigen::Vector2d& rawB,
                         int axis, double line, bool below)
{
    double lo = ta, hi = tb;
    // The values at the ends (rawA, rawB: raw() there), signed so that the `below` end is
    // negative; the snap may have put an end's raw point on the other side of the line (within
    // the snapping distance): then halve. flo and fhi are the Illinois rule's (halved) values,
    // vlo and vhi the true ones.
    double vlo = rawA[axis] - line, vhi = rawB[axis] - line;
    if (!below) vlo = -vlo, vhi = -vhi;
    double flo = vlo, fhi = vhi;
    enum class Step { Secant, Past, Halve };
    Step next = flo < 0 && fhi > 0 ? Step::Secant : Step::Halve;
    double past = 0;
    int kept = 0; // +1: lo stayed at the last step, -1: hi did
    for (int it = 0; it < 200; ++it) {
        const double mid = 0.5 * (lo + hi);
        if (mid <= lo || mid >= hi) break;
        double t = mid;
        if (next == Step::Secant) {
            const double r = lo + (hi - lo) * (flo / (flo - fhi));
            if (r > lo && r < hi) t = r;
        } else if (next == Step::Past && past > lo && past < hi) {
            t = past;
        }
        double f = use.raw(t)[axis] - line;
        if (f == 0) return t;
        if (!below) f = -f;
        const double width = hi - lo;
        // The slope through t and the true value at the end that stays.
        const double slope = f < 0 ? (vhi - f) / (hi - t) : (f - vlo) / (t - lo);
        if (f < 0) {
            lo = t, flo = f, vlo = f;
            if (kept == -1) fhi *= 0.5;
            kept = -1;
        } else {
            hi = t, fhi = f, vhi = f;
            if (kept == 1) flo *= 0.5;
            kept = 1;
        }
        const bool halved = hi - lo <= 0.5 * width;
        if (halved || next == Step::Past || !(slope > 0) || !std::isfinite(slope)) {
            next = halved && flo < 0 && fhi > 0 ? Step::Secant : Step::Halve;
            continue;
        }
        // Past the root the secant through t points to, away from t: the far end moves in.
        const double ulps = 4 * (std::nextafter(t, kInf) - t);
        past = f < 0 ? t + 2 * (-f / slope) + ulps : t - 2 * (f / slope) - ulps;
        next = Step::Past;
    }
    return 0.5 * (lo + hi);
}

/// A cache from a key (a parameter, or a side's two) to a value, for one edge's samples: open
/// addressing in one array that the next edge reuses (clear() is one increment: a slot holds a
/// value only if it carries the current generation). The keys compare with ==, as
/// std::unordered_map's do (-0 and 0 alike: the hash takes -0 as 0). sampleEdge asked the
/// allocator for a node per parameter and per side it cached, and a bucket array per use and edge
/// (the allocator took a third of bearing.iges's mesh; these caches, a sixth of that).
template <class Key, class Value, class Hash>
class FlatCache {
public:
    void clear()
    {
        count_ = 0;
        if (++generation_ == 0) { // (after 2^32 edges: wipe once)
            for (Slot& s : slots_) s.generation = 0;
            generation_ = 1;
        }
    }
    /// The value for key, and whether it was just added (then the caller sets it).
    std::pair<Value*, bool> tryEmplace(const Key& key)
    {
        if (2 * (count_ + 1) > slots_.size()) grow();
        Slot* s = probe(key);
        if (s->generation == generation_) return {&s->value, false};
        s->key = key;
        s->generation = generation_;
        ++count_;
        return {&s->value, true};
    }
    const Value* find(const Key& key) const
    {
        if (slots_.empty()) return nullptr;
        const std::size_t mask = slots_.size() - 1;
        for (std::size_t i = Hash()(key) & mask;; i = (i + 1) & mask) {
            const Slot& s = slots_[i];
            if (s.generation != generation_) return nullptr;
            if (s.key == key) return &s.value;
        }
    }

private:
    struct Slot {
        Key key{};
        Value value;
        std::uint32_t generation = 0;
    };
    Slot* probe(const Key& key)
    {
        const std::size_t mask = slots_.size() - 1;
        for (std::size_t i = Hash()(key) & mask;; i = (i + 1) & mask) {
            Slot& s = slots_[i];
            if (s.generation != generation_ || s.key == key) return &s;
        }
    }
    void grow()
    {
        std::vector<Slot> old;
        old.swap(slots_);
        slots_.resize(std::max<std::size_t>(16, 2 * old.size())); // (generation 0: empty)
        count_ = 0;
        for (Slot& s : old)
            if (s.generation == generation_) {
                *probe(s.key) = s;
                ++count_;
            }
    }
    std::vector<Slot> slots_;
    std::size_t count_ = 0;
    std::uint32_t generation_ = 1;
};

// (Hashes of the parameters' bits, mixed: std::hash<double> hashes their bytes one by one, 1.5% of
// screw.step's mesh. -0 is 0 first, as == takes them equal.)
struct ParameterHash {
    std::size_t operator()(double t) const
    {
        std::uint64_t x = std::bit_cast<std::uint64_t>(t == 0 ? 0.0 : t);
        x = (x ^ (x >> 31)) * 0x9E3779B97F4A7C15u;
        return static_cast<std::size_t>(x ^ (x >> 29));
    }
};
struct SideHash {
    std::size_t operator()(const std::pair<double, double>& side) const
    {
        return ParameterHash()(side.first) * 1000003u ^ ParameterHash()(side.second);
    }
};

/// What one use of an edge has found so far: its raw point at each sample, and the sides it kept
/// after bounding their deviation (with the bound, and whether that is the tightest one).
struct Kept {
    double deviation = 0;
    bool tightest = false;
};
struct UseCache {
    FlatCache<double, Eigen::Vector2d, ParameterHash> rawAt;
    FlatCache<std::pair<double, double>, Kept, SideHash> kept;
};

} // namespace

std::vector<double> sampleEdge(const std::vector<EdgeUse>& uses, double first, double last, int maxSamples,
                               std::vector<double>& worst)
{
    std::vector<double> ts{first, last};
    const double minStep = 1e-12 * std::max(1.0, std::abs(last - first));
    // What each use has found so far (UseCache). Each round walks every side again after the other
    // uses' cuts; a side kept stays kept, and only the new sides are bounded (on screw.step this
    // halved the bounds computed). (The caches, the walk's stack and its output: one set per
    // thread, reused from edge to edge.)
    thread_local std::vector<UseCache> caches;
    thread_local std::vector<std::pair<double, int>> stack;
    thread_local std::vector<double> out;
    if (caches.size() < uses.size()) caches.resize(uses.size());
    for (std::size_t u = 0; u < uses.size(); ++u) {
        caches[u].rawAt.clear();
        caches[u].kept.clear();
    }
    auto raw = [&](std::size_t u, double t) {
        const auto [value, fresh] = caches[u].rawAt.tryEmplace(t);
        if (fresh) *value = uses[u].raw(t);
        return *value;
    };
    for (int round = 0; round < 16; ++round) {
        bool changed = false;
        for (std::size_t u = 0; u < uses.size(); ++u) {
            const EdgeUse& use = uses[u];
            out.assign(1, ts.front());
            // Depth-first over the sides; each is cut at a crossing or in half until it passes.
            for (std::size_t k = 0; k + 1 < ts.size(); ++k) {
                stack.assign(1, {ts[k + 1], 0});
                double ta = ts[k];
                Eigen::Vector2d rawA = raw(u, ta), a = use.grid->snap(rawA); // at(ta), kept while ta is
                while (!stack.empty()) {
                    const auto [tb, depth] = stack.back();
                    const Eigen::Vector2d rawB = raw(u, tb), b = use.grid->snap(rawB);
                    if (caches[u].kept.find({ta, tb})) {
                        out.push_back(tb);
                        ta = tb;
                        rawA = rawB;
                        a = b;
                        stack.pop_back();
                        continue;
                    }
                    const auto [axis, line] = use.grid->crossing(a, b);
                    const std::size_t count = out.size() + stack.size() + (ts.size() - k - 1); // samples so far
                    const bool full = count >= static_cast<std::size_t>(std::max(maxSamples, 2));
                    // Every crossing of a grid line must be a sample (the face's cells are walked
                    // from one to the next): where the cap stops that, the mesh cannot be made.
                    if (axis >= 0 && full)
                        throw Error("tessellatePart: an edge needs more than " + std::to_string(maxSamples) +
                                    " samples at this tolerance (PartMeshOptions::maxEdgeSamples); use a coarser tolerance");
                    const bool room = depth < 200 && tb - ta > minStep && !full;
                    double cut = std::numeric_limits<double>::quiet_NaN();
                    int parts = 2;
                    bool crossed = false;
                    if (axis >= 0 && room) {
                        crossed = true;
                        cut = crossingParameter(use, ta, tb, rawA, rawB, axis, line, a[axis] < line);
                        if (!(cut > ta && cut < tb)) cut = std::numeric_limits<double>::quiet_NaN();
                    } else if (room) {
                        // Cut while that can still help: not where what is left over the target
                        // is the snap's part (a trim outside the face's box). The rest of the
                        // term shrinks as the square of the side's length (the pcurve's sagitta,
                        // the maps' bend), so the side is cut into as many equal parts as bring
                        // it to the target at that rate (checked again all the same); halving
                        // left sides between a quarter of the target and all of it.
                        double moved = 0;
                        bool tightest = true;
                        const double target = use.deviationTarget;
                        const double deviation = use.deviation(ta, tb, target, &moved, &tightest);
                        if (deviation > target && deviation - moved > kCuttable * target) {
                            const double ratio = (deviation - moved) / std::max(target - moved, kCuttable * target);
                            parts = static_cast<int>(std::clamp(std::ceil(std::sqrt(ratio)), 2.0, 16.0));
                            cut = ta + (tb - ta) / parts;
                        } else {
                            *caches[u].kept.tryEmplace({ta, tb}).first = Kept{deviation, tightest};
                        }
                    }
                    if (std::isnan(cut)) {
                        out.push_back(tb);
                        ta = tb;
                        rawA = rawB;
                        a = b;
                        stack.pop_back();
                    } else {
                        // A cut at a crossing leaves the rest of the side one grid line fewer to
                        // cross: its depth stays (an edge along thousands of grid lines is cut at
                        // each), while cuts into parts count towards the depth limit.
                        if (!crossed) stack.back().second = depth + 1;
                        for (int p = parts - 1; p >= 2; --p) stack.push_back({ta + (tb - ta) * p / parts, depth + 1});
                        stack.push_back({cut, depth + 1});
                        changed = true;
                    }
                }
            }
            ts.swap(out);
        }
        if (!changed) break;
    }
    // Crossings found for two faces at one point (a vertex on both faces' grid lines) differ in the
    // last bits: keep one sample (the snap puts it on both lines).
    const double merge = 1e-10 * std::abs(last - first);
    std::vector<double> merged{ts.front()};
    for (std::size_t k = 1; k + 1 < ts.size(); ++k)
        if (ts[k] - merged.back() > merge && ts.back() - ts[k] > merge) merged.push_back(ts[k]);
    merged.push_back(ts.back());
    ts = std::move(merged);
    // A sample that a face's snap puts within the snapping distance of the next one makes a side
    // of no real length whose direction is noise: where the trim meets a grid line at a tangent or
    // at its apex (a slot's end on a cylinder's seam), the snapped side can run back along the line,
    // out of the cell that holds its neighbours. Such a sample goes, for every face alike, unless a
    // face would then lose a grid line's crossing.
    auto at = [&](std::size_t u, double t) { return uses[u].grid->snap(raw(u, t)); };
    auto tiny = [&](double ta, double tb) {
        for (std::size_t u = 0; u < uses.size(); ++u) {
            const Eigen::Vector2d d = (at(u, ta) - at(u, tb)).cwiseAbs();
            if (d.x() <= uses[u].grid->snapU && d.y() <= uses[u].grid->snapV) return true;
        }
        return false;
    };
    auto crosses = [&](double ta, double tb) {
        for (std::size_t u = 0; u < uses.size(); ++u)
            if (uses[u].grid->crossing(at(u, ta), at(u, tb)).first >= 0) return true;
        return false;
    };
    merged.assign(1, ts.front());
    for (std::size_t k = 1; k + 1 < ts.size(); ++k)
        if (!((tiny(merged.back(), ts[k]) || tiny(ts[k], ts[k + 1])) && !crosses(merged.back(), ts[k + 1]))) merged.push_back(ts[k]);
    merged.push_back(ts.back());
    ts = std::move(merged);
    worst.assign(uses.size(), 0);
    for (std::size_t u = 0; u < uses.size(); ++u)
        for (std::size_t k = 0; k + 1 < ts.size(); ++k) {
            const Kept* it = caches[u].kept.find({ts[k], ts[k + 1]});
            const double deviation = it && it->tightest ? it->deviation : uses[u].deviation(ts[k], ts[k + 1]);
            worst[u] = std::max(worst[u], deviation);
        }
    return ts;
}

} // namespace freeform::part_mesh
