#include "radiosity/emitter.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "radiosity/detail/form_factor.h"
#include "radiosity/detail/hemisphere.h"

namespace radiosity {

namespace {

constexpr double kPi = std::numbers::pi;

bool finite(const Vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

bool finiteNonNegative(const Rgb& c) {
    for (int k = 0; k < 3; ++k)
        if (!std::isfinite(c[k]) || c[k] < 0) return false;
    return true;
}

/// A unit vector along `d`; throws when it has no direction.
Vec3 unitDirection(const Vec3& d, const std::string& what) {
    const double len = glm::length(d);
    if (!finite(d) || !(len > 1e-12))
        throw std::invalid_argument(what + ": direction must be finite and non-zero");
    return d / len;
}

double boundingRadius(const Bounds3& b) {
    return b.empty() ? 0.0 : 0.5 * glm::length(b.diagonal());
}

/// A point of the unit disc, uniform, in stratum `cell` of a k x k grid (polar map: the
/// area of a ring grows with r, hence sqrt).
void discPoint(int cell, int k, Rng& rng, double& x, double& y) {
    const double r = std::sqrt(((cell % k) + rng.uniform()) / k);
    const double phi = 2 * kPi * ((cell / k) + rng.uniform()) / k;
    x = r * std::cos(phi);
    y = r * std::sin(phi);
}

EmitterField numberField(const char* key, double v) {
    return {key, {v}, EmitterField::Shape::number};
}
EmitterField listField(const char* key, const Vec3& v) {
    return {key, {v.x, v.y, v.z}, EmitterField::Shape::list};
}
EmitterField rgbField(const char* key, const Rgb& c) {
    return {key, {c.r, c.g, c.b}, EmitterField::Shape::list};
}

/// `original` as the light type T that editFrom() compares with.
template <class T>
const T& sameType(const Emitter& self, const Emitter& original) {
    const T* o = dynamic_cast<const T*>(&original);
    if (!o)
        throw std::invalid_argument("light '" + self.name() + "' (" + self.type() +
                                    ") cannot be edited from a light of type " + original.type());
    return *o;
}

/// What every single-component light shares: one strength, checked >= 0.
class SingleEmitter : public Emitter {
  public:
    SingleEmitter(std::string name, const char* strengthName)
        : Emitter(std::move(name)), strengthName_(strengthName) {}
    Rgb irradiance(const Visibility& vis, const ReceiverPoint& p, int rays,
                   Rng& rng) const override {
        double g = 0;
        unitIrradiance(vis, p, rays, rng, &g);
        return s_ * g;
    }
    Rgb unoccludedIrradiance(const ReceiverPoint& p) const override {
        double g = 0;
        unitUnoccluded(p, &g);
        return s_ * g;
    }
    std::vector<Rgb> strengths() const override { return {s_}; }
    void setStrengths(std::span<const Rgb> s) override {
        if (s.size() != 1)
            throw std::invalid_argument("light '" + name() + "': one strength expected");
        set(s[0], strengthName_);
    }
    bool on() const override { return s_.maxComponent() > 0; }

  protected:
    /// The edit's strength fields, shared: the value set, then the scale.
    void applyStrength(const EmitterEdit& e) {
        if (e.strength) set(*e.strength, strengthName_);
        if (e.scale) set(s_ * *e.scale, "scale");
    }
    void set(const Rgb& c, const char* field) {
        if (!finiteNonNegative(c))
            throw std::invalid_argument("light '" + name() + "': " + field +
                                        " must give a finite, non-negative " + strengthName_);
        s_ = c;
    }
    Rgb s_;

  private:
    const char* strengthName_;
};

class Sun final : public SingleEmitter {
  public:
    Sun(std::string name, const Vec3& direction, double angleDegrees, const Rgb& irradiance)
        : SingleEmitter(std::move(name), "irradiance") {
        setDirection(direction);
        if (!std::isfinite(angleDegrees) || angleDegrees < 0 || angleDegrees >= 180)
            throw std::invalid_argument("sun '" + this->name() +
                                        "': angle must be in [0, 180) degrees");
        angle_ = angleDegrees;
        tanHalf_ = std::tan(0.5 * angleDegrees * kPi / 180);
        set(irradiance, "irradiance");
    }
    const char* type() const override { return "sun"; }

    void unitIrradiance(const Visibility& vis, const ReceiverPoint& p, int rays, Rng& rng,
                        double* out) const override {
        out[0] = discMean(vis, p, rays, rng, [](const Vec3&) { return 1.0; });
    }
    void unitUnoccluded(const ReceiverPoint& p, double* out) const override {
        out[0] = std::max(0.0, glm::dot(p.n, d_));
    }
    std::optional<ShadowSource> shadowSource() const override {
        return ShadowSource{ShadowSource::Kind::direction, d_, {}};
    }
    void unitGlossy(const Visibility& vis, const ReceiverPoint& p, const Lobe& lobe, int rays,
                    Rng& rng, double* out) const override {
        // The disc's directions as unitIrradiance draws them, each weighed by the lobe.
        out[0] = discMean(vis, p, rays, rng, [&](const Vec3& w) { return lobe(w); });
    }
    Rgb power(const Bounds3& b) const override {
        const double R = boundingRadius(b);
        return s_ * (kPi * R * R);
    }
    void apply(const EmitterEdit& e) override {
        if (e.sh9) refuse("sh9");
        if (e.position) refuse("position");
        if (e.rotate) refuse("rotate");
        if (e.direction) setDirection(*e.direction);
        applyStrength(e);
    }
    std::unique_ptr<Emitter> clone() const override { return std::make_unique<Sun>(*this); }
    const char* strengthKey() const override { return "irradiance"; }
    std::vector<EmitterField> fields() const override {
        return {listField("direction", given_), numberField("angle", angle_),
                rgbField("irradiance", s_)};
    }
    EmitterEdit editFrom(const Emitter& original) const override {
        EmitterEdit e;
        e.strength = s_;
        if (!(sameType<Sun>(*this, original).d_ == d_)) e.direction = given_;
        return e;
    }

  private:
    /// Directions towards points of the disc, uniform over it: for the small discs of a
    /// sun (tan of the half angle << 1) the tangent-plane disc is the cone to within
    /// (tan a)^2 (the real sun: 2e-5), and cos V weight(w) is averaged over it.
    template <class Weight>
    double discMean(const Visibility& vis, const ReceiverPoint& p, int rays, Rng& rng,
                    Weight weight) const {
        const int k = tanHalf_ > 0 ? strataSide(std::max(rays, 1)) : 1;
        const HemisphereFrame f(d_);
        // The directions above the point's horizon first, then their shadow rays as one
        // packet (coherent: one origin, a narrow cone), summed in the cells' order.
        constexpr int kMax = 256;  // DirectLightOptions' most rays: one batch
        Vec3 w[kMax];
        double c[kMax];
        bool blocked[kMax];
        double sum = 0;
        for (int first = 0; first < k * k; first += kMax) {
            int n = 0;
            for (int cell = first; cell < std::min(k * k, first + kMax); ++cell) {
                Vec3 dir = d_;
                if (tanHalf_ > 0) {
                    double x = 0, y = 0;
                    discPoint(cell, k, rng, x, y);
                    dir = glm::normalize(d_ + tanHalf_ * (x * f.t + y * f.b));
                }
                const double cosine = glm::dot(p.n, dir);
                if (cosine <= 0) continue;
                w[n] = dir;
                c[n++] = cosine;
            }
            vis.occludedBatch(p.x, w, n, p.polygon, blocked);
            for (int i = 0; i < n; ++i)
                if (!blocked[i]) sum += c[i] * weight(w[i]);
        }
        return sum / (k * k);
    }
    void setDirection(const Vec3& d) {
        d_ = unitDirection(d, "sun '" + name() + "'");
        given_ = d;  // as given: written back, it reads to the same d_ bit for bit
    }
    Vec3 d_, given_;
    double angle_ = 0;
    double tanHalf_ = 0;
};

class PointLamp final : public SingleEmitter {
  public:
    PointLamp(std::string name, const Vec3& position, const Rgb& intensity)
        : SingleEmitter(std::move(name), "intensity") {
        setPosition(position);
        set(intensity, "intensity");
    }
    const char* type() const override { return "point"; }

    void unitIrradiance(const Visibility& vis, const ReceiverPoint& p, int, Rng&,
                        double* out) const override {
        // A point casts hard shadows: one ray decides.
        unitUnoccluded(p, out);
        if (out[0] > 0 && !vis.visible(p.x, pos_, p.polygon)) out[0] = 0;
    }
    void unitUnoccluded(const ReceiverPoint& p, double* out) const override {
        const Vec3 v = pos_ - p.x;
        const double d2 = glm::dot(v, v);
        out[0] = 0;
        if (!(d2 > 1e-18)) return;  // guard: the lamp on the point itself
        const double c = glm::dot(p.n, v) / std::sqrt(d2);
        if (c > 0) out[0] = c / d2;  // cos(theta) / d^2
    }
    std::optional<ShadowSource> shadowSource() const override {
        return ShadowSource{ShadowSource::Kind::point, pos_, {}};
    }
    void unitGlossy(const Visibility& vis, const ReceiverPoint& p, const Lobe& lobe, int rays,
                    Rng& rng, double* out) const override {
        // One direction: the irradiance I cos / d^2 weighed by the lobe towards the lamp.
        unitIrradiance(vis, p, rays, rng, out);
        if (out[0] > 0) out[0] *= lobe(glm::normalize(pos_ - p.x));
    }
    Rgb power(const Bounds3&) const override { return s_ * (4 * kPi); }
    void apply(const EmitterEdit& e) override {
        if (e.sh9) refuse("sh9");
        if (e.direction) refuse("direction");
        if (e.rotate) refuse("rotate");
        if (e.position) setPosition(*e.position);
        applyStrength(e);
    }
    std::unique_ptr<Emitter> clone() const override { return std::make_unique<PointLamp>(*this); }
    const char* strengthKey() const override { return "intensity"; }
    std::vector<EmitterField> fields() const override {
        return {listField("position", pos_), rgbField("intensity", s_)};
    }
    EmitterEdit editFrom(const Emitter& original) const override {
        EmitterEdit e;
        e.strength = s_;
        if (!(sameType<PointLamp>(*this, original).pos_ == pos_)) e.position = pos_;
        return e;
    }

  private:
    void setPosition(const Vec3& p) {
        if (!finite(p))
            throw std::invalid_argument("point lamp '" + name() + "': position must be finite");
        pos_ = p;
    }
    Vec3 pos_;
};

class Environment final : public Emitter {
  public:
    Environment(std::string name, const Sh9Rgb& L) : Emitter(std::move(name)) { set(L); }
    const char* type() const override { return "environment"; }

    Rgb irradiance(const Visibility& vis, const ReceiverPoint& p, int rays,
                   Rng& rng) const override {
        Sh9 T{};
        unitIrradiance(vis, p, rays, rng, T.data());
        return sh9Dot(T, L_);
    }
    Rgb unoccludedIrradiance(const ReceiverPoint& p) const override {
        return sh9Irradiance(L_, p.n);  // R&H 2001, Eq. 7
    }
    int components() const override { return kSh9Count; }
    std::vector<Rgb> strengths() const override { return {L_.c.begin(), L_.c.end()}; }
    void setStrengths(std::span<const Rgb> s) override {
        if (s.size() != static_cast<size_t>(kSh9Count))
            throw std::invalid_argument("environment '" + name() + "': 9 coefficients expected");
        Sh9Rgb L;
        std::copy(s.begin(), s.end(), L.c.begin());
        set(L);
    }
    void unitIrradiance(const Visibility& vis, const ReceiverPoint& p, int rays, Rng& rng,
                        double* out) const override {
        // The transfer vector T_k = integral of Y_k V cos dw = pi E[Y_k V] over
        // cosine-distributed directions (stratified: radiosity/detail/hemisphere.h), as
        // sky_transfer.h (Sloan et al. 2002); E = sum_k L_k T_k.
        hemisphereMean(
            vis, p, rays, rng, [](const Vec3&) { return 1.0; }, out);
    }
    void unitGlossy(const Visibility& vis, const ReceiverPoint& p, const Lobe& lobe, int rays,
                    Rng& rng, double* out) const override {
        // pi E[Y_k(w) lobe(w) V(w)] over cosine-distributed directions: unitIrradiance's
        // estimate with each direction weighed (a sharp lobe is noisy: a sky's highlight
        // is broad).
        hemisphereMean(
            vis, p, rays, rng, [&](const Vec3& w) { return lobe(w); }, out);
    }
    void unitUnoccluded(const ReceiverPoint& p, double* out) const override {
        const Sh9 T = sh9CosineTransfer(p.n);  // R&H 2001, Eq. 7
        std::copy(T.begin(), T.end(), out);
    }
    Rgb power(const Bounds3& b) const override {
        // Through a sphere of radius R: pi R^2 times the integral of L over all directions,
        // L00 times the integral of Y00 = 2 sqrt(pi).
        const double R = boundingRadius(b);
        return L_.c[0] * (kPi * R * R * 2 * std::sqrt(kPi));
    }
    bool on() const override { return L_.c[0].maxComponent() > 0; }
    void apply(const EmitterEdit& e) override {
        if (e.direction) refuse("direction");
        if (e.position) refuse("position");
        if (e.strength) refuse("irradiance or intensity");
        if (e.sh9) set(*e.sh9);
        if (e.rotate) set(sh9RotateAboutAxis(L_, e.rotate->axis, e.rotate->degrees));
        if (e.scale) {
            if (!std::isfinite(*e.scale) || *e.scale < 0)
                throw std::invalid_argument("light '" + name() + "': scale must be >= 0");
            Sh9Rgb s = L_;
            for (Rgb& c : s.c) c *= *e.scale;
            set(s);
        }
    }
    std::unique_ptr<Emitter> clone() const override { return std::make_unique<Environment>(*this); }
    const char* strengthKey() const override { return "sh9"; }
    std::vector<EmitterField> fields() const override {
        EmitterField f{"sh9", {}, EmitterField::Shape::rows};
        for (const Rgb& c : L_.c) f.values.insert(f.values.end(), {c.r, c.g, c.b});
        return {f};
    }
    EmitterEdit editFrom(const Emitter& original) const override {
        sameType<Environment>(*this, original);
        EmitterEdit e;
        e.sh9 = L_;  // a turned or edited sky is its new coefficients: it does not move
        return e;
    }

  private:
    /// pi E[Y_k(w) weight(w) V(w)] over stratified cosine-distributed directions w, into
    /// out[0..8].
    template <class Weight>
    static void hemisphereMean(const Visibility& vis, const ReceiverPoint& p, int rays, Rng& rng,
                               Weight weight, double* out) {
        const int k = strataSide(std::max(rays, 1));
        const HemisphereFrame f(p.n);
        Sh9 sum{};
        for (int cell = 0; cell < k * k; ++cell) {
            const Vec3 w = cosineDirection(f, cell, k, rng);
            if (vis.occluded(p.x, w, 0, 1e30, p.polygon)) continue;
            const double wt = weight(w);
            const Sh9 Y = sh9Basis(w);
            for (size_t c = 0; c < Y.size(); ++c) sum[c] += wt * Y[c];
        }
        for (size_t c = 0; c < sum.size(); ++c) out[c] = sum[c] * (kPi / (k * k));
    }
    void set(const Sh9Rgb& L) {
        for (const Rgb& c : L.c)
            for (int k = 0; k < 3; ++k)
                if (!std::isfinite(c[k]))
                    throw std::invalid_argument("environment '" + name() +
                                                "': sh9 coefficients must be finite");
        L_ = L;
    }
    Sh9Rgb L_;
};

/// A point of polygon `c` (3 or 4 corners) for (u, v) in [0, 1)^2: bilinear on a quad, the
/// square folded onto a triangle (uniform by area for a triangle and a parallelogram).
Vec3 polygonPoint(const std::vector<Vec3>& c, double u, double v) {
    if (c.size() == 3) {
        const double su = std::sqrt(u);
        return (1 - su) * c[0] + su * (1 - v) * c[1] + su * v * c[2];
    }
    return (1 - u) * (1 - v) * c[0] + u * (1 - v) * c[1] + u * v * c[2] + (1 - u) * v * c[3];
}

}  // namespace

std::array<Vec3, ShadowSource::kFacePoints> ShadowSource::facePoints() const {
    std::array<Vec3, kFacePoints> out{};
    if (kind != Kind::face || (corners.size() != 3 && corners.size() != 4)) {
        out.fill(at);
        return out;
    }
    for (int k = 0; k < kFacePoints; ++k)
        out[static_cast<size_t>(k)] =
            polygonPoint(corners, 0.25 + 0.5 * (k % 2), 0.25 + 0.5 * (k / 2));
    return out;
}

namespace {

class QuadLamp final : public SingleEmitter {
  public:
    QuadLamp(std::string name, std::vector<std::vector<Vec3>> faces, std::vector<int> polygons,
             const Rgb& radiance)
        : SingleEmitter(std::move(name), "radiance"),
          faces_(std::move(faces)),
          polygons_(std::move(polygons)) {
        if (!polygons_.empty() && polygons_.size() != faces_.size())
            throw std::invalid_argument("quad lamp '" + this->name() +
                                        "': one polygon index per face, or none");
        for (const auto& f : faces_) {
            if (f.size() != 3 && f.size() != 4)
                throw std::invalid_argument("quad lamp '" + this->name() +
                                            "': faces have 3 or 4 corners");
            const Vec3 n = glm::cross(f[1] - f[0], f[2] - f[0]);
            const double len = glm::length(n);
            if (!(len > 0))
                throw std::invalid_argument("quad lamp '" + this->name() + "': a face has no area");
            normals_.push_back(n / len);
            double area = 0.5 * len;
            if (f.size() == 4) area += 0.5 * glm::length(glm::cross(f[2] - f[0], f[3] - f[0]));
            areas_.push_back(area);
        }
        set(radiance, "radiance");
    }
    const char* type() const override { return "quad"; }
    std::optional<ShadowSource> shadowSource() const override {
        if (faces_.size() != 1) return std::nullopt;  // one face: one set of shadow maps
        ShadowSource s{ShadowSource::Kind::face, {0, 0, 0}, faces_[0]};
        for (const Vec3& c : faces_[0]) s.at += c / static_cast<double>(faces_[0].size());
        return s;
    }

