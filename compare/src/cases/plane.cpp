// The plane's cases: an integer normal n and a point P on the plane (d = n . P, exact), lines
// through P or beside it (cases/surfaces.hpp).
#include "cases/surfaces.hpp"

namespace linequad {
namespace surfaces {

namespace {

struct PlaneAt {
    Plane plane;
    Vec3 P;
};

PlaneAt plane_at(Rng& r) {
    Vec3 n = direction(r), P = r.ivec(6);
    return {Plane{n, dot(n, P)}, P};
}

// A direction in the plane: n x e for an e not along n.
Vec3 in_plane(Vec3 n, Rng& r) {
    Vec3 e[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    Vec3 d = cross(n, e[r.integer(0, 2)]);
    for (const Vec3& u : e)
        if (d == Vec3{}) d = cross(n, u);
    return d;
}

Case make(const Plane& s, Vec3 L0, Vec3 v) {
    Case c;
    c.shape = s;
    c.line = Line{L0, v};
    return c;
}

} // namespace

bool plane_applies(Family f) {
    switch (f) {
    case Family::generic:
    case Family::near_tangent:
    case Family::axis_parallel:
    case Family::scale:
    case Family::far_origin:
    case Family::inside_start:
        return true;
    default:
        return false;
    }
}

Case plane_case(Family f, Rng& r, int k, Precision precision) {
    PlaneAt p = plane_at(r);
    Vec3 n = p.plane.n;
    double off = std::ldexp(1.0, -k) * (r.coin() ? 1 : -1);
    double s = r.integer(-32, 32) * 0.125; // P at t = s: exact
    switch (f) {
    case Family::generic: {
        Vec3 d = direction(r);
        return make(p.plane, p.P - s * d, d);
    }
    case Family::near_tangent: {
        // Grazing: a direction in the plane tilted 2^-k out of it (k = 0: in it, through P).
        Vec3 d = in_plane(n, r);
        if (k > 0) d = d + off * n;
        return make(p.plane, p.P - s * d, d);
    }
    case Family::axis_parallel: {
        // Along the plane: in it (on the surface), or lifted 2^-k off it.
        Vec3 d = in_plane(n, r);
        Vec3 L0 = p.P - s * d;
        if (k > 0) L0 = L0 + off * n;
        return make(p.plane, L0, d);
    }
    case Family::scale: {
        // Half: the same plane written 2^e (n, d), every answer the unscaled one's. Half: the
        // scene 2^j times as large (d and the line times 2^j), the same t.
        // binary32: within float's range for every coefficient (the largest near 2^12).
        bool binary32 = precision == Precision::binary32;
        Vec3 d = direction(r);
        if (r.coin()) {
            int e = std::min(k, binary32 ? 96 : k) * (r.coin() ? 1 : -1);
            Plane scaled{std::ldexp(1.0, e) * n, std::ldexp(p.plane.d, e)};
            return make(scaled, p.P - s * d, d);
        }
        double size = std::ldexp(1.0, std::min(k, binary32 ? 96 : k) * (r.coin() ? 1 : -1));
        return make(Plane{n, size * p.plane.d}, size * (p.P - s * d), size * d);
    }
    case Family::far_origin: {
        Vec3 d = direction(r);
        Vec3 L0 = p.P - std::ldexp(1.0, k) * d;
        if (r.coin()) L0 = L0 + 0.125 * in_plane(n, r);
        return make(p.plane, L0, d);
    }
    case Family::inside_start: {
        // From P, with the caller's word that it is on the plane or without; or 2^-k off it.
        Vec3 d = r.coin() ? direction(r) : in_plane(n, r) + off * n;
        Case c = make(p.plane, p.P, d);
        if (k > 0 && r.coin())
            c.line.L0 = p.P + off * n;
        else
            std::get<Plane>(c.shape).coincident = r.coin();
        return c;
    }
    default:
        return {};
    }
}

} // namespace surfaces

template <>
bool CaseMaker<Plane>::applies(Family f) {
    return surfaces::plane_applies(f);
}

template <>
Case CaseMaker<Plane>::make(Family f, Rng& r, int k, Frames, Precision p) {
    return surfaces::plane_case(f, r, k, p);
}

} // namespace linequad
