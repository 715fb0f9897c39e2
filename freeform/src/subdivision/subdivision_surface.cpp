// SubdivisionSurface through OpenSubdiv's Bfr (docs/subdivision.md): the cage adapter
// (Far::TopologyDescriptor with creases and corners), one Bfr::Surface per face, limit evaluation,
// the watertight tessellation (Bfr::Tessellation patterns, points on shared cage edges made once),
// and the tie to the Bézier core (regular faces through the tensor-product A-frame).

#include "freeform/subdivision/subdivision_surface.h"

#include "freeform/core/format.h"
#include "freeform/core/warning.h"

#include <opensubdiv/bfr/refinerSurfaceFactory.h>
#include <opensubdiv/bfr/surface.h>
#include <opensubdiv/bfr/tessellation.h>
#include <opensubdiv/far/error.h>
#include <opensubdiv/far/topologyDescriptor.h>
#include <opensubdiv/far/topologyRefinerFactory.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <mutex>
#include <unordered_map>

#include "certified_tessellation_common.h"
#include "freeform/mesh/topology.h"
#include "freeform/tessellate/tessellate.h"
#include "osd_errors.h"

namespace freeform {

namespace {
thread_local std::string osdErrorMessage;
void osdError(osd::Far::ErrorType, const char* message)
{
    if (osdErrorMessage.empty()) osdErrorMessage = std::string("OpenSubdiv: ") + message;
}
} // namespace

// An error is not thrown from the callback: the exception would pass through OpenSubdiv's factory,
// which holds what it allocated in raw pointers until it returns (LeakSanitizer found the leak).
// The first message of a call is kept and thrown once the call has returned (takeOsdError).
void clearOsdError() { osdErrorMessage.clear(); }

void takeOsdError()
{
    if (osdErrorMessage.empty()) return;
    const std::string message = std::move(osdErrorMessage);
    osdErrorMessage.clear();
    throw Error(message);
}

namespace {

// OpenSubdiv's default callbacks print "Warning: ..." / "Error: ..." on stdout, where the CLI's
// one JSON object goes (docs/cli.md). Its warnings go to the caller's warning handler
// (freeform/core/warning.h); its errors become Errors.
void osdWarning(const char* message) { warn(std::string("OpenSubdiv: ") + message); }
void installOsdCallbacks()
{
    static std::once_flag once;
    std::call_once(once, [] {
        osd::Far::SetWarningCallback(osdWarning);
        osd::Far::SetErrorCallback(osdError);
    });
}

std::uint64_t edgeKey(int a, int b)
{
    const auto lo = static_cast<std::uint32_t>(std::min(a, b)), hi = static_cast<std::uint32_t>(std::max(a, b));
    return (static_cast<std::uint64_t>(lo) << 32) | hi;
}

std::uint64_t directedKey(int a, int b)
{
    return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) | static_cast<std::uint32_t>(b);
}

std::string cageEdgeName(int a, int b) { return "edge " + std::to_string(a) + "-" + std::to_string(b); }

bool validSharpness(double s) { return std::isfinite(s) && s >= 0; }

} // namespace

SubdivisionScheme parseSubdivisionScheme(const std::string& text, const std::string& what)
{
    if (text == "catmark") return SubdivisionScheme::Catmark;
    if (text == "loop") return SubdivisionScheme::Loop;
    throw Error(what + ": \"" + text + "\" is not one of catmark, loop");
}

std::string toString(SubdivisionScheme scheme) { return scheme == SubdivisionScheme::Loop ? "loop" : "catmark"; }

BoundaryInterpolation parseBoundaryInterpolation(const std::string& text, const std::string& what)
{
    if (text == "none") return BoundaryInterpolation::None;
    if (text == "edge_only") return BoundaryInterpolation::EdgeOnly;
    if (text == "edge_and_corner") return BoundaryInterpolation::EdgeAndCorner;
    throw Error(what + ": \"" + text + "\" is not one of none, edge_only, edge_and_corner");
}