    void unitIrradiance(const Visibility& vis, const ReceiverPoint& p, int rays, Rng& rng,
                        double* out) const override {
        const int k = strataSide(std::max(rays, 1));
        double G = 0;  // sum_q F(x -> q) V_q
        for (size_t q = 0; q < faces_.size(); ++q) {
            const double F = formFactor(p, q);
            if (!(F > 0)) continue;
            const int own = polygons_.empty() ? -1 : polygons_[q];
            int seen = 0;
            for (int cell = 0; cell < k * k; ++cell) {
                const Vec3 y = polygonPoint(faces_[q], ((cell % k) + rng.uniform()) / k,
                                            ((cell / k) + rng.uniform()) / k);
                seen += vis.visible(p.x, y, p.polygon, own) ? 1 : 0;
            }
            G += F * seen / (k * k);
        }
        out[0] = kPi * G;  // H = pi L G: E = pi L (scene.h)
    }
    void unitGlossy(const Visibility& vis, const ReceiverPoint& p, const Lobe& lobe, int rays,
                    Rng& rng, double* out) const override {
        // dE = L cos(x) cos(y) / d^2 dA(y): k x k stratified points of each face, each
        // weighed by the lobe towards it and by the area its (u, v) cell stands for.
        const int k = strataSide(std::max(rays, 1));
        double sum = 0;
        for (size_t q = 0; q < faces_.size(); ++q) {
            const int own = polygons_.empty() ? -1 : polygons_[q];
            double face = 0;
            for (int cell = 0; cell < k * k; ++cell) {
                const double u = ((cell % k) + rng.uniform()) / k;
                const double v = ((cell / k) + rng.uniform()) / k;
                const Vec3 y = polygonPoint(faces_[q], u, v);
                const Vec3 d = y - p.x;
                const double d2 = glm::dot(d, d);
                if (!(d2 > 1e-18)) continue;  // guard: the point on the lamp itself
                const Vec3 w = d / std::sqrt(d2);
                const double cx = glm::dot(p.n, w), cy = -glm::dot(normals_[q], w);
                if (cx <= 0 || cy <= 0) continue;
                if (!vis.visible(p.x, y, p.polygon, own)) continue;
                face += cx * cy / d2 * jacobian(q, u, v) * lobe(w);
            }
            sum += face / (k * k);
        }
        out[0] = sum;
    }
    void unitUnoccluded(const ReceiverPoint& p, double* out) const override {
        double G = 0;
        for (size_t q = 0; q < faces_.size(); ++q) G += formFactor(p, q);
        out[0] = kPi * G;
    }
    Rgb power(const Bounds3&) const override {
        double A = 0;
        for (double a : areas_) A += a;
        return s_ * (kPi * A);  // E A, E = pi L (scene.h)
    }
    void apply(const EmitterEdit& e) override {
        if (e.sh9) refuse("sh9");
        if (e.direction) refuse("direction");
        if (e.position) refuse("position");
        if (e.rotate) refuse("rotate");
        applyStrength(e);
    }
    std::unique_ptr<Emitter> clone() const override { return std::make_unique<QuadLamp>(*this); }
    const char* strengthKey() const override { return "radiance"; }
    std::vector<EmitterField> fields() const override {
        // The format's quad light is one polygon; a lamp of several faces has no such entry.
        if (faces_.size() != 1)
            throw std::invalid_argument("quad lamp '" + name() + "' has " +
                                        std::to_string(faces_.size()) +
                                        " faces: a light entry holds one polygon");
        EmitterField v{"vertices", {}, EmitterField::Shape::rows};
        for (const Vec3& p : faces_[0]) v.values.insert(v.values.end(), {p.x, p.y, p.z});
        return {v, rgbField("radiance", s_)};
    }
    EmitterEdit editFrom(const Emitter& original) const override {
        sameType<QuadLamp>(*this, original);
        EmitterEdit e;
        e.strength = s_;
        return e;
    }

