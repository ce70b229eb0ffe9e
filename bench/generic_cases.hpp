// Generic benchmark cases: random well-shaped shapes, lines aimed through their middle (so
// most cross twice), reproducible from a seed.
#pragma once

#include "linequad/batch.hpp"
#include "linequad/shapes.hpp"

#include <random>
#include <stdexcept>
#include <string>
#include <vector>

namespace linequad::bench {

struct GenericCase {
    Shape shape;
    Line line;
};

// A well-shaped instance of each shape from one random frame C, a, b, c (|det| at least a
// quarter of the product of the lengths); lines aim near C + c / 2, the middle of every one of
// them. A shape without a specialisation here does not compile into the benchmarks.
template <class S>
struct Generic;
template <>
struct Generic<Cylinder> {
    template <class Real>
    static Cylinder make(Vec3 C, Vec3, Vec3, Vec3 c, Real& real) {
        return {C, C + c, real(0.5, 2)};
    }
};
template <>
struct Generic<EllipticCylinder> {
    template <class Real>
    static EllipticCylinder make(Vec3 C, Vec3 a, Vec3 b, Vec3 c, Real&) {
        return {C, a, b, c};
    }
};
template <>
struct Generic<EllipticCone> {
    template <class Real>
    static EllipticCone make(Vec3 C, Vec3 a, Vec3 b, Vec3 c, Real&) {
        return {C, C + c, a, b};
    }
};

template <>
struct Generic<Frustum> {
    template <class Real>
    static Frustum make(Vec3 C, Vec3, Vec3, Vec3 c, Real& real) {
        return {C, real(0.5, 2), C + c, real(0.25, 2)};
    }
};

template <>
struct Generic<Sphere> {
    template <class Real>
    static Sphere make(Vec3 C, Vec3, Vec3, Vec3 c, Real& real) {
        return {C + 0.5 * c, real(0.5, 2)};
    }
};

template <>
struct Generic<Ellipsoid> {
    template <class Real>
    static Ellipsoid make(Vec3 C, Vec3 a, Vec3 b, Vec3 c, Real&) {
        return {C + 0.5 * c, a, b, c};
    }
};

template <>
struct Generic<Capsule> {
    template <class Real>
    static Capsule make(Vec3 C, Vec3, Vec3, Vec3 c, Real& real) {
        return {C, C + c, real(0.5, 2)};
    }
};

// A plane through the middle, its normal a.
template <>
struct Generic<Plane> {
    template <class Real>
    static Plane make(Vec3 C, Vec3 a, Vec3, Vec3 c, Real&) {
        return {a, dot(a, C + 0.5 * c)};
    }
};

// An ellipsoid in GQ form around the middle m: f(x) = (x - m)^T Q (x - m) - r^2, Q diagonally
// dominant (so positive definite), expanded into the ten coefficients (each rounded once).
template <>
struct Generic<Quadric> {
    template <class Real>
    static Quadric make(Vec3 C, Vec3, Vec3, Vec3 c, Real& real) {
        Vec3 m = C + 0.5 * c;
        double A = real(1, 2), B = real(1, 2), Cq = real(1, 2);
        double D = real(-0.5, 0.5), E = real(-0.5, 0.5), F = real(-0.5, 0.5), r = real(0.5, 2);
        double G = -(2 * A * m.x + D * m.y + F * m.z), H = -(2 * B * m.y + D * m.x + E * m.z),
               J = -(2 * Cq * m.z + E * m.y + F * m.x);
        double K = A * m.x * m.x + B * m.y * m.y + Cq * m.z * m.z + D * m.x * m.y + E * m.y * m.z +
                   F * m.z * m.x - r * r;
        return {{A, B, Cq, D, E, F, G, H, J, K}};
    }
};

// The generic instance of the shape with index `index` in Shape.
template <std::size_t I = 0, class Real>
Shape generic_shape(int index, Vec3 C, Vec3 a, Vec3 b, Vec3 c, Real& real) {
    if constexpr (I < std::variant_size_v<Shape>) {
        if (index == int(I))
            return Generic<std::variant_alternative_t<I, Shape>>::make(C, a, b, c, real);
        return generic_shape<I + 1>(index, C, a, b, c, real);
    } else {
        throw std::invalid_argument("no shape has index " + std::to_string(index));
    }
}

// binary32: the same cases with every input rounded to float.
inline std::vector<GenericCase> generic_cases(int shape_index, int n, unsigned seed = 1,
                                              Precision p = Precision::binary64) {
    std::mt19937_64 rng(seed);
    auto real = [&](double lo, double hi) {
        return std::uniform_real_distribution<double>(lo, hi)(rng);
    };
    auto vec = [&](double s) { return Vec3{real(-s, s), real(-s, s), real(-s, s)}; };
    std::vector<GenericCase> out;
    while (int(out.size()) < n) {
        Vec3 C = vec(2), a = vec(2), b = vec(2), c = vec(2);
        if (std::fabs(dot(a, cross(b, c))) < 0.25 * norm(a) * norm(b) * norm(c)) continue;
        Shape s = generic_shape(shape_index, C, a, b, c, real);
        Vec3 middle = C + 0.5 * c, from = vec(4);
        Line l{from, middle + vec(0.3) - from, Range::line};
        if (p == Precision::binary32)
            out.push_back({rounded_to_binary32(s), rounded_to_binary32(l)});
        else
            out.push_back({s, l});
    }
    return out;
}

// One shape, n generic lines aimed at it, in R, as a batch takes them (stable in double, stable32
// in float: the shape and lines rounded to float).
template <class R>
struct OneShape {
    Shape shape;
    std::vector<R> soa[6];
    LineArraysT<R> lines() const {
        return {soa[0].data(), soa[1].data(), soa[2].data(), soa[3].data(),
                soa[4].data(), soa[5].data(), soa[0].size(), Range::line};
    }
};
template <class R>
OneShape<R> one_shape(int shape, int n = 1024) {
    constexpr bool in_float = std::is_same_v<R, float>;
    auto cases = generic_cases(shape, n);
    OneShape<R> o{in_float ? rounded_to_binary32(cases[0].shape) : cases[0].shape, {}};
    // Re-aim each line at this one shape: through a point near its middle (the generic cases'
    // own lines aim at their own shapes; their middle is where they aimed).
    Vec3 middle = cases[0].line.L0 + cases[0].line.v;
    for (std::size_t i = 0; i < cases.size(); ++i) {
        Vec3 from = cases[i].line.L0, target = middle + 0.1 * cases[i].line.v;
        Vec3 v = target - from;
        for (int a = 0; a < 3; ++a)
            o.soa[a].push_back(R(from[a])), o.soa[3 + a].push_back(R(v[a]));
    }
    return o;
}

} // namespace linequad::bench
