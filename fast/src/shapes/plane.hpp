// Line against a plane {n, d, coincident}: every derivation of it, once.
//
// Derivation (checked against the surface equation). P is on the plane iff f(P) = n . P - d = 0;
// with P = L0 + t v, g(t) = (n . v) t + (n . L0 - d): the quadric (quadric.hpp) whose quadratic
// part is zero, G, H, J = n and K = -d (each exact). So in the half-b form times 2,
//     A = 0,   B = n . v,   C0 = 2 (n . L0 - d),
// one root where n . v != 0; a line in the plane (n . v = 0 and f(L0) = 0) on_surface; parallel
// off it, no hit. Every layer but the seed takes the quadric's derivation of those coefficients.
//
// seed: OpenMC's SurfacePlane::distance, -f(L0) / (n . v) with f as written there.
#pragma once

#include "shapes/quadric.hpp"

namespace linequad::detail {

template <>
struct ShapeTraits<Plane> : AsQuadric<Plane, ShapeTraits<Plane>> {
    static constexpr const char* name = "plane";
    static constexpr auto fields = std::make_tuple(field("n", &Plane::n), field("d", &Plane::d));
    static constexpr const char* scale_fields = "n,d";
    static constexpr const char* fragile_fields = "v,n,d";

    // The plane as the quadric it is.
    static QuadricCoefficients<double> coefficients(const Plane& s) {
        return {0, 0, 0, 0, 0, 0, s.n.x, s.n.y, s.n.z, -s.d};
    }

    static Validity validate(const Plane& s) {
        if (s.n == Vec3{}) return {{ErrorCode::zero_coefficients, "n"}};
        return {};
    }

    // n . (x' / f) = d: n . x' = f d (n is a direction, d / |n| the distance from the origin).
    static std::optional<Plane> scaled_exactly(const Plane& s, double f) {
        double d = f * s.d;
        if (s.d != 0 &&
            !(std::fabs(d) >= std::numeric_limits<double>::min() && std::fabs(d) <= Binary64::max))
            return std::nullopt;
        return Plane{s.n, d, s.coincident};
    }

    // ---- seed: f(L0) and n . v as OpenMC writes them; a t^2 + b t + c with a = 0 ----

    template <class R, class Source>
    static SeedFormT<R> seed_form(const Source& src, const Line& l) {
        const Plane& s = src.shape;
        R A = R(s.n.x), B = R(s.n.y), C = R(s.n.z), D = R(s.d);
        R f = s.coincident ? R(0) : A * R(l.L0.x) + B * R(l.L0.y) + C * R(l.L0.z) - D;
        R projection = A * R(l.v.x) + B * R(l.v.y) + C * R(l.v.z);
        bool usable = std::isfinite(f) && std::isfinite(projection);
        return {R(0), projection, f, R(0), R(0), Extent{-Binary64::inf, Binary64::inf}, usable};
    }

    // A = 0: D = B^2, whose sign is that of n . v's magnitude (stable, certified, exact: the
    // quadric's).
    template <class NT>
    static int discriminant_sign(const Plane& s, const Line& l, int /*orientation*/) {
        using exact_form::lift;
        NT b = dot(lift<NT>(s.n), lift<NT>(l.v));
        return sign(b * b);
    }
};

} // namespace linequad::detail
