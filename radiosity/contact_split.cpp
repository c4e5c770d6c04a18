#include "radiosity/contact_split.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>

namespace radiosity {

namespace {

/// Samples along an edge that look for the polygons it lies on: a contact covering less than
/// an eighth of the edge may be missed, and is short enough not to matter.
constexpr int kEdgeSamples = 8;
/// Contacts kept per polygon: joining them is quadratic in their number, and a polygon with
/// more than this is cut at most into ContactSplitOptions::maxPieces anyway.
constexpr size_t kMaxContacts = 4096;
/// |cos| of the angle between two polygons above which they are parallel (2.6 degrees).
constexpr double kParallel = 0.999;

/// A contact: the edge a-b, and the plane m.x = d through it perpendicular to the polygon it
/// lies on. As a cut (spanningLines), a-b is the polygon's whole chord on the line, and the
/// plane cuts the pieces that the chord passes through (a binary space partition).
struct ContactLine {
    Vec3 a, b;
    Vec3 m;
    double d = 0;
};

/// The polygons that may be cut, in an Embree scene for point queries (Embree's BVH gives the
/// polygons whose bounds come within a radius of a point: Wald et al. 2014).
class CandidateIndex {
  public:
    CandidateIndex(const std::vector<Polygon>& polygons, const std::vector<int>& candidates,
                   const Vec3& origin)
        : candidates_(candidates), origin_(origin) {
        device_ = rtcNewDevice(nullptr);
        if (!device_) throw std::runtime_error("splitAtContacts: rtcNewDevice failed");
        scene_ = rtcNewScene(device_);
        RTCGeometry g = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_QUAD);
        const size_t n = candidates.size();
        auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(
            g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), 4 * n));
        auto* idx = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
            g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT4, 4 * sizeof(unsigned), n));
        if (!v || !idx) throw std::runtime_error("splitAtContacts: Embree buffers");
        for (size_t c = 0; c < n; ++c) {
            const Polygon& p = polygons[static_cast<size_t>(candidates[c])];
            for (int k = 0; k < 4; ++k) {
                const Vec3 x = p.v[static_cast<size_t>(k < p.vertexCount ? k : 2)] - origin;
                for (int a = 0; a < 3; ++a)
                    v[12 * c + 3 * static_cast<size_t>(k) + static_cast<size_t>(a)] =
                        static_cast<float>(x[a]);
                idx[4 * c + static_cast<size_t>(k)] =
                    static_cast<unsigned>(4 * c) + static_cast<unsigned>(k);
            }
        }
        rtcCommitGeometry(g);
        rtcAttachGeometry(scene_, g);
        rtcReleaseGeometry(g);
        rtcCommitScene(scene_);
    }
    ~CandidateIndex() {
        rtcReleaseScene(scene_);
        rtcReleaseDevice(device_);
    }
    CandidateIndex(const CandidateIndex&) = delete;
    CandidateIndex& operator=(const CandidateIndex&) = delete;

    /// The candidates (polygon indices) whose bounds come within `radius` of p.
    const std::vector<int>& near(const Vec3& p, double radius) {
        found_.clear();
        RTCPointQuery q;
        const Vec3 x = p - origin_;
        q.x = static_cast<float>(x.x);
        q.y = static_cast<float>(x.y);
        q.z = static_cast<float>(x.z);
        q.time = 0;
        q.radius = static_cast<float>(radius);
        RTCPointQueryContext context;
        rtcInitPointQueryContext(&context);
        rtcPointQuery(scene_, &q, &context, &CandidateIndex::onPrimitive, this);
        return found_;
    }

  private:
    static bool onPrimitive(RTCPointQueryFunctionArguments* args) {
        auto* self = static_cast<CandidateIndex*>(args->userPtr);
        self->found_.push_back(self->candidates_[args->primID]);
        return false;  // the query's radius is kept
    }
    const std::vector<int>& candidates_;
    Vec3 origin_;
    RTCDevice device_ = nullptr;
    RTCScene scene_ = nullptr;
    std::vector<int> found_;
};

