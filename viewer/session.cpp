#include "viewer/session.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "radiosity/emitter.h"
#include "radiosity/stopwatch.h"
#include "relight/errors.h"
#include "relight/io/edit_writer.h"
#include "relight/io/mesh_reader.h"
#include "relight/io/scene_lights.h"

namespace relight::viewer {

namespace fs = std::filesystem;
using radiosity::Clock;
using radiosity::secondsSince;

namespace {

/// A unit vector perpendicular to n: the world x axis made perpendicular (y when n is
/// nearly x), so that a box on a floor is aligned with the room's axes.
Vec3 tangentOf(const Vec3& n) {
    const Vec3 a = std::abs(n.x) < 0.9 ? Vec3(1, 0, 0) : Vec3(0, 1, 0);
    return glm::normalize(a - n * glm::dot(a, n));
}

/// "V3": with snprintf, as GCC 12 warns wrongly (-Wrestrict) on "V" + std::to_string(3).
std::string numbered(const char* prefix, int n) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%s%d", prefix, n);
    return buf;
}

ObjFile unitBox() {
    std::istringstream in(unitBoxObjText());
    return parseObj(in, "unit box");
}

}  // namespace

Rgb LightControl::radiance() const {
    if (emitter) return on ? emitter->strengths().at(static_cast<size_t>(component)) : Rgb{};
    return on ? colour * intensity : Rgb{};
}

namespace {

/// Real light l (component 0 of a sun, point lamp or sky) as `edit` leaves it: its emitter
/// with the photo's strengths, edited as editRadiance() and movedLights() edit it for
/// `relight render`; `on` false when the edit or the photo has it off (then the emitter
/// keeps its nominal strengths for when it goes on).
std::shared_ptr<radiosity::Emitter> startingEmitter(const SceneFile& sf, const EditFile& edit,
                                                    const std::vector<Rgb>& photoRadiance, size_t l,
                                                    bool& on) {
    const radiosity::Light& light = sf.scene.lights[l];
    std::shared_ptr<radiosity::Emitter> em = light.emitter->clone();
    const size_t n = static_cast<size_t>(em->components());
    std::vector<Rgb> nominal(photoRadiance.begin() + static_cast<long>(l),
                             photoRadiance.begin() + static_cast<long>(l + n));
    em->setStrengths(nominal);
    on = sf.lightOnInPhoto(l);
    if (auto it = edit.lights.find(light.name); it != edit.lights.end() && it->second.emitter) {
        em->apply(*it->second.emitter);
        on = true;
    }
    if (!em->on()) {
        // Off: its nominal strengths (the photo's, else scene.json's) wait for it.
        for (size_t c = 0; c < n; ++c)
            if (!(nominal[c].maxComponent() > 0)) nominal[c] = sf.scene.lights[l + c].radiance;
        em->setStrengths(nominal);
        on = false;
    }
    return em;
}

}  // namespace

void LightControl::setRadiance(const Rgb& radiance) {
    intensity = std::max({radiance.r, radiance.g, radiance.b, 0.0});
    colour = intensity > 0 ? radiance * (1.0 / intensity) : Rgb{1, 1, 1};
    on = true;
}