std::string toString(BoundaryInterpolation boundary)
{
    switch (boundary) {
    case BoundaryInterpolation::None: return "none";
    case BoundaryInterpolation::EdgeAndCorner: return "edge_and_corner";
    default: return "edge_only";
    }
}

SubdivisionScheme defaultScheme(const PolygonMesh& mesh)
{
    return mesh.faceCount() > 0 && mesh.isTriangleMesh() ? SubdivisionScheme::Loop : SubdivisionScheme::Catmark;
}

void validateCage(const SubdivisionCage& cage, SubdivisionScheme scheme, const std::string& what)
{
    const PolygonMesh& mesh = cage.mesh;
    mesh.validate(what); // index range, >= 3 corners, no repeated vertex, finite positions
    if (mesh.faceCount() == 0) throw Error(what + ": has no faces");
    if (scheme == SubdivisionScheme::Loop)
        for (int f = 0; f < mesh.faceCount(); ++f)
            if (mesh.faceSize(f) != 3)
                throw Error(what + ": face " + std::to_string(f) + " has " + std::to_string(mesh.faceSize(f)) +
                            " vertices; the Loop scheme needs triangles (use catmark)");

    // Every directed edge once (consistent orientation), every edge in at most two faces.
    std::unordered_map<std::uint64_t, int> directed;
    std::unordered_map<std::uint64_t, int> undirected;
    for (int f = 0; f < mesh.faceCount(); ++f) {
        const int n = mesh.faceSize(f);
        for (int k = 0; k < n; ++k) {
            const int a = mesh.face(f)[k], b = mesh.face(f)[(k + 1) % n];
            const auto [it, fresh] = directed.emplace(directedKey(a, b), f);
            if (!fresh)
                throw Error(what + ": " + cageEdgeName(a, b) + " runs the same way in faces " + std::to_string(it->second) +
                            " and " + std::to_string(f) + " (inconsistent orientation or a non-manifold edge)");
            if (++undirected[edgeKey(a, b)] > 2)
                throw Error(what + ": " + cageEdgeName(a, b) + " has more than two faces (face " + std::to_string(f) +
                            " is the third): the cage is not manifold");
        }
    }
    const MeshReport report = meshReport(mesh);
    if (!report.nonManifoldVertices.empty()) {
        const auto& v = report.nonManifoldVertices.front();
        throw Error(what + ": vertex " + std::to_string(v.vertex) + " joins " + std::to_string(v.fanCount) +
                    " separate fans of faces: the cage is not manifold");
    }
    const int vertices = mesh.vertexCount();
    // The faces of each edge, and how many edges each pair of faces shares: OpenSubdiv (Debian's
    // 3.5.0) does not find an edge whose two faces share another edge as well, and reads
    // uninitialised memory when a crease names it (found by fuzz_cage), so such a crease is refused
    // here. Holes must name faces.
    std::unordered_map<std::uint64_t, std::vector<int>> edgeFaceList;
    if (!cage.creases.empty())
        for (int f = 0; f < mesh.faceCount(); ++f)
            for (int k = 0; k < mesh.faceSize(f); ++k)
                edgeFaceList[edgeKey(mesh.face(f)[k], mesh.face(f)[(k + 1) % mesh.faceSize(f)])].push_back(f);
    std::unordered_map<std::uint64_t, int> sharedByPair;
    for (const auto& [edge, faces] : edgeFaceList)
        if (faces.size() == 2) ++sharedByPair[edgeKey(faces[0], faces[1])];
    for (std::size_t i = 0; i < cage.holes.size(); ++i)
        if (cage.holes[i] < 0 || cage.holes[i] >= mesh.faceCount())
            throw Error(what + ": hole " + std::to_string(i) + ": face " + std::to_string(cage.holes[i]) + " is out of range");
    for (std::size_t i = 0; i < cage.creases.size(); ++i) {
        const EdgeCrease& c = cage.creases[i];
        const std::string name = what + ": crease " + std::to_string(i) + " (" + cageEdgeName(c.v0, c.v1) + ")";
        if (c.v0 < 0 || c.v0 >= vertices || c.v1 < 0 || c.v1 >= vertices)
            throw Error(name + ": vertex index out of range 0.." + std::to_string(vertices - 1));
        if (!undirected.count(edgeKey(c.v0, c.v1))) throw Error(name + ": the cage has no such edge");
        const auto faces = edgeFaceList.find(edgeKey(c.v0, c.v1));
        if (faces != edgeFaceList.end() && faces->second.size() == 2 && sharedByPair[edgeKey(faces->second[0], faces->second[1])] > 1)
            throw Error(name + ": its faces " + std::to_string(faces->second[0]) + " and " + std::to_string(faces->second[1]) +
                        " share another edge too; OpenSubdiv cannot place a crease there");
        if (!validSharpness(c.sharpness)) throw Error(name + ": sharpness must be finite and >= 0");
    }
    for (std::size_t i = 0; i < cage.corners.size(); ++i) {
        const VertexCorner& c = cage.corners[i];
        const std::string name = what + ": corner " + std::to_string(i) + " (vertex " + std::to_string(c.vertex) + ")";
        if (c.vertex < 0 || c.vertex >= vertices)
            throw Error(name + ": vertex index out of range 0.." + std::to_string(vertices - 1));
        if (!validSharpness(c.sharpness)) throw Error(name + ": sharpness must be finite and >= 0");
    }
}