/// Whether x lies inside convex polygon p, at least `margin` from each of its edges.
bool insideWithMargin(const Polygon& p, const Vec3& x, double margin) {
    for (int i = 0; i < p.vertexCount; ++i) {
        const Vec3& a = p.v[static_cast<size_t>(i)];
        const Vec3& b = p.v[static_cast<size_t>((i + 1) % p.vertexCount)];
        const Vec3 e = b - a;
        const double len = glm::length(e);
        if (!(len > 0)) return false;
        if (!(glm::dot(glm::cross(e, x - a), p.normal) >= margin * len)) return false;
    }
    return true;
}

/// The contact of edge (a, b) on polygon p.
ContactLine lineOn(const Polygon& p, const Vec3& a, const Vec3& b) {
    const Vec3 m = glm::normalize(glm::cross(b - a, p.normal));
    return {a, b, m, glm::dot(m, a)};
}

/// Adds l unless the same edge is there (both of its faces found it).
void addLine(std::vector<ContactLine>& lines, const ContactLine& l, double eps) {
    const auto same = [eps](const Vec3& x, const Vec3& y) { return glm::length(x - y) <= eps; };
    for (const ContactLine& o : lines)
        if ((same(o.a, l.a) && same(o.b, l.b)) || (same(o.a, l.b) && same(o.b, l.a))) return;
    lines.push_back(l);
}

/// Whether segment a-b passes through convex polygon v (normal n) for more than eps.
bool crosses(const std::vector<Vec3>& v, const Vec3& n, const Vec3& a, const Vec3& b, double eps) {
    const double len = glm::length(b - a);
    if (!(len > 0)) return false;
    double t0 = 0, t1 = 1;
    for (size_t i = 0; i < v.size(); ++i) {
        // The inside of edge i: in = (e x (x - v_i)).n >= 0, linear in t along a-b.
        const Vec3 e = v[(i + 1) % v.size()] - v[i];
        const double fa = glm::dot(glm::cross(e, a - v[i]), n);
        const double fb = glm::dot(glm::cross(e, b - v[i]), n);
        if (fa < 0 && fb < 0) return false;
        if (fa < 0) t0 = std::max(t0, fa / (fa - fb));
        if (fb < 0) t1 = std::min(t1, fa / (fa - fb));
    }
    return (t1 - t0) * len > eps;
}

/// The lines along which `lines` (the contacts found on convex polygon A) cut it: those whose
/// contacts, joined along one line, cover A's chord on it from boundary to boundary (up to
/// 2 % of the chord, for meshes that do not quite meet). A wall that stands across a slab, a
/// slab that runs through a wall: A lies on both sides and every element across the line
/// leaks. A box on a floor does not span the floor: cut along its foot's lines to the floor's
/// edges, the floor would become long strips for a leak under the box that nobody sees.
/// Each line returned runs along its whole chord (a, b: the chord's ends).
std::vector<ContactLine> spanningLines(const Polygon& A, const std::vector<ContactLine>& lines,
                                       double eps) {
    std::vector<ContactLine> out;
    std::vector<char> done(lines.size(), 0);
    const std::vector<Vec3> corners(A.v.begin(), A.v.begin() + A.vertexCount);
    for (size_t g = 0; g < lines.size(); ++g) {
        if (done[g]) continue;
        const ContactLine& L = lines[g];
        const Vec3 u = glm::normalize(glm::cross(A.normal, L.m));
        // The chord: the line L.a + t u clipped to A.
        double t0 = -1e300, t1 = 1e300;
        for (size_t i = 0; i < corners.size(); ++i) {
            const Vec3 e = corners[(i + 1) % corners.size()] - corners[i];
            const double f0 = glm::dot(glm::cross(e, L.a - corners[i]), A.normal);
            const double df = glm::dot(glm::cross(e, u), A.normal);
            if (std::abs(df) < 1e-300) {
                if (f0 < 0) t1 = t0 - 1;  // parallel to an edge, outside it
                continue;
            }
            (df > 0 ? t0 : t1) = df > 0 ? std::max(t0, -f0 / df) : std::min(t1, -f0 / df);
        }
        // The contacts on this line, as intervals of t within the chord.
        std::vector<std::pair<double, double>> cover;
        for (size_t k = g; k < lines.size(); ++k) {
            const ContactLine& o = lines[k];
            if (std::abs(glm::dot(o.m, L.m)) < 1 - 1e-9 ||
                std::abs(glm::dot(L.m, o.a) - L.d) > eps ||
                std::abs(glm::dot(L.m, o.b) - L.d) > eps)
                continue;
            done[k] = 1;
            const double ta = glm::dot(o.a - L.a, u), tb = glm::dot(o.b - L.a, u);
            cover.emplace_back(std::max(std::min(ta, tb), t0), std::min(std::max(ta, tb), t1));
        }
        if (!(t1 - t0 > 2 * eps)) continue;
        std::sort(cover.begin(), cover.end());
        const double slack = 2 * eps + 0.02 * (t1 - t0);
        double reached = t0, gaps = 0;
        for (const auto& [lo, hi] : cover) {
            gaps += std::max(0.0, lo - reached);
            reached = std::max(reached, hi);
        }
        gaps += std::max(0.0, t1 - reached);
        if (gaps <= slack) out.push_back({L.a + t0 * u, L.a + t1 * u, L.m, L.d});
    }
    return out;
}