Session::Session(Relighting& r, const EditFile& edit) : r_(&r) {
    if (!r_->solver) throw std::invalid_argument("Session: the relighting is not prepared");
    const SceneFile& sf = r_->scene;
    realLights_ = static_cast<int>(sf.scene.lights.size());
    realPolygons_ = r_->solver->scene().polygons.size();
    const auto b = r_->solver->scene().bounds();
    diagonal_ = std::max(glm::length(b.hi - b.lo), 1e-3);
    const std::vector<Rgb> radiance = editRadiance(sf, edit, r_->prepared.photoRadiance);
    for (int l = 0; l < realLights_; ++l) {
        LightControl c;
        c.name = sf.scene.lights[static_cast<size_t>(l)].name;
        if (const radiosity::Light& light = sf.scene.lights[static_cast<size_t>(l)];
            light.emitter) {
            // A sun, point lamp or sky: one emitter, shared by its components' controls.
            if (light.component == 0)
                c.emitter = startingEmitter(sf, edit, r_->prepared.photoRadiance,
                                            static_cast<size_t>(l), c.on);
            else {
                c.emitter = lights_.back().emitter;
                c.on = lights_.back().on;
            }
            c.component = light.component;
            lights_.push_back(c);
            continue;
        }
        c.setRadiance(radiance[static_cast<size_t>(l)]);
        // A light that is off keeps its nominal colour and strength for when it goes on.
        if (!(radiance[static_cast<size_t>(l)].maxComponent() > 0)) {
            c.setRadiance(r_->prepared.photoRadiance[static_cast<size_t>(l)].maxComponent() > 0
                              ? r_->prepared.photoRadiance[static_cast<size_t>(l)]
                              : sf.scene.lights[static_cast<size_t>(l)].radiance);
            c.on = false;
        }
        lights_.push_back(c);
    }
    for (const VirtualLight& v : edit.addLights) {
        LightControl c;
        c.name = v.name;
        c.isVirtual = true;
        c.face = v;
        c.setRadiance(v.radiance);
        if (v.emitter) {
            c.emitter = v.emitter->clone();
            c.face.emitter = nullptr;  // the control's emitter is the light
        }
        lights_.push_back(c);
    }
    removed_ = edit.removeObjects;
    for (const VirtualObject& o : edit.addObjects) {
        ObjectControl c;
        c.object = o;
        c.geometry = readMesh(o.file).geometry;  // any format the edit loader reads
        objects_.push_back(std::move(c));
    }
    stale_ = true;
    update();
}

Session::~Session() {
    dyn_.reset();  // takes the virtual parts out of the relighting's solver
}

namespace {

/// Virtual light `c` as an edit's add_lights entry has it (off: zero strengths).
VirtualLight virtualLight(const LightControl& c) {
    VirtualLight v = c.face;
    v.name = c.name;
    v.radiance = c.radiance();
    if (c.emitter) {
        std::shared_ptr<radiosity::Emitter> em = c.emitter->clone();
        if (!c.on) {
            radiosity::EmitterEdit off;
            off.scale = 0.0;
            em->apply(off);
        }
        v.emitter = std::move(em);
    }
    return v;
}

}  // namespace

bool Session::moved(size_t l) const {
    const LightControl& c = lights_[l];
    if (!c.emitter || c.isVirtual || !c.on) return false;
    LightEdit e;
    e.emitter = c.emitter->editFrom(*r_->scene.scene.lights[l].emitter);
    return e.moves();
}

bool Session::anyMoved() const {
    for (size_t l = 0; l < static_cast<size_t>(realLights_); ++l)
        if (lights_[l].component == 0 && moved(l)) return true;
    return false;
}

std::vector<double> Session::emitterState() const {
    std::vector<double> out;
    for (const LightControl& c : lights_) {
        if (!c.emitter || c.component != 0) continue;
        out.push_back(c.on ? 1 : 0);
        for (const radiosity::EmitterField& f : c.emitter->fields())
            out.insert(out.end(), f.values.begin(), f.values.end());
    }
    return out;
}

LightControl* Session::findControl(const std::string& name) {
    for (LightControl& c : lights_)
        if (c.name == name) return &c;
    return nullptr;
}

const radiosity::Emitter* Session::emitter(const std::string& name) const {
    for (const LightControl& c : lights_)
        if (c.name == name) return c.emitter.get();
    return nullptr;
}

void Session::editLight(const std::string& name, const radiosity::EmitterEdit& e) {
    LightControl* c = findControl(name);
    if (!c || !c->emitter)
        throw std::invalid_argument("no sun, point lamp or sky \"" + name + "\" to edit");
    std::shared_ptr<radiosity::Emitter> next = c->emitter->clone();
    next->apply(e);  // throws for a field the light lacks, the light unchanged
    const std::shared_ptr<radiosity::Emitter> old = c->emitter;
    for (LightControl& l : lights_)
        if (l.emitter == old) l.emitter = next;
    update();
}

