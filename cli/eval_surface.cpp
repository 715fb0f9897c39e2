// `freeform eval` for bezier_surface and deboor_surface objects: point, unit normal (limits at
// collapsed edges) and, with --derivatives K, every partial derivative up to order K.

#include <cmath>

#include "command.h"
#include "surface_objects.h"

namespace freeform::cli {
namespace {

/// "u"*a + "v"*b: the key of d^(a+b) f / du^a dv^b.
std::string derivativeKey(int a, int b)
{
    return std::string(static_cast<std::size_t>(a), 'u') + std::string(static_cast<std::size_t>(b), 'v');
}

Json evalSurface(const Document& doc, const DocumentObject& object, const std::string& at, int order)
{
    const std::vector<double> uv = parseNumberList(at, "--at", 2);
    std::array<int, 2> segments{};
    const PatchComplex complex = surfacePatches(doc, object, &segments);
    // Bézier surfaces live on [0,1]^2; de Boor surfaces on [0, Lu] x [0, Lv] (unit intervals).
    int index[2] = {0, 0};
    double local[2] = {0, 0};
    for (int d = 0; d < 2; ++d) {
        const double t = uv[static_cast<std::size_t>(d)];
        if (t < 0 || t > segments[d])
            throw Error(doc.source + ": object \"" + object.name + "\": " + (d == 0 ? "u" : "v") + " = " +
                        Json(t).dump() + " is outside the surface's domain [0, " +
                        std::to_string(segments[d]) + "]");
        index[d] = std::min(static_cast<int>(std::floor(t)), segments[d] - 1);
        local[d] = t - index[d];
    }
    const Patch& patch = complex.patches[static_cast<std::size_t>(index[0] * segments[1] + index[1])];
    const auto jet = patch.jet(local[0], local[1], order);
    const Eigen::Vector3d normal = patch.normal(local[0], local[1]);
    Json out;
    out["object"] = object.name;
    out["u"] = uv[0];
    out["v"] = uv[1];
    out["point"] = pointJson(jet.col(0).data(), 3);
    out["normal"] = pointJson(normal.data(), 3);
    if (order > 0) {
        Json ders = Json::object();
        for (int k = 1; k <= order; ++k)
            for (int a = k; a >= 0; --a)
                ders[derivativeKey(a, k - a)] = pointJson(jet.col(Patch::jetIndex(a, k - a)).data(), 3);
        out["derivatives"] = std::move(ders);
    }
    return out;
}

} // namespace

void addSurfaceEvaluators(std::map<std::string, Evaluator>& table)
{
    table["bezier_surface"] = evalSurface;
    table["deboor_surface"] = evalSurface;
}

} // namespace freeform::cli
