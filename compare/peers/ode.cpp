// ODE 0.16 (double precision): dCollide of a dRay with a dCylinder (flat caps), a dSphere or a
// dCapsule, the ray query of ODE's collision detection.
#include "peers/peers.hpp"

#include <ode/ode.h>

#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <memory>
#include <string>

namespace linequad::peers {

namespace {

// What ODE prints (its internal errors, as "ODE INTERNAL ERROR 1: assertion ... in
// dxNormalize3()" before an abort that the audit counts as a crash) goes to the report, not to
// the terminal of whoever runs the audit.
const std::shared_ptr<audit::OwnOutput>& ode_output() {
    static const auto out = std::make_shared<audit::OwnOutput>();
    return out;
}

void keep_message(const char* what, int errnum, const char* msg, va_list ap) {
    char text[512];
    std::vsnprintf(text, sizeof text, msg, ap);
    ode_output()->write(std::string(what) + " " + std::to_string(errnum) + ": " + text + "\n");
}

struct World {
    World() {
        dSetErrorHandler(
            [](int n, const char* m, va_list ap) { keep_message("ODE Error", n, m, ap); });
        dSetDebugHandler(
            [](int n, const char* m, va_list ap) { keep_message("ODE INTERNAL ERROR", n, m, ap); });
        dSetMessageHandler(
            [](int n, const char* m, va_list ap) { keep_message("ODE Message", n, m, ap); });
        dInitODE2(0);
    }
    ~World() { dCloseODE(); }
};

// ODE keeps data per thread, and the audit calls it from whichever of its workers grades the
// chunk (one at a time): each calling thread allocates its own once.
void enter_ode() {
    static World world;
    thread_local bool ready = dAllocateODEDataForThread(dAllocateMaskAll) != 0;
    (void)ready;
}

// ODE's rays have a length; the audit's rays none. Long enough for any case, short enough that
// length times a unit direction stays finite.
constexpr double ray_length = 0x1p500;

// g with its z axis along H - C (a rotation, rounded) and its centre at the axis' midpoint.
dGeomID placed(dGeomID g, Vec3 C, Vec3 H) {
    Basis b = basis_along(H - C);
    dMatrix3 R = {b.x.x, b.y.x, b.z.x, 0, b.x.y, b.y.y, b.z.y, 0, b.x.z, b.y.z, b.z.z, 0};
    Vec3 mid = 0.5 * (C + H);
    dGeomSetPosition(g, mid.x, mid.y, mid.z);
    dGeomSetRotation(g, R);
    return g;
}

// The closest contact of the posed ray with g (which it then destroys): its depth (the distance
// along u) and position.
std::optional<Result> ray_against(dGeomID g, const Line& l) {
    double length = std::isinf(l.range.t1) ? ray_length : l.range.t1;
    dGeomID ray = dCreateRay(nullptr, length);
    dGeomRaySet(ray, l.L0.x, l.L0.y, l.L0.z, l.v.x, l.v.y, l.v.z);
    dGeomRaySetClosestHit(ray, 1);
    dContactGeom contact;
    int n = dCollide(ray, g, 1, &contact, sizeof contact);
    dGeomDestroy(ray);
    dGeomDestroy(g);
    Result r;
    if (n > 0)
        r.hits[r.count++] = Hit{contact.depth, {contact.pos[0], contact.pos[1], contact.pos[2]},
                                NAN,           HitKind::cross,
                                Part::lateral, false};
    return r;
}

} // namespace

audit::ExternalSolver ode() {
    audit::ExternalSolver s;
    s.name = "ode";
    s.answers = audit::Answers::nearest;
    s.parametrisation = audit::Parametrisation::unit_direction;
    s.surface = audit::Surface::closed;
    s.kinds = false, s.parts = false;
    s.own_output = ode_output();
    s.mapping =
        "dCollide(dCreateRay(0, length), dCreateCylinder(0, r, |H - C|), 1 contact) "
        "with dGeomRaySetClosestHit; the ray from L0 along u = v/|v| (ODE normalises it "
        "again), length t1 (2^500 for a ray); the answer is the contact's depth (the "
        "distance along u) and pos. The cylinder placed at the axis' midpoint by a "
        "rotation taking z to the axis (rounded). Sphere: dCreateSphere(r) at C. Capsule: "
        "dCreateCapsule(r, |H - C|) placed as the cylinder. ODE's rays start at L0: lines and "
        "ranges from t0 > 0 cannot be represented, nor open or infinite shapes, cones, "
        "frusta, the elliptic shapes.";
    s.on<Cylinder>() = [](const Cylinder& c, const Line& l) -> std::optional<Result> {
        enter_ode();
        double h = norm(c.H - c.C);
        if (l.range.t0 != 0 || !(c.r > 0) || !(h > 0)) return std::nullopt;
        return ray_against(placed(dCreateCylinder(nullptr, c.r, h), c.C, c.H), l);
    };
    s.on<Sphere>() = [](const Sphere& k, const Line& l) -> std::optional<Result> {
        enter_ode();
        if (l.range.t0 != 0 || !(k.r > 0)) return std::nullopt;
        dGeomID sphere = dCreateSphere(nullptr, k.r);
        dGeomSetPosition(sphere, k.C.x, k.C.y, k.C.z);
        return ray_against(sphere, l);
    };
    s.on<Capsule>() = [](const Capsule& k, const Line& l) -> std::optional<Result> {
        enter_ode();
        double h = norm(k.H - k.C);
        if (l.range.t0 != 0 || !(k.r > 0) || !(h > 0)) return std::nullopt;
        return ray_against(placed(dCreateCapsule(nullptr, k.r, h), k.C, k.H), l);
    };
    return s;
}

} // namespace linequad::peers