std::string Session::addPointLampAt(const Pick& p, double offset) {
    if (!p.hit) throw std::invalid_argument("no surface there to put a point lamp above");
    LightControl c;
    do {
        c.name = numbered("P", nextPoint_++);
    } while (findControl(c.name));
    c.isVirtual = true;
    c.face.name = c.name;
    // The scene's mean irradiance at 10 % of its diagonal: a lamp of the room's scale.
    Rgb H;
    const std::vector<Rgb> h = vertexIrradiance();
    for (const Rgb& x : h) H += x;
    H = h.empty() ? Rgb{} : H * (1.0 / static_cast<double>(h.size()));
    if (!(H.maxComponent() > 0)) H = Rgb{1, 1, 1};
    const double d = 0.1 * diagonal_;
    c.emitter = radiosity::makePointLamp(
        c.name, p.point + glm::normalize(p.normal) * offsetOrDefault(offset), H * (d * d));
    lights_.push_back(c);
    stale_ = true;
    update();
    return c.name;
}

bool Session::settle() {
    // During a drag only the moved object's quick image settles (the pointer rests); the
    // next move shows it quickly again.
    if (!canSettle()) return false;
    stale_ = true;
    update();
    return true;
}

void Session::rebuild() {
    exactPending_ = faceShownMoved_ = false;
    dyn_.reset();
    objectPolygons_.clear();
    const std::vector<Rgb> real = realRadiance();
    solverLight_.assign(lights_.size(), -1);
    for (size_t l = 0; l < static_cast<size_t>(realLights_); ++l)
        solverLight_[l] = static_cast<int>(l);
    if (hasVirtualParts()) {
        dyn_ = std::make_unique<DynamicRelighting>(*r_, real, &geometry_);
        for (const std::string& name : removed_) dyn_->removeObject(name);
        // In render's order (relight/cli/render.cpp): the moved lights, then the virtual ones.
        for (size_t l = 0; l < static_cast<size_t>(realLights_); ++l)
            if (lights_[l].component == 0 && moved(l))
                solverLight_[l] =
                    dyn_->addLight({lights_[l].name, {}, Rgb{}, lights_[l].emitter->clone()});
        for (size_t l = static_cast<size_t>(realLights_); l < lights_.size(); ++l)
            solverLight_[l] = dyn_->addLight(virtualLight(lights_[l]));
        for (const ObjectControl& o : objects_) {
            const size_t first = r_->solver->scene().polygons.size();
            dyn_->addObject(o.object);
            objectPolygons_.emplace_back(first, r_->solver->scene().polygons.size());
        }
    }
    stale_ = false;
}

void Session::update() {
    apply(/*quickOnly=*/false);
}

bool Session::updateQuickly() {
    return apply(/*quickOnly=*/true);
}

