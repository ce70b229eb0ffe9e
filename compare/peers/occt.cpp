// OpenCascade 7.6: IntAna_IntConicQuad, the analytic intersection of a gp_Lin with the quadric of a
// gp_Cylinder, gp_Cone, gp_Sphere or gp_Pln (what BRep and GeomAPI intersections of lines with such
// faces rest on).
#include "peers/peers.hpp"

// IntAna's headers use the gp types without including them.
#include <gp_Ax3.hxx>
#include <gp_Cone.hxx>
#include <gp_Cylinder.hxx>
#include <gp_Lin.hxx>
#include <gp_Pln.hxx>
#include <gp_Sphere.hxx>

#include <IntAna_IntConicQuad.hxx>
#include <IntAna_Quadric.hxx>
#include <Standard_Failure.hxx>

#include <cmath>

namespace linequad::peers {

namespace {

gp_Pnt pnt(Vec3 p) {
    return gp_Pnt(p.x, p.y, p.z);
}

// The intersection with the infinite quadric, on the posed line: gp_Lin holds a unit direction,
// and ParamOnConic is the distance along it.
std::optional<Result> intersect(const IntAna_Quadric& q, const Line& l) {
    if (!(dot(l.v, l.v) > 0)) return Result::failure(ErrorCode::zero_direction, "v");
    try {
        gp_Lin line(pnt(l.L0), gp_Dir(l.v.x, l.v.y, l.v.z));
        IntAna_IntConicQuad x(line, q);
        if (!x.IsDone()) return Result::failure(ErrorCode::foreign, "IntAna: not done");
        if (x.IsInQuadric()) {
            Result r;
            r.on_surface = true, r.s0 = l.range.t0, r.s1 = l.range.t1;
            return r;
        }
        if (x.IsParallel()) return Result{};
        double ts[max_hits];
        Vec3 ps[max_hits];
        int n = std::min(x.NbPoints(), max_hits);
        for (int i = 0; i < n; ++i) {
            ts[i] = x.ParamOnConic(i + 1);
            const gp_Pnt& p = x.Point(i + 1);
            ps[i] = {p.X(), p.Y(), p.Z()};
        }
        return hits_in_range(ts, ps, n, l.range);
    } catch (const Standard_Failure& e) {
        return Result::failure(ErrorCode::foreign,
                               interned(std::string("OCCT: ") + e.GetMessageString()));
    }
}

// A frame OCCT can hold: a, b orthogonal to each other and to c, of one length (to 1e-12 of it).
bool circular(Vec3 a, Vec3 b, Vec3 c) {
    double s = dot(a, a), tol = 1e-12;
    return std::fabs(dot(a, b)) <= tol * s && std::fabs(dot(a, c)) <= tol * norm(a) * norm(c) &&
           std::fabs(dot(b, c)) <= tol * norm(b) * norm(c) && std::fabs(dot(b, b) - s) <= tol * s;
}

} // namespace

audit::ExternalSolver occt() {
    audit::ExternalSolver s;
    s.name = "occt";
    s.answers = audit::Answers::all;
    s.parametrisation = audit::Parametrisation::unit_direction;
    s.surface = audit::Surface::infinite;
    s.kinds = false, s.parts = false;
    s.mapping = "IntAna_IntConicQuad(gp_Lin(L0, gp_Dir(u)), IntAna_Quadric(surface)); hits are "
                "its points whose distance ParamOnConic lies in the posed range. Cylinder: "
                "gp_Cylinder(gp_Ax3(C, H - C), r). Elliptic cylinder with a circular frame: "
                "gp_Cylinder(gp_Ax3(C, c, a), |a|). Elliptic cone with a circular frame: "
                "gp_Cone(gp_Ax3(H, c, a), atan(|a|/|c|), 0), both nappes: OCCT holds a cone by "
                "its half-angle, which rounds. Cannot represent: finite extents and caps (OCCT "
                "bounds faces elsewhere), oblique or elliptic frames (to 1e-12), frusta (one "
                "nappe). Sphere: gp_Sphere(gp_Ax3(C, z), r). Plane: gp_Pln(n, -d) (OCCT "
                "normalises n, which rounds). Quadric: only a sphere in GQ form (A = B = C > 0, "
                "D = E = F = 0), as gp_Sphere around (-G, -H, -J) / 2A of radius "
                "sqrt(|centre|^2 - K/A), rounded; IntAna_Quadric takes no general coefficients. "
                "coincident cannot be said. Tangent or crossing is not told apart.";
    s.on<Cylinder>() = [](const Cylinder& c, const Line& l) -> std::optional<Result> {
        Vec3 axis = c.H - c.C;
        if (!(c.r > 0) || !(dot(axis, axis) > 0)) return std::nullopt;
        gp_Cylinder cyl(gp_Ax3(pnt(c.C), gp_Dir(axis.x, axis.y, axis.z)), c.r);
        return intersect(IntAna_Quadric(cyl), l);
    };
    s.on<EllipticCylinder>() = [](const EllipticCylinder& e,
                                  const Line& l) -> std::optional<Result> {
        if (!circular(e.a, e.b, e.c) || !(dot(e.a, e.a) > 0) || !(dot(e.c, e.c) > 0))
            return std::nullopt;
        gp_Ax3 frame(pnt(e.C), gp_Dir(e.c.x, e.c.y, e.c.z), gp_Dir(e.a.x, e.a.y, e.a.z));
        return intersect(IntAna_Quadric(gp_Cylinder(frame, norm(e.a))), l);
    };
    s.on<EllipticCone>() = [](const EllipticCone& k, const Line& l) -> std::optional<Result> {
        Vec3 c = k.c();
        if (!circular(k.a, k.b, c) || !(dot(k.a, k.a) > 0) || !(dot(c, c) > 0)) return std::nullopt;
        gp_Ax3 frame(pnt(k.H), gp_Dir(c.x, c.y, c.z), gp_Dir(k.a.x, k.a.y, k.a.z));
        double angle = std::atan(norm(k.a) / norm(c));
        if (!(angle > 0 && angle < M_PI / 2)) return std::nullopt;
        return intersect(IntAna_Quadric(gp_Cone(frame, angle, 0.0)), l);
    };
    s.on<Sphere>() = [](const Sphere& k, const Line& l) -> std::optional<Result> {
        if (!(k.r > 0)) return std::nullopt;
        return intersect(IntAna_Quadric(gp_Sphere(gp_Ax3(pnt(k.C), gp_Dir(0, 0, 1)), k.r)), l);
    };
    s.on<Plane>() = [](const Plane& p, const Line& l) -> std::optional<Result> {
        if (p.coincident || !(dot(p.n, p.n) > 0)) return std::nullopt;
        return intersect(IntAna_Quadric(gp_Pln(p.n.x, p.n.y, p.n.z, -p.d)), l);
    };
    s.on<Quadric>() = [](const Quadric& k, const Line& l) -> std::optional<Result> {
        const auto& q = k.q;
        bool sphere = q[0] > 0 && q[0] == q[1] && q[1] == q[2] && q[3] == 0 && q[4] == 0 &&
                      q[5] == 0 && !k.coincident;
        if (!sphere) return std::nullopt;
        Vec3 centre = (-0.5 / q[0]) * Vec3{q[6], q[7], q[8]};
        double r2 = dot(centre, centre) - q[9] / q[0];
        if (!(r2 > 0) || !std::isfinite(r2)) return std::nullopt;
        gp_Sphere ball(gp_Ax3(pnt(centre), gp_Dir(0, 0, 1)), std::sqrt(r2));
        return intersect(IntAna_Quadric(ball), l);
    };
    return s;
}

} // namespace linequad::peers
