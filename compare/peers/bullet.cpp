// Bullet 3.24 (double precision build): btCollisionWorld::rayTestSingle, the ray test a physics
// scene's rayTest runs for each object, against a btCylinderShapeZ, a btConeShapeZ, a
// btSphereShape or a btCapsuleShapeZ with Bullet's default collision margin.
#include "peers/peers.hpp"

#include <BulletCollision/CollisionDispatch/btCollisionObject.h>
#include <BulletCollision/CollisionDispatch/btCollisionWorld.h>
#include <BulletCollision/CollisionShapes/btCapsuleShape.h>
#include <BulletCollision/CollisionShapes/btConeShape.h>
#include <BulletCollision/CollisionShapes/btCylinderShape.h>
#include <BulletCollision/CollisionShapes/btSphereShape.h>

#include <cmath>

namespace linequad::peers {

namespace {

// The shape's frame: its local z along the axis, its origin at the axis' midpoint.
btTransform placed(Vec3 base, Vec3 top) {
    Basis b = basis_along(top - base);
    btMatrix3x3 m(b.x.x, b.y.x, b.z.x, b.x.y, b.y.y, b.z.y, b.x.z, b.y.z, b.z.z);
    Vec3 mid = 0.5 * (base + top);
    return btTransform(m, btVector3(mid.x, mid.y, mid.z));
}

std::optional<Result> ray_test(btConvexShape& shape, const btTransform& where, const Line& l) {
    if (!(dot(l.v, l.v) > 0)) return std::nullopt; // Bullet has no answer for a point
    btCollisionObject object;
    object.setCollisionShape(&shape);
    object.setWorldTransform(where);
    Vec3 to = l.L0 + l.v; // exact: the audit poses the segment so
    btVector3 from_v(l.L0.x, l.L0.y, l.L0.z), to_v(to.x, to.y, to.z);
    btTransform from_t(btMatrix3x3::getIdentity(), from_v), to_t(btMatrix3x3::getIdentity(), to_v);
    btCollisionWorld::ClosestRayResultCallback hit(from_v, to_v);
    btCollisionWorld::rayTestSingle(from_t, to_t, &object, &shape, where, hit);
    Result r;
    if (hit.hasHit()) {
        const btVector3& p = hit.m_hitPointWorld;
        r.hits[r.count++] = Hit{double(hit.m_closestHitFraction),
                                {p.x(), p.y(), p.z()},
                                NAN,
                                HitKind::cross,
                                Part::lateral,
                                false};
    }
    return r;
}

} // namespace

audit::ExternalSolver bullet() {
    audit::ExternalSolver s;
    s.name = "bullet";
    s.answers = audit::Answers::first_entry;
    s.parametrisation = audit::Parametrisation::segment;
    s.surface = audit::Surface::closed;
    s.kinds = false, s.parts = false;
    // Bullet's contract: its shapes are rounded by the collision margin (0.04, in scene units),
    // and placed by a rotation rounded to a few ulps of the scene.
    s.tolerance = {0.04, 0x1p-50};
    s.mapping =
        "btCollisionWorld::rayTestSingle(from, to) with a ClosestRayResultCallback; the "
        "answer is m_closestHitFraction and m_hitPointWorld. Cylinder: "
        "btCylinderShapeZ(r, r, |H - C|/2); frustum with one radius 0: "
        "btConeShapeZ(r, |C1 - C0|), its apex at the end of radius 0; each placed by a "
        "rotation taking z to the axis (rounded) and its midpoint, with Bullet's default "
        "collision margin (0.04). Sphere: btSphereShape(r) at C (its margin is its radius). "
        "Capsule: btCapsuleShapeZ(r, |H - C|) placed as the cylinder. Cannot represent: open or "
        "infinite shapes (Bullet's "
        "are solids), lines and rays (a ray test is a segment), frusta with two nonzero "
        "radii, the elliptic shapes.";
    s.on<Cylinder>() = [](const Cylinder& c, const Line& l) -> std::optional<Result> {
        double h = norm(c.H - c.C);
        if (!(c.r > 0) || !(h > 0)) return std::nullopt;
        btCylinderShapeZ shape(btVector3(c.r, c.r, 0.5 * h));
        return ray_test(shape, placed(c.C, c.H), l);
    };
    s.on<Frustum>() = [](const Frustum& f, const Line& l) -> std::optional<Result> {
        if ((f.r0 == 0) == (f.r1 == 0)) return std::nullopt;
        // btConeShapeZ has its apex at +z: z runs from the base disc to the apex.
        Vec3 base = f.r0 > 0 ? f.C0 : f.C1, apex = f.r0 > 0 ? f.C1 : f.C0;
        double h = norm(apex - base);
        if (!(h > 0)) return std::nullopt;
        btConeShapeZ shape(std::max(f.r0, f.r1), h);
        return ray_test(shape, placed(base, apex), l);
    };
    s.on<Sphere>() = [](const Sphere& k, const Line& l) -> std::optional<Result> {
        btSphereShape shape(k.r);
        btTransform at(btMatrix3x3::getIdentity(), btVector3(k.C.x, k.C.y, k.C.z));
        return ray_test(shape, at, l);
    };
    s.on<Capsule>() = [](const Capsule& k, const Line& l) -> std::optional<Result> {
        double h = norm(k.H - k.C);
        if (!(h > 0)) return std::nullopt;
        btCapsuleShapeZ shape(k.r, h);
        return ray_test(shape, placed(k.C, k.H), l);
    };
    return s;
}

} // namespace linequad::peers