bool Session::apply(bool quickOnly) {
    const auto t0 = Clock::now();
    std::vector<Rgb> now;
    for (const LightControl& l : lights_) now.push_back(l.radiance());
    std::vector<double> state = emitterState();
    bool strengthsKept = now.size() == applied_.size();
    for (size_t i = 0; strengthsKept && i < now.size(); ++i) strengthsKept = now[i] == applied_[i];
    const bool radianceChanged = !strengthsKept || state != appliedState_;
    if (!stale_ && !faceShownMoved_ && !radianceChanged) return true;
    const bool shapesKept = state == appliedState_;
    const bool sameCount = applied_.size() == now.size();
    // An object shown moved (dragTo's quick frames) is not in the solver: insert it again.
    // So is a lamp's face shown moved (previewFace).
    const bool stale = stale_ || faceShownMoved_ || (dyn_ && dyn_->previewingObject());
    // Without virtual parts (nor a moved light, nor any before) a radiance change is the
    // superposition path: nothing to solve. With virtual objects, the quick path while a
    // slider moves (settle() makes it exact); a sun or lamp moved, its quick path too.
    // Each quick path changes nothing where it does not apply, so that updateQuickly() can
    // leave the rest to update() (on the window's worker thread).
    bool quickMove = false;
    if (!stale && strengthsKept && !shapesKept && quickMoves_ && previewMoves()) {
        quickMove = exactPending_ = true;
    } else if (!stale && radianceChanged && shapesKept && dyn_ && sameCount &&
               dyn_->setRealRadiances(realRadiance())) {
        exactPending_ = true;
    } else if (stale || (radianceChanged && (hasVirtualParts() || dyn_))) {
        if (quickOnly) return false;
        stale_ = true;
        rebuild();
    }
    const std::vector<Rgb> before = std::exchange(applied_, now);
    appliedState_ = std::move(state);
    // The first update (the edit the session starts from) is checked on its first frame,
    // which names the edit's key (viewer/main.cpp); a change made in the panel here. A move
    // shown quickly keeps the vertices' values, and the strengths: nothing to check.
    if (!quickMove && !before.empty() && sameCount && !displayFinite()) undo(before);
    appliedEmitters_.clear();
    for (const LightControl& l : lights_)
        appliedEmitters_.push_back(
            l.emitter ? std::shared_ptr<radiosity::Emitter>(l.emitter->clone()) : nullptr);
    updateSeconds_ = secondsSince(t0);
    const int wasMoving = movingLight_, epoch = movingEpoch_;
    changed();
    // One light moved quickly, and the same as the last change's: the frames of one drag.
    if (quickMove && previewed_ >= 0) {
        movingLight_ = previewed_;
        if (previewed_ == wasMoving) movingEpoch_ = epoch;
    }
    return true;
}

bool Session::displayFinite() const {
    // The display's values go to the GPU as 32-bit floats.
    constexpr double kMax = std::numeric_limits<float>::max();
    for (const Rgb& v : vertexRatios())
        for (int c = 0; c < 3; ++c)
            if (!(std::abs(v[c]) <= kMax)) return false;
    return true;
}

void Session::undo(const std::vector<Rgb>& before) {
    std::string names;
    for (size_t i = 0; i < lights_.size(); ++i) {
        LightControl& l = lights_[i];
        if (l.radiance() == before[i]) continue;
        char value[96];
        std::snprintf(value, sizeof value, " [%.6g, %.6g, %.6g]", l.radiance().r, l.radiance().g,
                      l.radiance().b);
        names += (names.empty() ? "" : ", ") + ("\"" + l.name + "\"") + value;
        if (l.emitter) {
            // Its emitter as last applied, shared again by the light's components.
            if (i < appliedEmitters_.size() && appliedEmitters_[i]) {
                const std::shared_ptr<radiosity::Emitter> old = l.emitter;
                const std::shared_ptr<radiosity::Emitter> back = appliedEmitters_[i]->clone();
                for (LightControl& o : lights_)
                    if (o.emitter == old) o.emitter = back;
            }
            continue;
        }
        if (before[i].maxComponent() > 0)
            l.setRadiance(before[i]);
        else
            l.on = false;
    }
    applied_.clear();
    for (const LightControl& l : lights_) applied_.push_back(l.radiance());
    appliedState_ = emitterState();
    if (hasVirtualParts() || dyn_) rebuild();
    changed();
    throw InputError("the relit image would not be finite with the radiance of " + names +
                     ": the change is undone");
}

void Session::setReflectance(int i, const Rgb& reflectance) {
    ObjectControl& o = objects_.at(static_cast<size_t>(i));
    for (int c = 0; c < 3; ++c)
        if (!(reflectance[c] >= 0 && reflectance[c] < 1))
            throw std::invalid_argument("a reflectance must be in [0, 1)");
    o.object.reflectance = reflectance;
    std::vector<std::string> warnings;
    placeObject(o.object, o.geometry, warnings);
    stale_ = true;
    update();
}

