// The sense of a point, derived once for every number type: double (the filter), BigFloat (fast/'s
// exact path) and CGAL's Mpzf (the oracle in robust/).
//
// Along the line p + t u, f is the polynomial g(t) = f(p) + t (grad f(p) . u) + t^2 f2(u), where
// f2 is f's quadratic part (A u_x^2 + ... + F u_z u_x) and
//     grad f(p) = (2A x + D y + F z + G,  2B y + D x + E z + H,  2C z + E y + F x + J).
// (Expanding f(p + t u) term by term: A (x + t u_x)^2 = A x^2 + 2A x u_x t + A u_x^2 t^2, and
// D (x + t u_x)(y + t u_y) = D xy + D (x u_y + y u_x) t + D u_x u_y t^2, and so on.) The sign of
// g just after t = 0 is that of its first nonzero coefficient. For a plane g(t) = (n . p - d) +
// t (n . u). Each coefficient is written as a sum of products of at most three inputs (and a
// factor 2, exact), handed one at a time to `add`: a filter sums them and their magnitudes, an
// exact type just sums them.
#pragma once

#include "linequad/shapes.hpp"
#include "linequad/surfaces.hpp"

#include <optional>
#include <type_traits>

namespace linequad::detail {

template <class T>
using QuadricCoefficients = std::array<T, 10>;

// f(p): g's constant coefficient.
template <class T, class Add>
void quadric_value_terms(const QuadricCoefficients<T>& q, const Vec3T<T>& p, Add&& add) {
    add(q[0] * p.x * p.x), add(q[1] * p.y * p.y), add(q[2] * p.z * p.z);
    add(q[3] * p.x * p.y), add(q[4] * p.y * p.z), add(q[5] * p.z * p.x);
    add(q[6] * p.x), add(q[7] * p.y), add(q[8] * p.z), add(q[9]);
}

// 2 in T: a number type, or a bounded one (numeric/bounded.hpp) built from an exact double.
template <class T>
T two_in() {
    if constexpr (std::is_constructible_v<T, double>)
        return T(2.0);
    else
        return T::exact(2);
}

// grad f(p) . u: g's linear coefficient.
template <class T, class Add>
void quadric_slope_terms(const QuadricCoefficients<T>& q, const Vec3T<T>& p, const Vec3T<T>& u,
                         Add&& add) {
    const T two = two_in<T>();
    add(two * q[0] * p.x * u.x), add(q[3] * p.y * u.x), add(q[5] * p.z * u.x), add(q[6] * u.x);
    add(two * q[1] * p.y * u.y), add(q[3] * p.x * u.y), add(q[4] * p.z * u.y), add(q[7] * u.y);
    add(two * q[2] * p.z * u.z), add(q[4] * p.y * u.z), add(q[5] * p.x * u.z), add(q[8] * u.z);
}

// f2(u): g's quadratic coefficient.
template <class T, class Add>
void quadric_curvature_terms(const QuadricCoefficients<T>& q, const Vec3T<T>& u, Add&& add) {
    add(q[0] * u.x * u.x), add(q[1] * u.y * u.y), add(q[2] * u.z * u.z);
    add(q[3] * u.x * u.y), add(q[4] * u.y * u.z), add(q[5] * u.z * u.x);
}

// n . p - d and n . u.
template <class T, class Add>
void plane_value_terms(const Vec3T<T>& n, const T& d, const Vec3T<T>& p, Add&& add) {
    add(n.x * p.x), add(n.y * p.y), add(n.z * p.z), add(-d);
}
template <class T, class Add>
void plane_slope_terms(const Vec3T<T>& n, const Vec3T<T>& u, Add&& add) {
    add(n.x * u.x), add(n.y * u.y), add(n.z * u.z);
}

// A sphere, or a cylinder along coordinate axis k, as OpenMC defines them: f is the sum over the
// axes across it (`across`: all three for a sphere, the two but k for a cylinder) of
// (p_i - c_i)^2, less r^2; along the line, g(t) = f(p) + 2 t sum (p_i - c_i) u_i + t^2 sum u_i^2.
// Expanded into products of the inputs: (p_i - c_i)^2 = p_i p_i - 2 p_i c_i + c_i c_i.
struct Across {
    bool axis[3];
};
// A cylinder's axes across it, where it lies along a coordinate axis (C and H apart on that axis
// alone); none otherwise.
inline std::optional<Across> cylinder_across(const Cylinder& s) {
    Vec3 d = s.H - s.C;
    int along = (d.x != 0) + (d.y != 0) + (d.z != 0);
    if (along != 1) return std::nullopt;
    return Across{{d.x == 0, d.y == 0, d.z == 0}};
}
// A sphere's f or an axis-aligned cylinder's, for the terms below: the axes across it, its centre
// and radius (for a surface check_sense accepted).
struct Centred {
    Across across;
    Vec3 c;
    double r;
};
inline Centred centred(const Sphere& s) {
    return {{{true, true, true}}, s.C, s.r};
}
inline Centred centred(const Cylinder& s) {
    return {*cylinder_across(s), s.C, s.r};
}
template <class T, class Add>
void centred_value_terms(Across a, const Vec3T<T>& c, const T& r, const Vec3T<T>& p, Add&& add) {
    const T two = two_in<T>();
    for (int i = 0; i < 3; ++i)
        if (a.axis[i]) add(p[i] * p[i]), add(-(two * p[i] * c[i])), add(c[i] * c[i]);
    add(-(r * r));
}
template <class T, class Add>
void centred_slope_terms(Across a, const Vec3T<T>& c, const Vec3T<T>& p, const Vec3T<T>& u,
                         Add&& add) {
    const T two = two_in<T>();
    for (int i = 0; i < 3; ++i)
        if (a.axis[i]) add(two * p[i] * u[i]), add(-(two * c[i] * u[i]));
}
template <class T, class Add>
void centred_curvature_terms(Across a, const Vec3T<T>& u, Add&& add) {
    for (int i = 0; i < 3; ++i)
        if (a.axis[i]) add(u[i] * u[i]);
}

// The exact sum of the terms `terms(add)` gives, in an exact ring type T.
template <class T, class Terms>
T exact_sum(Terms&& terms) {
    T sum(0);
    terms([&](const T& x) { sum = sum + x; });
    return sum;
}

} // namespace linequad::detail
