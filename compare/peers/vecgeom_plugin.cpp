// VecGeom (Geant4's navigation solids) as a plugin: DistanceToIn and DistanceToOut on the solids
// that hold a linequad shape along the coordinate axes, run out of process like any plugin (some
// degenerate solids crash VecGeom; the audit goes on).
//
// VecGeom's own contract, declared (linequad/audit_plugin.h, ABI 3): its surfaces are kTolerance
// thick (a point within kHalfTolerance of a surface is on it), a line that only touches a solid
// does not enter it (the Tube's, EllipticalTube's and Ellipsoid's rule; the Orb's counts a touch,
// which the tolerance covers), DistanceToIn from inside is undefined (-1 or minus the safety), a
// start on the surface moving out has no entry, a line lying on a surface enters where the contact
// starts, and a negative distance within kHalfTolerance means 0.
//
// Built with -msse4.2 and without AVX (VecGeom's virtual functions take Vc vectors of that
// width) and -DVECCORE_ENABLE_VC (its Config.h enables Vc).
#include "linequad/audit_plugin.h"

#include <VecGeom/management/GeoManager.h>
#include <VecGeom/volumes/UnplacedCone.h>
#include <VecGeom/volumes/UnplacedEllipsoid.h>
#include <VecGeom/volumes/UnplacedEllipticalCone.h>
#include <VecGeom/volumes/UnplacedEllipticalTube.h>
#include <VecGeom/volumes/UnplacedOrb.h>
#include <VecGeom/volumes/UnplacedTube.h>

#include <cmath>
#include <cstdio>
#include <memory>