void Session::setSpecular(int i, const std::optional<Specular>& specular) {
    ObjectControl& o = objects_.at(static_cast<size_t>(i));
    if (specular) {
        for (int c = 0; c < 3; ++c)
            if (!(specular->ks[c] >= 0 && std::isfinite(specular->ks[c])))
                throw std::invalid_argument("ks must be finite and >= 0");
        if (!(specular->shininess > 0 && specular->shininess <= 1e5))
            throw std::invalid_argument("the shininess must be in (0, 100000]");
    }
    o.object.specular = specular;
    const auto sameName = std::count_if(objects_.begin(), objects_.end(), [&](const auto& x) {
        return x.object.name == o.object.name;
    });
    // The term is the overlay's alone (DynamicRelighting::setObjectSpecular): no update,
    // unless a name is shared and only inserting the parts again tells the objects apart.
    if (dyn_ && sameName == 1 && dyn_->setObjectSpecular(o.object.name, specular) == 1) {
        changed();
        return;
    }
    stale_ = true;
    update();
}

Pick Session::pick(double u, double v, const std::string& through) const {
    const Camera& camera = r_->scene.camera;
    const Vec3 eye = camera.position();
    const Vec3 dir = camera.rayDirection(u, v);
    const auto& lights = r_->solver->scene().lights;
    const int passed = through.empty() ? -1 : r_->solver->scene().findLight(through);
    const int ignore = passed >= 0 && lights[static_cast<size_t>(passed)].polygons.size() == 1
                           ? lights[static_cast<size_t>(passed)].polygons[0]
                           : -1;
    const auto hit = r_->solver->visibility().intersect(eye, dir, 0, 1e30, ignore);
    Pick p;
    const auto& polygons = r_->solver->scene().polygons;
    if (hit.polygon < 0 || hit.polygon >= static_cast<int>(polygons.size())) return p;
    p.hit = true;
    p.point = eye + hit.t * dir;
    p.normal = polygons[static_cast<size_t>(hit.polygon)].normal;
    if (glm::dot(p.normal, dir) > 0) p.normal = -p.normal;
    for (size_t i = 0; i < objectPolygons_.size(); ++i)
        if (static_cast<size_t>(hit.polygon) >= objectPolygons_[i].first &&
            static_cast<size_t>(hit.polygon) < objectPolygons_[i].second)
            p.object = static_cast<int>(i);
    const auto& scene = r_->scene;
    if (static_cast<size_t>(hit.polygon) < r_->solver->scenePolygons()) {
        const int object = polygons[static_cast<size_t>(hit.polygon)].object;
        const std::string& name = scene.scene.objects[static_cast<size_t>(object)];
        const auto settings = scene.objectSettings.find(name);
        if (settings != scene.objectSettings.end() && settings->second.removable)
            p.realObject = name;
    }
    return p;
}

void Session::removeRealObject(const std::string& name) {
    const auto settings = r_->scene.objectSettings.find(name);
    if (settings == r_->scene.objectSettings.end() || !settings->second.removable)
        throw std::invalid_argument("object \"" + name +
                                    "\" is not marked \"removable\" in scene.json");
    if (std::find(removed_.begin(), removed_.end(), name) != removed_.end()) return;
    removed_.push_back(name);
    stale_ = true;
    update();
}

void Session::restoreRealObject(const std::string& name) {
    const auto it = std::find(removed_.begin(), removed_.end(), name);
    if (it == removed_.end()) return;
    removed_.erase(it);
    stale_ = true;
    update();
}

