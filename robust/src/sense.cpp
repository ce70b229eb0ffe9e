// The oracle's sense of a point: the terms of fast/src/sense/sense_terms.hpp summed in CGAL::Mpzf,
// no filter. Inputs are checked by fast/'s check_sense (the same refusals, named the same).
#include "linequad/exact.hpp"

#include "numeric/fp_environment.hpp"
#include "sense/sense_terms.hpp"

#include <CGAL/Mpzf.h>

namespace linequad::exact {

namespace {

using Exact = CGAL::Mpzf;

Vec3T<Exact> exact(Vec3 v) {
    return {Exact(v.x), Exact(v.y), Exact(v.z)};
}
detail::QuadricCoefficients<Exact> exact(const std::array<double, 10>& q) {
    detail::QuadricCoefficients<Exact> out;
    for (std::size_t i = 0; i < 10; ++i)
        out[i] = Exact(q[i]);
    return out;
}

template <class Terms>
Sense sense_of(Terms&& terms) {
    Exact sum = detail::exact_sum<Exact>(terms);
    return sum > 0 ? Sense::positive : sum < 0 ? Sense::negative : Sense::on;
}

Sense value(const Plane& s, Vec3 p) {
    return sense_of(
        [&](auto&& add) { detail::plane_value_terms(exact(s.n), Exact(s.d), exact(p), add); });
}
Sense value(const Quadric& s, Vec3 p) {
    return sense_of([&](auto&& add) { detail::quadric_value_terms(exact(s.q), exact(p), add); });
}

SenseResult refused(Error e) {
    return {Sense::on, e};
}

// A sphere's or an axis-aligned cylinder's sense (sense_terms.hpp's centred terms).
template <class S>
SenseResult centred_sense(const S& shape, Vec3 p, const Vec3* u) {
    numeric::StandardEnvironmentT<true> standard;
    if (Error e = check_sense(shape, p, u); !e.ok()) return refused(e);
    detail::Centred s = detail::centred(shape);
    Sense at = sense_of([&](auto&& add) {
        detail::centred_value_terms(s.across, exact(s.c), Exact(s.r), exact(p), add);
    });
    if (at != Sense::on || !u) return {at, {}};
    Sense slope = sense_of([&](auto&& add) {
        detail::centred_slope_terms(s.across, exact(s.c), exact(p), exact(*u), add);
    });
    if (slope != Sense::on) return {slope, {}};
    return {
        sense_of([&](auto&& add) { detail::centred_curvature_terms(s.across, exact(*u), add); }),
        {}};
}

} // namespace

SenseResult sense(const Plane& s, Vec3 p) {
    numeric::StandardEnvironmentT<true> standard;
    if (Error e = check_sense(s, p); !e.ok()) return refused(e);
    return {value(s, p), {}};
}

SenseResult sense(const Quadric& s, Vec3 p) {
    numeric::StandardEnvironmentT<true> standard;
    if (Error e = check_sense(s, p); !e.ok()) return refused(e);
    return {value(s, p), {}};
}

SenseResult sense(const Plane& s, Vec3 p, Vec3 u) {
    numeric::StandardEnvironmentT<true> standard;
    if (Error e = check_sense(s, p, &u); !e.ok()) return refused(e);
    if (Sense at = value(s, p); at != Sense::on) return {at, {}};
    return {sense_of([&](auto&& add) { detail::plane_slope_terms(exact(s.n), exact(u), add); }),
            {}};
}

SenseResult sense(const Quadric& s, Vec3 p, Vec3 u) {
    numeric::StandardEnvironmentT<true> standard;
    if (Error e = check_sense(s, p, &u); !e.ok()) return refused(e);
    if (Sense at = value(s, p); at != Sense::on) return {at, {}};
    Sense slope = sense_of(
        [&](auto&& add) { detail::quadric_slope_terms(exact(s.q), exact(p), exact(u), add); });
    if (slope != Sense::on) return {slope, {}};
    return {
        sense_of([&](auto&& add) { detail::quadric_curvature_terms(exact(s.q), exact(u), add); }),
        {}};
}

SenseResult sense(const Sphere& s, Vec3 p) {
    return centred_sense(s, p, nullptr);
}
SenseResult sense(const Cylinder& s, Vec3 p) {
    return centred_sense(s, p, nullptr);
}
SenseResult sense(const Sphere& s, Vec3 p, Vec3 u) {
    return centred_sense(s, p, &u);
}
SenseResult sense(const Cylinder& s, Vec3 p, Vec3 u) {
    return centred_sense(s, p, &u);
}

} // namespace linequad::exact
