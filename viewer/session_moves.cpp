// The session's lights that move: a sun turned, a point lamp or a virtual quad lamp moved,
// shown quickly while they move (DynamicRelighting::previewEmitter; the window's GPU frames
// through movedLightFrame), exact once the hand rests (Session::settle, session.cpp).
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "radiosity/emitter.h"
#include "viewer/session.h"

namespace relight::viewer {

namespace {

/// A lamp's face `corners` (a planar polygon) turned and moved onto the surface at `p`:
/// parallel to it, facing along its normal, its centroid above p.point by 2 % of its size
/// (addLightAt's rule), turned by the least rotation that takes its normal to the surface's
/// (so that on the same surface it keeps its turn about the normal).
std::vector<Vec3> faceAbove(const std::vector<Vec3>& corners, const Pick& p) {
    Vec3 centroid{0, 0, 0}, area{0, 0, 0};
    for (const Vec3& c : corners) centroid += c;
    centroid /= static_cast<double>(corners.size());
    for (size_t k = 1; k + 1 < corners.size(); ++k)  // a fan: the face is convex
        area += 0.5 * glm::cross(corners[k] - corners[0], corners[k + 1] - corners[0]);
    const double size = std::sqrt(glm::length(area));
    if (!(size > 0)) throw std::invalid_argument("the lamp's face has no area");
    const Vec3 from = area / glm::length(area), to = glm::normalize(p.normal);
    // Rodrigues' rotation of `from` onto `to`; half a turn about any axis across `from`
    // when they are opposite (the rotation is then not unique).
    const Vec3 axis = glm::cross(from, to);
    const double sine = glm::length(axis), cosine = glm::dot(from, to);
    const Vec3 k = sine > 1e-9 ? axis / sine
                               : glm::normalize(glm::cross(
                                     from, std::abs(from.x) < 0.9 ? Vec3(1, 0, 0) : Vec3(0, 1, 0)));
    const double angle = std::atan2(sine, cosine);
    const auto turn = [&](const Vec3& v) {
        return v * std::cos(angle) + glm::cross(k, v) * std::sin(angle) +
               k * (glm::dot(k, v) * (1 - std::cos(angle)));
    };
    const Vec3 centre = p.point + to * std::max(0.005, 0.02 * size);
    std::vector<Vec3> out;
    for (const Vec3& c : corners) out.push_back(centre + turn(c - centroid));
    return out;
}

}  // namespace

void Session::movePointLampTo(const std::string& name, const Pick& p, double offset) {
    if (!p.hit) throw std::invalid_argument("no surface there to put the point lamp above");
    radiosity::EmitterEdit e;
    e.position = p.point + glm::normalize(p.normal) * offsetOrDefault(offset);
    editLight(name, e);
}

void Session::moveLightTo(const std::string& name, const Pick& p, double offset) {
    LightControl* c = findControl(name);
    if (c && c->emitter) return movePointLampTo(name, p, offset);
    if (!c || !c->isVirtual)
        throw std::invalid_argument("no point lamp or virtual lamp \"" + name + "\" to move");
    if (!p.hit) throw std::invalid_argument("no surface there to put the lamp on");
    c->face.corners = faceAbove(c->face.corners, p);
    if (previewFace(static_cast<size_t>(c - lights_.data()))) return;
    stale_ = true;
    update();
}

bool Session::previewFace(size_t i) {
    // Shown quickly as the point lamps are (previewMoves): its direct light per pixel at the
    // new place through the quad lamp's model (one ray per pixel on the CPU; the window's
    // GPU frames, four shadow maps), its face drawn there, the rest as last solved. Its own
    // face, still where it was in the solver, does not block it.
    if (!quickMoves_ || stale_ || !dyn_ || dyn_->previewingObject() || i >= solverLight_.size() ||
        solverLight_[i] < 0 || !lights_[i].on)
        return false;
    const int light = solverLight_[i];
    const radiosity::Light& held = r_->solver->scene().lights[static_cast<size_t>(light)];
    if (held.polygons.size() != 1) return false;  // a virtual lamp is one face
    dyn_->previewEmitter(light, *radiosity::makeQuadLamp(lights_[i].name, {lights_[i].face.corners},
                                                         held.polygons, Rgb{1, 1, 1}));
    faceShownMoved_ = exactPending_ = true;
    // The frames of one drag: the window may draw them on the GPU (movedLightFrame).
    const int wasMoving = movingLight_, epoch = movingEpoch_;
    changed();
    movingLight_ = light;
    if (light == wasMoving) movingEpoch_ = epoch;
    return true;
}

Vec3 Session::sunDirection(double azimuth, double elevation) {
    constexpr double kDeg = 3.14159265358979323846 / 180;
    const double ce = std::cos(elevation * kDeg);
    return {ce * std::cos(azimuth * kDeg), ce * std::sin(azimuth * kDeg),
            std::sin(elevation * kDeg)};
}

void Session::dragSun(const std::string& name, double du, double dv) {
    const radiosity::Emitter* em = emitter(name);
    const auto d = em ? radiosity::findField(*em, "direction") : std::nullopt;
    if (!d) throw std::invalid_argument("no sun \"" + name + "\" to turn");
    double azimuth = 0, elevation = 0;
    sunAngles(Vec3(d->values[0], d->values[1], d->values[2]), azimuth, elevation);
    const Camera& camera = r_->scene.camera;
    azimuth -= 180.0 * du / std::max(1, camera.width);
    elevation = std::clamp(elevation - 90.0 * dv / std::max(1, camera.height), -10.0, 90.0);
    radiosity::EmitterEdit e;
    e.direction = sunDirection(azimuth, elevation);
    editLight(name, e);
}

void Session::sunAngles(const Vec3& direction, double& azimuth, double& elevation) {
    constexpr double kDeg = 180 / 3.14159265358979323846;
    const Vec3 d = glm::normalize(direction);
    azimuth = std::atan2(d.y, d.x) * kDeg;
    elevation = std::asin(std::clamp(d.z, -1.0, 1.0)) * kDeg;
}

bool Session::previewMoves() {
    // The lights whose place changed since the last update, nothing else: a sun turned, a
    // point lamp moved (the strengths are the same: update() checked them).
    std::vector<size_t> movedNow;
    for (size_t i = 0; i < lights_.size(); ++i) {
        const LightControl& c = lights_[i];
        if (!c.emitter || c.component != 0) continue;
        if (i >= appliedEmitters_.size() || !appliedEmitters_[i]) return false;
        const std::vector<radiosity::EmitterField> was = appliedEmitters_[i]->fields();
        const std::vector<radiosity::EmitterField> is = c.emitter->fields();
        bool same = was.size() == is.size();
        for (size_t f = 0; same && f < was.size(); ++f) same = was[f].values == is[f].values;
        if (same) continue;
        LightEdit e;
        e.emitter = c.emitter->editFrom(*appliedEmitters_[i]);
        if (!e.moves() || !c.on) return false;
        movedNow.push_back(i);
    }
    if (movedNow.empty()) return false;
    if (!dyn_) {
        // Nothing solved beyond the preparation (no light moved yet, no virtual part): the
        // photo's lights in place, at the lights' radiances, each at its scene index.
        std::vector<Rgb> real;
        for (size_t l = 0; l < static_cast<size_t>(realLights_); ++l)
            real.push_back(lights_[l].radiance());
        dyn_ = std::make_unique<DynamicRelighting>(*r_, real, &geometry_);
        solverLight_.assign(lights_.size(), -1);
        for (size_t l = 0; l < static_cast<size_t>(realLights_); ++l)
            solverLight_[l] = static_cast<int>(l);
    }
    for (const size_t i : movedNow)
        if (i >= solverLight_.size() || solverLight_[i] < 0) return false;
    for (const size_t i : movedNow) dyn_->previewEmitter(solverLight_[i], *lights_[i].emitter);
    previewed_ = movedNow.size() == 1 ? solverLight_[movedNow[0]] : -1;
    return true;
}

std::optional<MovedLightFrame> Session::movedLightFrame() {
    if (movingLight_ < 0 || !dyn_) return std::nullopt;
    return dyn_->movedLightFrame(movingLight_);
}

bool Session::prepareMovedLightFrames() {
    const PreparedImage& P = r_->prepared;
    const size_t pixels =
        static_cast<size_t>(P.display.width) * static_cast<size_t>(P.display.height);
    if (geometry_.pooledByRadius || P.pixelDirect.empty() ||
        P.photoPixels.rho.size() != 3 * pixels || P.photoPixels.light.size() != pixels)
        return false;
    geometry_.pooledByRadius =
        std::make_shared<const std::vector<float>>(pooledByRadius(P.display, P.photoPixels));
    return true;
}

std::optional<radiosity::ShadowSource> Session::movingSource() const {
    if (movingLight_ < 0 || !dyn_) return std::nullopt;
    return dyn_->shownSource(movingLight_);
}

}  // namespace relight::viewer