// ------------------------------------------------------------------------ topology

struct SubdivisionSurface::Topology {
    SubdivisionScheme scheme = SubdivisionScheme::Catmark;
    BoundaryInterpolation boundary = BoundaryInterpolation::EdgeOnly;
    std::unique_ptr<osd::Far::TopologyRefiner> refiner;
    std::unique_ptr<osd::Bfr::RefinerSurfaceFactory<>> factory;
    std::vector<osd::Bfr::Surface<double>> surfaces; // per face; invalid when it has no limit surface
    std::vector<int> patchOffset;                    // F + 1 offsets (in points) into the patch points
    std::unordered_map<std::uint64_t, std::array<int, 2>> directed; // (a, b) -> (face, corner of a)
    std::unordered_map<std::uint64_t, int> edgeFaces;               // {a, b} -> number of faces
    std::vector<int> valence;                                       // faces at each vertex
    std::vector<char> boundaryVertex, sharpVertex;                  // on a boundary edge; touched by sharpness

    const osd::Bfr::Surface<double>& surface(int f) const { return surfaces[static_cast<std::size_t>(f)]; }
};

SubdivisionSurface::SubdivisionSurface(SubdivisionCage cage, SubdivisionScheme scheme, BoundaryInterpolation boundary)
    : cage_(std::move(cage))
{
    validateCage(cage_, scheme);
    installOsdCallbacks();
    auto topo = std::make_shared<Topology>();
    topo->scheme = scheme;
    topo->boundary = boundary;
    const PolygonMesh& mesh = cage_.mesh;
    const int faces = mesh.faceCount();

    std::vector<int> counts(static_cast<std::size_t>(faces));
    for (int f = 0; f < faces; ++f) counts[static_cast<std::size_t>(f)] = mesh.faceSize(f);
    const detail::Sharpness sharp = detail::cageSharpness(cage_, false);
    const osd::Far::TopologyDescriptor desc = detail::topologyDescriptor(mesh.vertexCount(), counts, mesh.faceVertices, sharp, &cage_.holes);
    // The cage's interpolateboundary tag stands in for the default; an explicit other choice that
    // contradicts it is an Error rather than a silent pick.
    if (cage_.boundary && *cage_.boundary != boundary) {
        if (boundary != BoundaryInterpolation::EdgeOnly)
            throw Error("cage: its interpolateboundary tag says " + toString(*cage_.boundary) + ", the boundary asked for is " +
                        toString(boundary));
        boundary = *cage_.boundary;
        topo->boundary = boundary;
    }
    if (cage_.smoothTriangles && scheme != SubdivisionScheme::Catmark)
        throw Error("cage: the smoothtriangles tag applies to Catmark only");

    const osd::Sdc::SchemeType type = scheme == SubdivisionScheme::Loop ? osd::Sdc::SCHEME_LOOP : osd::Sdc::SCHEME_CATMARK;
    topo->refiner = detail::makeRefiner(desc, type, detail::sdcOptions(cage_, boundary), "cage: OpenSubdiv could not build the topology");
    topo->factory = std::make_unique<osd::Bfr::RefinerSurfaceFactory<>>(*topo->refiner);

    topo->surfaces.resize(static_cast<std::size_t>(faces));
    topo->patchOffset.assign(static_cast<std::size_t>(faces) + 1, 0);
    for (int f = 0; f < faces; ++f) {
        auto& s = topo->surfaces[static_cast<std::size_t>(f)];
        if (!topo->factory->InitVertexSurface<double>(f, &s)) s.Clear();
        topo->patchOffset[static_cast<std::size_t>(f) + 1] =
            topo->patchOffset[static_cast<std::size_t>(f)] + (s.IsValid() ? s.GetNumPatchPoints() : 0);
    }

    // Adjacency for the regular neighbourhoods.
    topo->valence.assign(static_cast<std::size_t>(mesh.vertexCount()), 0);
    topo->boundaryVertex.assign(static_cast<std::size_t>(mesh.vertexCount()), 0);
    topo->sharpVertex.assign(static_cast<std::size_t>(mesh.vertexCount()), 0);
    for (int f = 0; f < faces; ++f) {
        const int n = mesh.faceSize(f);
        for (int k = 0; k < n; ++k) {
            const int a = mesh.face(f)[k], b = mesh.face(f)[(k + 1) % n];
            topo->directed[directedKey(a, b)] = {f, k};
            ++topo->edgeFaces[edgeKey(a, b)];
            ++topo->valence[static_cast<std::size_t>(a)];
        }
    }
    for (int f = 0; f < faces; ++f) {
        const int n = mesh.faceSize(f);
        for (int k = 0; k < n; ++k) {
            const int a = mesh.face(f)[k], b = mesh.face(f)[(k + 1) % n];
            if (topo->edgeFaces[edgeKey(a, b)] == 1)
                topo->boundaryVertex[static_cast<std::size_t>(a)] = topo->boundaryVertex[static_cast<std::size_t>(b)] = 1;
        }
    }
    for (const EdgeCrease& c : cage_.creases)
        if (c.sharpness > 0) topo->sharpVertex[static_cast<std::size_t>(c.v0)] = topo->sharpVertex[static_cast<std::size_t>(c.v1)] = 1;
    for (const VertexCorner& c : cage_.corners)
        if (c.sharpness > 0) topo->sharpVertex[static_cast<std::size_t>(c.vertex)] = 1;

    topology_ = std::move(topo);
    *this = withPositions(cage_.mesh.positions);
}