double polygonArea(const std::vector<Vec3>& v) {
    Vec3 s(0.0);
    for (size_t i = 1; i + 1 < v.size(); ++i) s += glm::cross(v[i] - v[0], v[i + 1] - v[0]);
    return 0.5 * glm::length(s);
}

/// Cuts convex polygon `v` by the line's plane into `neg` and `pos` (Sutherland & Hodgman
/// 1974, one plane); false when one side holds less than eps of it.
bool cutConvex(const std::vector<Vec3>& v, const ContactLine& l, double eps, std::vector<Vec3>& neg,
               std::vector<Vec3>& pos) {
    std::vector<double> s(v.size());
    double lo = 0, hi = 0;
    for (size_t i = 0; i < v.size(); ++i) {
        s[i] = glm::dot(l.m, v[i]) - l.d;
        lo = std::min(lo, s[i]);
        hi = std::max(hi, s[i]);
    }
    if (!(lo < -eps && hi > eps)) return false;
    neg.clear();
    pos.clear();
    for (size_t i = 0; i < v.size(); ++i) {
        const size_t j = (i + 1) % v.size();
        if (s[i] <= 0) neg.push_back(v[i]);
        if (s[i] >= 0) pos.push_back(v[i]);
        if ((s[i] < 0 && s[j] > 0) || (s[i] > 0 && s[j] < 0)) {
            const Vec3 x = v[i] + (s[i] / (s[i] - s[j])) * (v[j] - v[i]);
            neg.push_back(x);
            pos.push_back(x);
        }
    }
    return neg.size() >= 3 && pos.size() >= 3;
}

/// Polygon p cut along `lines` into convex pieces, at most maxPieces; each piece becomes
/// triangles or a quad. Empty when a piece fails checkPolygon (p is then kept whole).
std::vector<Polygon> cutPolygon(const Polygon& p, const std::vector<ContactLine>& lines, double eps,
                                int maxPieces, bool& limited) {
    std::vector<std::vector<Vec3>> pieces{
        std::vector<Vec3>(p.v.begin(), p.v.begin() + p.vertexCount)};
    std::vector<Vec3> neg, pos;
    limited = false;
    for (const ContactLine& l : lines) {
        const size_t count = pieces.size();
        for (size_t i = 0; i < count; ++i) {
            if (static_cast<int>(pieces.size()) >= maxPieces) {
                limited = true;
                break;
            }
            if (!crosses(pieces[i], p.normal, l.a, l.b, eps) ||
                !cutConvex(pieces[i], l, eps, neg, pos))
                continue;
            if (!(polygonArea(neg) > eps * eps && polygonArea(pos) > eps * eps)) continue;
            pieces[i] = neg;
            pieces.push_back(pos);
        }
    }
    std::vector<Polygon> out;
    for (const std::vector<Vec3>& piece : pieces) {
        // A fan from the first corner, of quads where the corners allow (a quad of a convex
        // polygon's corners is convex), closed by a triangle.
        const size_t n = piece.size();
        for (size_t k = 1; k + 1 < n;) {
            std::vector<Vec3> corners{piece[0], piece[k], piece[k + 1]};
            if (k + 2 < n) corners.push_back(piece[k + 2]);
            if (checkPolygon(corners).status != PolygonCheck::Status::ok) return {};
            Polygon q = makePolygon(corners, p.object, p.rho);
            if (glm::dot(q.normal, p.normal) < 0.5) return {};
            out.push_back(q);
            k += corners.size() - 2;
        }
    }
    return out;
}

}  // namespace