void Session::addLightAt(const Pick& p) {
    if (!p.hit) return;
    const auto& scene = r_->solver->scene();
    // The scene's own lights give the size and strength of a lamp in this room.
    double area = 0;
    int faces = 0;
    Rgb radiance;
    int lit = 0;
    for (int l = 0; l < realLights_; ++l) {
        const auto& light = scene.lights[static_cast<size_t>(l)];
        for (int poly : light.polygons) area += scene.polygons[static_cast<size_t>(poly)].area;
        faces += light.polygons.empty() ? 0 : 1;
        const Rgb L = r_->prepared.photoRadiance[static_cast<size_t>(l)];
        if (L.maxComponent() > 0) {
            radiance += L;
            ++lit;
        }
    }
    const double side = faces > 0 && area > 0 ? std::sqrt(area / faces) : 0.05 * diagonal_;
    radiance = lit > 0 ? radiance * (1.0 / lit) : Rgb{10, 10, 10};
    const Vec3 n = glm::normalize(p.normal);
    LightControl l;
    do {
        l.name = numbered("V", nextLight_++);
    } while (std::any_of(lights_.begin(), lights_.end(),
                         [&](const LightControl& o) { return o.name == l.name; }));
    l.isVirtual = true;
    // Counter-clockwise seen from the side it emits to: (v1 - v0) x (v2 - v0) along n.
    l.face.name = l.name;
    l.face.corners = lampQuad(p.point + n * std::max(0.005, 0.02 * side), n, side, side);
    l.setRadiance(radiance);
    l.face.radiance = radiance;
    const bool appendable =
        dyn_ && !stale_ && !faceShownMoved_ && !dyn_->previewingObject() && objects_.empty();
    lights_.push_back(l);
    if (appendable) {
        const int at = dyn_->addLight(l.face);
        solverLight_.resize(lights_.size(), -1);
        solverLight_.back() = at;
        applied_.push_back(l.radiance());
        appliedEmitters_.push_back(nullptr);
        changed();
    } else {
        stale_ = true;
        update();
    }
}

std::vector<Vec3> PlacedLamp::corners() const {
    const Vec3 n = glm::normalize(normal);
    return lampQuad(centre + n * std::max(0.005, 0.01 * std::max(width, height)), n, width, height);
}

int Session::placeLampAt(const Pick& p, double width, double height) {
    if (!p.hit) throw std::invalid_argument("no surface there to put a lamp on");
    const auto& scene = r_->solver->scene();
    // The size of the scene's own lamps, as for a virtual light (addLightAt).
    double area = 0;
    int lamps = 0;
    for (int l = 0; l < realLights_; ++l) {
        const auto& light = scene.lights[static_cast<size_t>(l)];
        for (int poly : light.polygons) area += scene.polygons[static_cast<size_t>(poly)].area;
        lamps += light.polygons.empty() ? 0 : 1;
    }
    const double side = lamps > 0 && area > 0 ? std::sqrt(area / lamps) : 0.05 * diagonal_;
    PlacedLamp lamp;
    auto taken = [&](const std::string& name) {
        return std::any_of(lights_.begin(), lights_.end(),
                           [&](const LightControl& o) { return o.name == name; }) ||
               std::any_of(placed_.begin(), placed_.end(),
                           [&](const PlacedLamp& o) { return o.name == name; });
    };
    do {
        lamp.name = numbered("L", nextLamp_++);
    } while (taken(lamp.name));
    lamp.centre = p.point;
    lamp.normal = glm::normalize(p.normal);
    lamp.width = width > 0 ? width : side;
    lamp.height = height > 0 ? height : side;
    placed_.push_back(lamp);
    return static_cast<int>(placed_.size()) - 1;
}

void Session::moveLampTo(int i, const Pick& p) {
    if (!p.hit) throw std::invalid_argument("no surface there to put the lamp on");
    PlacedLamp& lamp = placed_.at(static_cast<size_t>(i));
    lamp.centre = p.point;
    lamp.normal = glm::normalize(p.normal);
}

void Session::saveLamps(const fs::path& sceneDir) {
    std::vector<RealLamp> lamps;
    for (const PlacedLamp& p : placed_)
        lamps.push_back({p.name, p.corners(),
                         p.estimate ? std::nullopt : std::optional<Rgb>(p.radiance), p.onInPhoto});
    addLampsToScene(sceneDir, lamps);
    placed_.clear();
}