SubdivisionSurface::~SubdivisionSurface() = default;
SubdivisionSurface::SubdivisionSurface(const SubdivisionSurface&) = default;
SubdivisionSurface& SubdivisionSurface::operator=(const SubdivisionSurface&) = default;
SubdivisionSurface::SubdivisionSurface(SubdivisionSurface&&) noexcept = default;
SubdivisionSurface& SubdivisionSurface::operator=(SubdivisionSurface&&) noexcept = default;

SubdivisionSurface SubdivisionSurface::withPositions(const Eigen::Matrix<double, 3, Eigen::Dynamic>& positions) const
{
    if (positions.cols() != cage_.mesh.positions.cols())
        throw Error("cage: " + std::to_string(positions.cols()) + " positions for " +
                    std::to_string(cage_.mesh.positions.cols()) + " vertices");
    requireFinite(positions, "cage positions");
    SubdivisionSurface out(*this);
    out.cage_.mesh.positions = positions;
    out.patchPoints_.assign(static_cast<std::size_t>(topology_->patchOffset.back()) * 3, 0.0);
    const osd::Bfr::Surface<double>::PointDescriptor pd(3);
    for (int f = 0; f < faceCount(); ++f) {
        const auto& s = topology_->surface(f);
        if (!s.IsValid()) continue;
        s.PreparePatchPoints(out.cage_.mesh.positions.data(), pd,
                             out.patchPoints_.data() + 3 * topology_->patchOffset[static_cast<std::size_t>(f)], pd);
    }
    return out;
}