ContactSplitReport splitAtContacts(std::vector<Polygon>& polygons, size_t count,
                                   const ContactSplitOptions& options) {
    ContactSplitReport report;
    count = std::min(count, polygons.size());
    Bounds3 box;
    for (size_t i = 0; i < count; ++i) box.extend(polygons[i].bounds());
    if (box.empty()) return report;
    const double diag = glm::length(box.diagonal());
    if (!(diag > 0) || !std::isfinite(diag)) return report;
    // Contact tolerance: 1e-4 of the scene (a millimetre in a 10 m hall), far above float
    // rounding of the coordinates and far below any gap a model means.
    const double eps = 1e-4 * diag;
    const double minArea = options.minArea * diag * diag;
    const double minEdge = options.minEdge * diag;

    std::vector<int> candidates;
    for (size_t i = 0; i < count; ++i)
        if (polygons[i].light < 0 && polygons[i].area >= minArea)
            candidates.push_back(static_cast<int>(i));
    if (candidates.empty()) return report;
    CandidateIndex index(polygons, candidates, box.centre());

    std::vector<std::vector<ContactLine>> lines(count);
    for (size_t b = 0; b < count; ++b) {
        const Polygon& B = polygons[b];
        if (B.light >= 0) continue;
        for (int k = 0; k < B.vertexCount; ++k) {
            const Vec3& a = B.v[static_cast<size_t>(k)];
            const Vec3& c = B.v[static_cast<size_t>((k + 1) % B.vertexCount)];
            if (!(glm::length(c - a) >= minEdge)) continue;
            for (int s = 0; s < kEdgeSamples; ++s) {
                const Vec3 x = a + ((s + 0.5) / kEdgeSamples) * (c - a);
                for (const int ai : index.near(x, eps)) {
                    const Polygon& A = polygons[static_cast<size_t>(ai)];
                    // B in A's plane (a decal, a doubled face) divides no space.
                    if (static_cast<size_t>(ai) == b ||
                        std::abs(glm::dot(A.normal, B.normal)) > kParallel)
                        continue;
                    // The edge lies in A's plane (both ends) and this point of it in A's
                    // interior: the contact line crosses A.
                    if (std::abs(glm::dot(A.normal, a - A.v[0])) > eps ||
                        std::abs(glm::dot(A.normal, c - A.v[0])) > eps ||
                        !insideWithMargin(A, x, eps))
                        continue;
                    std::vector<ContactLine>& on = lines[static_cast<size_t>(ai)];
                    if (on.size() < kMaxContacts) addLine(on, lineOn(A, a, c), eps);
                }
            }
        }
    }

    for (size_t i = 0; i < count; ++i) {
        if (lines[i].empty()) continue;
        const std::vector<ContactLine> cuts = spanningLines(polygons[i], lines[i], eps);
        if (cuts.empty()) continue;
        bool limited = false;
        std::vector<Polygon> pieces =
            cutPolygon(polygons[i], cuts, eps, options.maxPieces, limited);
        if (pieces.size() < 2) continue;
        for (Polygon& q : pieces) q.light = polygons[i].light;
        ++report.polygonsCut;
        report.lines += static_cast<int>(cuts.size());
        report.piecesLimited += limited ? 1 : 0;
        report.piecesAdded += static_cast<int>(pieces.size()) - 1;
        polygons[i] = pieces[0];
        polygons.insert(polygons.end(), pieces.begin() + 1, pieces.end());
    }
    return report;
}

}  // namespace radiosity