  private:
    /// Area per unit (u, v) of polygonPoint at (u, v): the face's area for a triangle
    /// (uniform by area), |dP/du x dP/dv| of the bilinear map for a quad.
    double jacobian(size_t q, double u, double v) const {
        const std::vector<Vec3>& c = faces_[q];
        if (c.size() == 3) return areas_[q];
        const Vec3 du = (1 - v) * (c[1] - c[0]) + v * (c[2] - c[3]);
        const Vec3 dv = (1 - u) * (c[3] - c[0]) + u * (c[2] - c[1]);
        return glm::length(glm::cross(du, dv));
    }
    double formFactor(const ReceiverPoint& p, size_t q) const {
        return pointToPolygon(p.x, p.n, faces_[q].data(), static_cast<int>(faces_[q].size()),
                              normals_[q]);
    }
    std::vector<std::vector<Vec3>> faces_;
    std::vector<int> polygons_;
    std::vector<Vec3> normals_;
    std::vector<double> areas_;
};

}  // namespace

void Emitter::refuse(const char* field) const {
    throw std::invalid_argument(std::string("light '") + name_ + "' (" + type() + ") has no " +
                                field);
}

std::unique_ptr<Emitter> makeSun(std::string name, const Vec3& direction, double angleDegrees,
                                 const Rgb& irradiance) {
    return std::make_unique<Sun>(std::move(name), direction, angleDegrees, irradiance);
}

std::unique_ptr<Emitter> makePointLamp(std::string name, const Vec3& position,
                                       const Rgb& intensity) {
    return std::make_unique<PointLamp>(std::move(name), position, intensity);
}

std::unique_ptr<Emitter> makeEnvironment(std::string name, const Sh9Rgb& sh9) {
    return std::make_unique<Environment>(std::move(name), sh9);
}

std::unique_ptr<Emitter> makeQuadLamp(std::string name, std::vector<std::vector<Vec3>> faces,
                                      std::vector<int> polygons, const Rgb& radiance) {
    return std::make_unique<QuadLamp>(std::move(name), std::move(faces), std::move(polygons),
                                      radiance);
}

std::vector<EmitterField> editFields(const Emitter& light, const EmitterEdit& e) {
    std::vector<EmitterField> out;
    if (e.scale) out.push_back(numberField("scale", *e.scale));
    if (e.strength) out.push_back(rgbField(light.strengthKey(), *e.strength));
    if (e.sh9) {
        EmitterField f{"sh9", {}, EmitterField::Shape::rows};
        for (const Rgb& c : e.sh9->c) f.values.insert(f.values.end(), {c.r, c.g, c.b});
        out.push_back(std::move(f));
    }
    if (e.direction) out.push_back(listField("direction", *e.direction));
    if (e.position) out.push_back(listField("position", *e.position));
    if (e.rotate) {
        out.push_back(listField("rotate.axis", e.rotate->axis));
        out.push_back(numberField("rotate.degrees", e.rotate->degrees));
    }
    return out;
}

std::optional<EmitterField> findField(const Emitter& light, const std::string& key) {
    for (EmitterField& f : light.fields())
        if (f.key == key) return std::move(f);
    return std::nullopt;
}

Rgb totalIrradiance(const std::vector<std::unique_ptr<Emitter>>& emitters, const Visibility& vis,
                    const ReceiverPoint& p, int rays, uint64_t seed) {
    Rgb sum;
    for (size_t i = 0; i < emitters.size(); ++i) {
        if (!emitters[i]->on()) continue;
        Rng rng(seed * 0x9E3779B97F4A7C15ull + i + 1);
        sum += emitters[i]->irradiance(vis, p, rays, rng);
    }
    return sum;
}

}  // namespace radiosity