const SubdivisionCage& SubdivisionSurface::cage() const { return cage_; }
SubdivisionScheme SubdivisionSurface::scheme() const { return topology_->scheme; }
BoundaryInterpolation SubdivisionSurface::boundary() const { return topology_->boundary; }
int SubdivisionSurface::faceCount() const { return cage_.mesh.faceCount(); }

bool SubdivisionSurface::hasLimitSurface(int face) const
{
    return face >= 0 && face < faceCount() && topology_->surface(face).IsValid();
}

bool SubdivisionSurface::isRegularPatch(int face) const
{
    return hasLimitSurface(face) && topology_->surface(face).IsRegular();
}

bool SubdivisionSurface::inDomain(int face, double u, double v) const
{
    if (!hasLimitSurface(face) || !std::isfinite(u) || !std::isfinite(v)) return false;
    const osd::Bfr::Parameterization p = topology_->surface(face).GetParameterization();
    switch (p.GetType()) {
    case osd::Bfr::Parameterization::QUAD: return u >= 0 && u <= 1 && v >= 0 && v <= 1;
    case osd::Bfr::Parameterization::TRI: return u >= 0 && v >= 0 && u + v <= 1;
    default: {
        const double uv[2] = {u, v};
        double sub[2];
        const int k = p.ConvertCoordToNormalizedSubFace(uv, sub);
        return u >= 0 && v >= 0 && k >= 0 && k < p.GetFaceSize() && sub[0] >= 0 && sub[0] <= 1 && sub[1] >= 0 && sub[1] <= 1;
    }
    }
}

namespace {

LimitPoint limitPoint(const osd::Bfr::Surface<double>& s, const double* patch, double u, double v)
{
    const osd::Bfr::Surface<double>::PointDescriptor pd(3);
    LimitPoint out;
    const double uv[2] = {u, v};
    s.Evaluate(uv, patch, pd, out.position.data(), out.du.data(), out.dv.data());
    const Eigen::Vector3d c = out.du.cross(out.dv);
    const double len = c.norm();
    if (len > 0 && std::isfinite(len)) out.normal = c / len;
    return out;
}

} // namespace

LimitPoint SubdivisionSurface::evaluate(int face, double u, double v) const
{
    if (face < 0 || face >= faceCount())
        throw Error("subdivision surface: face " + std::to_string(face) + " is out of range 0.." + std::to_string(faceCount() - 1));
    if (!hasLimitSurface(face))
        throw Error("subdivision surface: face " + std::to_string(face) + " has no limit surface (boundary interpolation none)");
    if (!inDomain(face, u, v)) {
        throw Error("subdivision surface: (u, v) = (" + formatNumber(u) + ", " + formatNumber(v) +
                    ") is outside the domain of face " + std::to_string(face));
    }
    return limitPoint(topology_->surface(face), patchPoints_.data() + 3 * topology_->patchOffset[static_cast<std::size_t>(face)], u, v);
}

// ------------------------------------------------------------------------ the tie to the Bézier core

