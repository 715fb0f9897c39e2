#pragma once
// The leaf triangulation of both certified tessellations: the patch tessellation's leaves
// (tessellate/tessellate_local.cpp) and the subdivision surfaces' (subdivision/
// certified_tessellation_common.h) are convex rings in their integer parameters, their corners and
// the points that neighbouring leaves put inside their sides, cut into triangles here without a
// new vertex (docs/surfaces.md, "Local refinement"; docs/subdivision.md).
//
// The ring is convex and counter-clockwise, so an ear is a corner b (neighbours a and c) that turns
// left, orient(a, b, c) > 0, and whose cut does not leave the rest of the ring on the line ac. For a
// convex ring that is the same as "no other point of the ring in the closed triangle abc": a point
// of the ring on the segment ac makes the chain from c to a straight. Every convex ring with a
// positive area has such an ear, and cutting one leaves a convex ring with a positive area, so
// the triangulation always ends with n - 2 triangles, each of positive area, none with a ring point
// inside an edge of another. orient must be exact (integer parameters).
//
// The two tessellations take the ears in different orders, kept so that their meshes stay what
// they were: the patch tessellation the ear whose new edge is shortest in space (its cost), the
// subdivision surfaces the next ear from where the last was cut (FirstEarInTurn).

#include <cstddef>
#include <limits>
#include <type_traits>
#include <vector>

namespace freeform::detail {

/// The order that takes, each time, the first ear at or after the place of the last one cut.
struct FirstEarInTurn {};

/// Whether ring[k] is an ear of the convex counter-clockwise ring (above).
template <class Orient>
bool isConvexRingEar(const std::vector<int>& ring, std::size_t k, const Orient& orient)
{
    const std::size_t n = ring.size();
    const int a = ring[(k + n - 1) % n], b = ring[k], c = ring[(k + 1) % n];
    if (!(orient(a, b, c) > 0)) return false; // a point inside a side
    for (std::size_t r = (k + 2) % n; r != (k + n - 1) % n; r = (r + 1) % n)
        if (orient(a, c, ring[r]) != 0) return true;
    return false; // the rest on the line ac
}

/// Cuts the convex counter-clockwise ring (point indices; cut down to its last triangle) into ring.size() - 2 triangles,
/// emit(a, b, c) each, counter-clockwise. orient(a, b, c): a number with the sign of twice the signed
/// area of the points a, b, c, exact. order: FirstEarInTurn, or cost(a, c), the ear whose new edge
/// ac costs least (the first in the ring of equal ones). False when the ring was no convex ring of a
/// positive area (no ear, or a flat last triangle): what was cut is emitted, the rest is not.
template <class Orient, class Emit, class Order>
bool clipConvexRing(std::vector<int>& ring, const Orient& orient, const Emit& emit, const Order& order)
{
    std::size_t start = 0; // FirstEarInTurn: where the search begins
    while (ring.size() > 3) {
        const std::size_t n = ring.size();
        std::size_t best = n;
        if constexpr (std::is_same_v<Order, FirstEarInTurn>) {
            for (std::size_t s = 0; s < n && best == n; ++s)
                if (isConvexRingEar(ring, (start + s) % n, orient)) best = (start + s) % n;
        } else {
            auto bestCost = std::numeric_limits<decltype(order(ring[0], ring[1]))>::infinity();
            for (std::size_t k = 0; k < n; ++k) {
                const auto cost = order(ring[(k + n - 1) % n], ring[(k + 1) % n]);
                if (cost >= bestCost || !isConvexRingEar(ring, k, orient)) continue;
                best = k;
                bestCost = cost;
            }
        }
        if (best == n) return false;
        emit(ring[(best + n - 1) % n], ring[best], ring[(best + 1) % n]);
        ring.erase(ring.begin() + static_cast<std::ptrdiff_t>(best));
        start = best % ring.size();
    }
    if (ring.size() != 3 || !(orient(ring[0], ring[1], ring[2]) > 0)) return false;
    emit(ring[0], ring[1], ring[2]);
    return true;
}

} // namespace freeform::detail