void Session::addBoxAt(const Pick& p) {
    if (!p.hit) return;
    ObjectControl o;
    do {
        o.object.name = numbered("box", nextBox_++);
    } while (std::any_of(objects_.begin(), objects_.end(),
                         [&](const ObjectControl& x) { return x.object.name == o.object.name; }));
    o.viewerBox = true;
    o.geometry = unitBox();
    o.object.reflectance = Rgb{0.7, 0.2, 0.2};
    const double s = 0.06 * diagonal_;
    const Vec3 z = glm::normalize(p.normal);
    const Vec3 x = tangentOf(z);
    const Vec3 y = glm::cross(z, x);
    for (int i = 0; i < 3; ++i) {
        o.object.transform[static_cast<size_t>(i)] = {x[i] * s, y[i] * s, z[i] * s, p.point[i]};
    }
    o.object.transform[3] = {0, 0, 0, 1};
    std::vector<std::string> warnings;
    placeObject(o.object, o.geometry, warnings);
    const bool appendable = dyn_ && !stale_ && !faceShownMoved_ && !dyn_->previewingObject();
    objects_.push_back(std::move(o));
    if (appendable) {
        const size_t first = r_->solver->scene().polygons.size();
        dyn_->addObject(objects_.back().object);
        objectPolygons_.emplace_back(first, r_->solver->scene().polygons.size());
        changed();
    } else {
        stale_ = true;
        update();
    }
}

void Session::beginDrag(int i, const Pick& p) {
    if (i < 0 || i >= static_cast<int>(objects_.size()) || !p.hit) return;
    // Only the part added last moves incrementally: put this object at the end.
    if (i != static_cast<int>(objects_.size()) - 1) {
        std::rotate(objects_.begin() + i, objects_.begin() + i + 1, objects_.end());
        stale_ = true;
        update();
    }
    dragging_ = static_cast<int>(objects_.size()) - 1;
    grab_ = p.point;
    const auto& M = objects_.back().object.transform;
    dragUp_ = glm::normalize(Vec3(M[0][2], M[1][2], M[2][2]));
}

bool Session::dragTo(double u, double v) {
    if (dragging_ < 0 || !dyn_) return false;
    const auto t0 = Clock::now();
    const Camera& camera = r_->scene.camera;
    const Vec3 eye = camera.position();
    const Vec3 dir = camera.rayDirection(u, v);
    const double denom = glm::dot(dir, dragUp_);
    if (std::abs(denom) < 1e-9) return false;  // the ray runs along the plane
    const double t = glm::dot(grab_ - eye, dragUp_) / denom;
    if (!(t > 0) || !std::isfinite(t)) return false;  // the plane is behind the camera
    const Vec3 q = eye + t * dir;
    const Vec3 delta = q - grab_;
    grab_ = q;
    ObjectControl& o = objects_.back();
    for (int i = 0; i < 3; ++i) o.object.transform[static_cast<size_t>(i)][3] += delta[i];
    std::vector<std::string> warnings;
    placeObject(o.object, o.geometry, warnings);
    if (quickMoves_ && dyn_->previewLastObject(o.object.polygons)) {
        exactPending_ = true;  // settle() or endDrag() inserts it where it is
    } else if (dyn_->previewingObject()) {
        stale_ = true;  // quick moves turned off during the drag: solved as render solves it
        update();
    } else {
        dyn_->moveLastObject(o.object.polygons);
    }
    updateSeconds_ = secondsSince(t0);
    changed();
    return true;
}

std::string Session::stage() const {
    if (!exactPending_) return "exact";
    if (dyn_ && dyn_->previewingObject())
        return "drag: direct light only (the box's shadows and its own light; the indirect "
               "light as without it), exact when the drag rests";
    return "quick image: exact when the slider rests";
}

void Session::endDrag() {
    if (dragging_ < 0) return;
    dragging_ = -1;
    stale_ = true;
    update();
}

void Session::removeLight(int i) {
    if (i < realLights_ || i >= static_cast<int>(lights_.size())) return;
    // A sun, point lamp or sky comes out by a rebuild (its light has no face to take out).
    const bool last = objects_.empty() && i == static_cast<int>(lights_.size()) - 1 &&
                      !lights_[static_cast<size_t>(i)].emitter;
    lights_.erase(lights_.begin() + i);
    if (last && dyn_ && !stale_ && !faceShownMoved_ && !dyn_->previewingObject()) {
        dyn_->removeLast();
        if (static_cast<size_t>(i) < solverLight_.size())
            solverLight_.erase(solverLight_.begin() + i);
        applied_.erase(applied_.begin() + i);
        if (static_cast<size_t>(i) < appliedEmitters_.size())
            appliedEmitters_.erase(appliedEmitters_.begin() + i);
        if (!hasVirtualParts()) dyn_.reset();
        changed();
    } else {
        stale_ = true;
        update();
    }
}