std::optional<std::array<int, 16>> SubdivisionSurface::regularNeighbourhood(int face) const
{
    const Topology& t = *topology_;
    const PolygonMesh& mesh = cage_.mesh;
    if (t.scheme != SubdivisionScheme::Catmark || face < 0 || face >= faceCount() || mesh.faceSize(face) != 4) return std::nullopt;
    for (int k = 0; k < 4; ++k) {
        const auto v = static_cast<std::size_t>(mesh.face(face)[k]);
        if (t.valence[v] != 4 || t.boundaryVertex[v]) return std::nullopt;
    }
    // Cell (r, c), r, c in 0..2, is the quad G(r,c) G(r+1,c) G(r+1,c+1) G(r,c+1); the face is cell (1, 1).
    std::array<int, 16> g;
    g.fill(-1);
    auto at = [&](int r, int c) -> int& { return g[static_cast<std::size_t>(r * 4 + c)]; };
    at(1, 1) = mesh.face(face)[0];
    at(2, 1) = mesh.face(face)[1];
    at(2, 2) = mesh.face(face)[2];
    at(1, 2) = mesh.face(face)[3];
    const int order[8][2] = {{0, 1}, {2, 1}, {1, 0}, {1, 2}, {0, 0}, {2, 0}, {0, 2}, {2, 2}};
    for (const auto& cell : order) {
        const int cr[4][2] = {{cell[0], cell[1]}, {cell[0] + 1, cell[1]}, {cell[0] + 1, cell[1] + 1}, {cell[0], cell[1] + 1}};
        int k = 0;
        while (k < 4 && (at(cr[k][0], cr[k][1]) < 0 || at(cr[(k + 1) % 4][0], cr[(k + 1) % 4][1]) < 0)) ++k;
        if (k == 4) return std::nullopt;
        const auto it = t.directed.find(directedKey(at(cr[k][0], cr[k][1]), at(cr[(k + 1) % 4][0], cr[(k + 1) % 4][1])));
        if (it == t.directed.end()) return std::nullopt;
        const int f = it->second[0], m = it->second[1];
        if (mesh.faceSize(f) != 4) return std::nullopt;
        for (int j = 0; j < 4; ++j) {
            const int v = mesh.face(f)[(m + j) % 4];
            int& slot = at(cr[(k + j) % 4][0], cr[(k + j) % 4][1]);
            if (slot < 0) slot = v;
            else if (slot != v) return std::nullopt;
        }
    }
    std::array<int, 16> sorted = g;
    std::sort(sorted.begin(), sorted.end());
    if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end()) return std::nullopt;
    for (int v : g)
        if (t.sharpVertex[static_cast<std::size_t>(v)]) return std::nullopt;
    return g;
}

std::optional<Patch> SubdivisionSurface::bezierPatch(int face) const
{
    const auto ring = regularNeighbourhood(face);
    if (!ring) return std::nullopt;
    PointMatrix<double, 3> deBoor(3, 16);
    for (int i = 0; i < 16; ++i) deBoor.col(i) = cage_.mesh.positions.col((*ring)[static_cast<std::size_t>(i)]);
    return deboorSurfacePatches(deBoor, 4, 4, EndCondition::Open, EndCondition::Open).patches.front();
}

PatchComplex SubdivisionSurface::regularBezierPatches(std::vector<int>* faces) const
{
    PatchComplex out;
    if (faces) faces->clear();
    for (int f = 0; f < faceCount(); ++f) {
        if (auto p = bezierPatch(f)) {
            out.patches.push_back(std::move(*p));
            if (faces) faces->push_back(f);
        }
    }
    return out;
}

// ------------------------------------------------------------------------ tessellation