namespace {

using vecgeom::GeoManager;
using vecgeom::kTwoPi;
using vecgeom::Precision;
using vecgeom::VUnplacedVolume;
using Vector = vecgeom::Vector3D<Precision>;

// The coordinate a vector lies along (exactly one coordinate nonzero), or -1.
int axis_of(const double* w) {
    int n = (w[0] != 0) + (w[1] != 0) + (w[2] != 0);
    if (n != 1) return -1;
    return w[0] != 0 ? 0 : w[1] != 0 ? 1 : 2;
}

// A VecGeom solid and where it stands: local coordinate j is world coordinate axis[j], times
// sign[j], from the world point centre.
struct Placed {
    std::unique_ptr<VUnplacedVolume> solid;
    int axis[3] = {0, 1, 2};
    double sign[3] = {1, 1, 1};
    double centre[3] = {0, 0, 0};
    const char* why = nullptr; // why the shape cannot be held, when solid is null
};

Placed refused(const char* why) {
    Placed p;
    p.why = why;
    return p;
}

// Local axes x, y, z along world ka, kb, kc (a permutation), from the world point C; refused
// unless they are three distinct coordinate axes.
Placed on_axes(int ka, int kb, int kc, const double* C) {
    if (ka < 0 || kb < 0 || kc < 0 || ka == kb || kb == kc || ka == kc)
        return refused("its axes are not along distinct coordinate axes");
    Placed p;
    p.axis[0] = ka, p.axis[1] = kb, p.axis[2] = kc;
    for (int i = 0; i < 3; ++i)
        p.centre[i] = C[i];
    return p;
}

// Local axes: z along world k with the given sign, x and y along the next two (a rotation).
void along(Placed& p, int k, double z_sign) {
    p.axis[0] = (k + 1) % 3, p.axis[1] = (k + 2) % 3, p.axis[2] = k;
    p.sign[2] = z_sign;
}

Placed place(const lq_shape& s) {
    const double* q = s.p;
    switch (s.kind) {
    case LQ_CYLINDER:
    case LQ_FRUSTUM: {
        // Cylinder: C, H, r. Frustum: C0, r0, C1, r1.
        bool cylinder = s.kind == LQ_CYLINDER;
        const double* P0 = q;
        const double* P1 = cylinder ? q + 3 : q + 4;
        double r0 = cylinder ? q[6] : q[3], r1 = cylinder ? q[6] : q[7];
        double d[3] = {P1[0] - P0[0], P1[1] - P0[1], P1[2] - P0[2]};
        int k = axis_of(d);
        if (k < 0) return refused("its axis is not along a coordinate axis");
        Placed p;
        along(p, k, d[k] > 0 ? 1 : -1);
        for (int i = 0; i < 3; ++i)
            p.centre[i] = P0[i];
        p.centre[k] = 0.5 * (P0[k] + P1[k]);
        double dz = 0.5 * std::fabs(d[k]);
        if (cylinder)
            p.solid.reset(GeoManager::MakeInstance<vecgeom::UnplacedTube>(0., r0, dz, 0., kTwoPi));
        else // rmax1 at -dz (the end P0), rmax2 at +dz
            p.solid.reset(
                GeoManager::MakeInstance<vecgeom::UnplacedCone>(0., r0, 0., r1, dz, 0., kTwoPi));
        return p;
    }
    case LQ_ELLIPTIC_CYLINDER: {
        // C + x a + y b + z c, z in [0, 1].
        const double *C = q, *a = q + 3, *b = q + 6, *c = q + 9;
        int ka = axis_of(a), kb = axis_of(b), kc = axis_of(c);
        Placed p = on_axes(ka, kb, kc, C);
        if (p.why) return p;
        p.centre[kc] = C[kc] + 0.5 * c[kc];
        p.solid.reset(new vecgeom::UnplacedEllipticalTube(std::fabs(a[ka]), std::fabs(b[kb]),
                                                          0.5 * std::fabs(c[kc])));
        return p;
    }
    case LQ_ELLIPTIC_CONE: {
        // Apex H, base centre C, base semi-axes a, b. VecGeom's: (x/A)^2 + (y/B)^2 = (h - z)^2
        // for |z| <= zcut, apex at z = h; here h = zcut = L/2 about the middle, so that the base
        // z = -L/2 has semi-axes A L and B L.
        if (s.nappes != 1) return refused("VecGeom's EllipticalCone has one nappe");
        const double *C = q, *H = q + 3, *a = q + 6, *b = q + 9;
        double d[3] = {H[0] - C[0], H[1] - C[1], H[2] - C[2]};
        int ka = axis_of(a), kb = axis_of(b), kc = axis_of(d);
        Placed p = on_axes(ka, kb, kc, C);
        if (p.why) return p;
        p.sign[2] = d[kc] > 0 ? 1 : -1;
        p.centre[kc] = 0.5 * (C[kc] + H[kc]);
        double L = std::fabs(d[kc]);
        p.solid.reset(new vecgeom::UnplacedEllipticalCone(std::fabs(a[ka]) / L,
                                                          std::fabs(b[kb]) / L, 0.5 * L, 0.5 * L));
        return p;
    }
    case LQ_SPHERE: {
        Placed p;
        for (int i = 0; i < 3; ++i)
            p.centre[i] = q[i];
        p.solid.reset(new vecgeom::UnplacedOrb(q[3]));
        return p;
    }
    case LQ_ELLIPSOID: {
        const double *C = q, *a = q + 3, *b = q + 6, *c = q + 9;
        int ka = axis_of(a), kb = axis_of(b), kc = axis_of(c);
        Placed p = on_axes(ka, kb, kc, C);
        if (p.why) return p;
        p.solid.reset(
            new vecgeom::UnplacedEllipsoid(std::fabs(a[ka]), std::fabs(b[kb]), std::fabs(c[kc])));
        return p;
    }
    }
    return refused("VecGeom has no such solid");
}

void unrepresented(lq_answer* out, const char* why) {
    out->status = LQ_UNREPRESENTED;
    std::snprintf(out->error, sizeof out->error, "%s", why);
}

// self: 0 for DistanceToIn, 1 for DistanceToOut.
int solve(void* self, const lq_shape* shape, const lq_line* line, lq_answer* out) {
    bool to_out = self != nullptr;
    out->status = LQ_HITS, out->count = 0;
    // VecGeom measures along a unit direction from a start point: a ray or a segment from t0 = 0.
    if (line->t0 != 0) return unrepresented(out, "not a ray or segment from its start"), 0;
    Placed p = place(*shape);
    if (!p.solid) return unrepresented(out, p.why), 0;
    Vector from, u;
    for (int j = 0; j < 3; ++j) {
        int k = p.axis[j];
        from[j] = p.sign[j] * (line->L0[k] - p.centre[k]);
        u[j] = p.sign[j] * line->v[k];
    }
    double d = to_out ? p.solid->DistanceToOut(from, u, vecgeom::kInfLength)
                      : p.solid->DistanceToIn(from, u, vecgeom::kInfLength);
    // kInfLength: no surface ahead; beyond a segment's end: none within it.
    if (!(d < vecgeom::kInfLength) || d > line->t1) return 0;
    out->count = 1;
    out->hits[0].t = d;
    return 0;
}

const char* const mapping =
    "Tube and Cone (rmin 0, full phi), EllipticalTube, EllipticalCone, Orb and Ellipsoid, "
    "placed by a translation (rounded: in the declared tolerance) and a permutation of the axes; "
    "a solid not along the coordinate axes, a cone of two nappes, a capsule or a whole line (not a "
    "ray or segment) is unrepresented";

lq_solver make(const char* name, int answers, void* self) {
    lq_solver s{};
    s.name = name;
    s.precision = 64;
    s.answers = answers;
    s.parametrisation = LQ_UNIT_DIRECTION;
    s.surface = LQ_CLOSED;
    s.carries = 0; // a distance only
    s.shapes = 1u << LQ_CYLINDER | 1u << LQ_ELLIPTIC_CYLINDER | 1u << LQ_ELLIPTIC_CONE |
               1u << LQ_FRUSTUM | 1u << LQ_SPHERE | 1u << LQ_ELLIPSOID;
    s.mapping = mapping;
    s.solve = solve;
    s.self = self;
    s.inside = answers == LQ_FIRST_ENTRY ? LQ_INSIDE_UNDEFINED : LQ_INSIDE_AS_ANSWERS;
    // A line lying on a surface (a cap's plane, a cone's generator) enters where the contact
    // starts: VecGeom answers that distance.
    s.contact = LQ_CONTACT_FIRST_POINT;
    s.start_on_surface =
        answers == LQ_FIRST_ENTRY ? LQ_ON_SURFACE_BY_DIRECTION : LQ_ON_SURFACE_AS_INSIDE;
    s.tangent = LQ_TANGENT_NO_HIT;
    // kHalfTolerance: how far from the surface a point still counts as on it; 2^-50 of the
    // scene: the placement's rounding (a few ulps of the largest coordinate).
    s.tolerance_absolute = vecgeom::kHalfTolerance;
    s.tolerance_relative = 0x1p-50;
    s.negative_zero = vecgeom::kHalfTolerance;
    return s;
}

int to_out_marker; // a non-null self for DistanceToOut

} // namespace

extern "C" int linequad_audit_plugin(int abi, const lq_solver** solvers) {
    if (abi != LQ_ABI) return -1;
    static const lq_solver all[] = {make("vecgeom", LQ_FIRST_ENTRY, nullptr),
                                    make("vecgeom_out", LQ_FIRST_EXIT, &to_out_marker)};
    *solvers = all;
    return 2;
}