void Session::removeObject(int i) {
    if (i < 0 || i >= static_cast<int>(objects_.size())) return;
    const bool last = i == static_cast<int>(objects_.size()) - 1;
    objects_.erase(objects_.begin() + i);
    dragging_ = -1;
    if (last && dyn_ && !stale_ && !faceShownMoved_ && !dyn_->previewingObject()) {
        dyn_->removeLast();
        objectPolygons_.pop_back();
        if (!hasVirtualParts()) dyn_.reset();
        changed();
    } else {
        stale_ = true;
        update();
    }
}

std::vector<Rgb> Session::realRadiance() const {
    std::vector<Rgb> out;
    // A moved light is off where it was (rebuild() puts it where it went).
    for (size_t l = 0; l < static_cast<size_t>(realLights_); ++l)
        out.push_back(moved(l - static_cast<size_t>(lights_[l].component)) ? Rgb{}
                                                                           : lights_[l].radiance());
    return out;
}

std::vector<Rgb> Session::vertexIrradiance() const {
    if (dyn_) return dyn_->vertexIrradiance();
    return relight::vertexIrradiance(r_->prepared, realRadiance());
}

std::vector<Rgb> Session::vertexRatios() const {
    if (dyn_) return dyn_->vertexRatios();
    return vertexRatio(r_->prepared, relight::vertexIrradiance(r_->prepared, realRadiance()));
}

Image Session::relitPerPixel(DisplayMode mode) {
    if (!drawsPerPixel(mode))
        throw std::invalid_argument(std::string("relitPerPixel: the ") + displayModeName(mode) +
                                    " display does not draw per pixel");
    if (dyn_) return dyn_->render(mode);
    return renderEdit(r_->prepared, realRadiance(), mode);
}

VirtualOverlay Session::overlay() {
    return dyn_ ? dyn_->overlay() : VirtualOverlay{};
}

fs::path Session::boxObjFile(const fs::path& editFile) {
    return editFile.parent_path() / (editFile.stem().string() + ".box.obj");
}

EditFile Session::edit(const fs::path& editFile) const {
    EditFile e;
    e.file = editFile;
    for (int l = 0; l < realLights_; ++l) {
        const LightControl& c = lights_[static_cast<size_t>(l)];
        LightEdit le;
        if (c.emitter) {
            // A sun, point lamp or sky: the edit that takes scene.json's light to this one.
            if (c.component != 0) continue;
            le.light = r_->scene.scene.lights[static_cast<size_t>(l)].emitter;
            radiosity::EmitterEdit ee;
            if (c.on)
                ee = c.emitter->editFrom(*le.light);
            else
                ee.scale = 0.0;
            le.scale = ee.scale;
            le.emitter = ee;
            e.lights[c.name] = le;
            continue;
        }
        if (c.on)
            le.radiance = c.radiance();
        else
            le.scale = 0.0;
        e.lights[c.name] = le;
    }
    for (size_t l = static_cast<size_t>(realLights_); l < lights_.size(); ++l)
        e.addLights.push_back(virtualLight(lights_[l]));
    for (const ObjectControl& o : objects_) {
        VirtualObject v = o.object;
        if (o.viewerBox) v.file = boxObjFile(editFile);
        e.addObjects.push_back(v);
    }
    e.removeObjects = removed_;
    return e;
}

void Session::save(const fs::path& editFile) const {
    const EditFile e = edit(editFile);
    if (std::any_of(objects_.begin(), objects_.end(),
                    [](const ObjectControl& o) { return o.viewerBox; }))
        writeUnitBoxObj(boxObjFile(editFile));
    writeEdit(editFile, e);
}

}  // namespace relight::viewer