namespace {

/// Segments n such that (Muu/8 + Muv/4 + Mvv/8) / n^2 <= tolerance, from second derivatives
/// sampled at the interior points of a rate-4 pattern (an estimate for faces without a Bézier
/// patch). The face's corners are left out: at an extraordinary or sharp vertex the second
/// derivatives of the limit surface can be unbounded.
int estimatedRate(const osd::Bfr::Surface<double>& s, const double* patch, double tolerance, int maxLevel)
{
    const osd::Bfr::Tessellation pattern(s.GetParameterization(), 4);
    std::vector<double> coords(static_cast<std::size_t>(pattern.GetNumInteriorCoords()) * 2);
    pattern.GetInteriorCoords(coords.data());
    const osd::Bfr::Surface<double>::PointDescriptor pd(3);
    double muu = 0, muv = 0, mvv = 0;
    for (std::size_t i = 0; i < coords.size(); i += 2) {
        Eigen::Vector3d p, du, dv, duu, duv, dvv;
        s.Evaluate(&coords[i], patch, pd, p.data(), du.data(), dv.data(), duu.data(), duv.data(), dvv.data());
        muu = std::max(muu, duu.norm());
        muv = std::max(muv, duv.norm());
        mvv = std::max(mvv, dvv.norm());
    }
    const double need = std::ceil(std::sqrt((muu / 8 + muv / 4 + mvv / 8) / tolerance));
    return static_cast<int>(std::clamp(need, 1.0, static_cast<double>(maxLevel)));
}

} // namespace

PolygonMesh SubdivisionSurface::tessellate(const SubdivisionTessellationOptions& options,
                                           SubdivisionTessellationReport* report) const
{
    if (options.maxLevel < 1) throw Error("subdivision tessellation: maxLevel must be at least 1");
    if (!(options.tolerance >= 0) || !std::isfinite(options.tolerance))
        throw Error("subdivision tessellation: the tolerance must be finite and >= 0");
    if (options.tolerance == 0 && (options.level < 1 || options.level > options.maxLevel))
        throw Error("subdivision tessellation: level " + std::to_string(options.level) + " is outside 1.." +
                    std::to_string(options.maxLevel));
    const Topology& t = *topology_;
    // The certified path (docs/subdivision.md, "Certified tessellation"): every Catmull-Clark cage,
    // holes, boundary none, smooth triangles and smooth boundary corners (edge_only, a boundary
    // vertex of one face) included.
    if (options.tolerance > 0 && options.certified && t.scheme == SubdivisionScheme::Catmark)
        return tessellateCertified(options, report);
    // Loop cages: every cage, with boundaries (any interpolation), holes, creases and corners
    // (certified_tessellation_loop.cpp; docs/subdivision.md, "Loop cages").
    if (options.tolerance > 0 && options.certified && t.scheme == SubdivisionScheme::Loop) return tessellateCertifiedLoop(options, report);
    const PolygonMesh& cageMesh = cage_.mesh;
    const int faces = faceCount();
    auto patchOf = [&](int f) { return patchPoints_.data() + 3 * t.patchOffset[static_cast<std::size_t>(f)]; };

    // Rates per face, then per edge (the larger of its faces).
    std::vector<int> rate(static_cast<std::size_t>(faces), 0);
    int regular = 0;
    for (int f = 0; f < faces; ++f) {
        if (!t.surface(f).IsValid()) continue;
        int& r = rate[static_cast<std::size_t>(f)];
        if (options.tolerance == 0) {
            r = options.level;
        } else if (const auto patch = bezierPatch(f)) {
            const auto n = adaptiveSegments(*patch, options.tolerance, options.maxLevel);
            r = std::max(n[0], n[1]);
            ++regular;
        } else {
            r = estimatedRate(t.surface(f), patchOf(f), options.tolerance, options.maxLevel);
        }
    }
    std::unordered_map<std::uint64_t, int> edgeRate;
    for (int f = 0; f < faces; ++f) {
        const int n = cageMesh.faceSize(f);
        for (int k = 0; k < n; ++k) {
            int& r = edgeRate[edgeKey(cageMesh.face(f)[k], cageMesh.face(f)[(k + 1) % n])];
            r = std::max(r, rate[static_cast<std::size_t>(f)]);
        }
    }

    std::vector<Eigen::Vector3d> positions, normals;
    std::vector<int> triangles;
    std::vector<int> vertexOut(static_cast<std::size_t>(cageMesh.vertexCount()), -1);
    struct EdgePoints {
        int from = -1, first = -1;
    };
    std::unordered_map<std::uint64_t, EdgePoints> edgePoints;
    std::vector<double> coords;
    std::vector<int> facets, index, rates;
    const osd::Bfr::Tessellation::Options tessOptions;

    for (int f = 0; f < faces; ++f) {
        const auto& s = t.surface(f);
        if (!s.IsValid()) continue;
        const double* patch = patchOf(f);
        const int n = cageMesh.faceSize(f);
        const int* fv = cageMesh.face(f);
        rates.resize(static_cast<std::size_t>(n));
        for (int k = 0; k < n; ++k) rates[static_cast<std::size_t>(k)] = edgeRate[edgeKey(fv[k], fv[(k + 1) % n])];
        const osd::Bfr::Tessellation pattern(s.GetParameterization(), n, rates.data(), tessOptions);
        coords.resize(static_cast<std::size_t>(pattern.GetNumCoords()) * 2);
        pattern.GetCoords(coords.data());
        facets.resize(static_cast<std::size_t>(pattern.GetNumFacets()) * 3);
        pattern.GetFacets(facets.data());
        index.assign(static_cast<std::size_t>(pattern.GetNumCoords()), -1);

        auto emit = [&](int coord) {
            const double* uv = &coords[static_cast<std::size_t>(coord) * 2];
            LimitPoint p = limitPoint(s, patch, uv[0], uv[1]);
            if (p.normal.isZero(0.0)) {
                // f_u x f_v vanishes here: the normal approached from the face centre.
                double centre[2];
                s.GetParameterization().GetCenterCoord(centre);
                const double w = 1e-7;
                p.normal = limitPoint(s, patch, (1 - w) * uv[0] + w * centre[0], (1 - w) * uv[1] + w * centre[1]).normal;
            }
            positions.push_back(p.position);
            normals.push_back(p.normal);
            return static_cast<int>(positions.size()) - 1;
        };

        // Boundary coordinates come first: corner k, then the points inside edge k, for every k.
        int c = 0;
        for (int k = 0; k < n; ++k) {
            int& corner = vertexOut[static_cast<std::size_t>(fv[k])];
            if (corner < 0) corner = emit(c);
            index[static_cast<std::size_t>(c++)] = corner;
            const int inside = pattern.GetNumEdgeCoords(k);
            const int a = fv[k], b = fv[(k + 1) % n];
            EdgePoints& e = edgePoints[edgeKey(a, b)];
            if (e.first < 0) {
                e.from = a;
                e.first = static_cast<int>(positions.size());
                for (int i = 0; i < inside; ++i) emit(c + i);
            }
            for (int i = 0; i < inside; ++i)
                index[static_cast<std::size_t>(c + i)] = e.from == a ? e.first + i : e.first + (inside - 1 - i);
            c += inside;
        }
        for (; c < pattern.GetNumCoords(); ++c) index[static_cast<std::size_t>(c)] = emit(c);
        for (int i : facets) triangles.push_back(index[static_cast<std::size_t>(i)]);
    }

    PolygonMesh out = detail::triangleMesh(positions, normals, std::move(triangles));
    if (report) {
        *report = SubdivisionTessellationReport{};
        report->rates = std::move(rate);
        report->regularFaces = regular;
    }
    return out;
}

// ------------------------------------------------------------------------ cage deformation

SubdivisionCage deformCage(const SubdivisionCage& cage, const Lattice& lattice, const DeformOptions& options)
{
    SubdivisionCage out = cage;
    deformPoints(lattice, out.mesh.positions, options);
    return out;
}

} // namespace freeform
