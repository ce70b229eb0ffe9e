// The sense of a point: a floating-point filter, then exact dyadic arithmetic (BigFloat) when the
// filter cannot prove the sign. The terms themselves are in sense_terms.hpp.
#include "linequad/cells.hpp"
#include "linequad/surfaces.hpp"

#include "numeric/big_float.hpp"
#include "numeric/fp_environment.hpp"
#include "sense/sense_terms.hpp"

#include <cmath>
#include <limits>

namespace linequad {

namespace {

// A double for the filter whose products refuse to underflow: a product of nonzero factors below
// 2^-960 is NaN (no decision). An intermediate product that underflowed could be multiplied back
// up (2^-1000 x 2^-100 x 2^1000 reads 0, not 2^-100), and no absolute bound would hold.
struct Guarded {
    double v;
    Guarded(double x) : v(x) {} // NOLINT: the terms' constants (2) convert
    friend Guarded operator*(Guarded a, Guarded b) {
        double p = a.v * b.v;
        bool lost = std::fabs(p) < 0x1p-960 && a.v != 0 && b.v != 0;
        return lost ? std::numeric_limits<double>::quiet_NaN() : p;
    }
    friend Guarded operator-(Guarded a) { return -a.v; }
};

// Sums the terms in double beside the sum of their magnitudes M. Each term is a product of at
// most four factors, one of them 2 (exact): at most two roundings, each in double's normal range
// (Guarded), a relative error of gamma_2; summing at most 12 of them adds gamma_11 of M (a sum
// that lands among the subnormals is exact). So |sum - exact| <= 13 u M (1 + O(u)) with
// u = 2^-53, below 2^-48 M even with M's own rounding. A product that overflows or underflows
// makes M infinite or NaN: no decision, and the exact path takes it.
struct Filter {
    double sum = 0, magnitude = 0;
    void operator()(Guarded x) { sum += x.v, magnitude += std::fabs(x.v); }
    // -1, 0 or 1 when proven; 2 when not.
    int sign() const {
        if (!std::isfinite(magnitude)) return 2;
        double bound = 0x1p-48 * magnitude;
        // A zero sum is not proven: its terms may cancel exactly or not at all.
        return sum > bound ? 1 : sum < -bound ? -1 : 2;
    }
};

// The exact sign of the sum `terms(add)` gives: the filter on the terms in Guarded doubles, then
// the same terms in BigFloat.
template <class Terms>
int sign_of(Terms&& terms) {
    Filter f;
    terms(Guarded(0), f);
    if (int s = f.sign(); s != 2) return s;
    return sign(detail::exact_sum<BigFloat>([&](auto&& add) { terms(BigFloat(), add); }));
}

template <class T>
Vec3T<T> as(Vec3 v) {
    return {T(v.x), T(v.y), T(v.z)};
}
template <class T>
detail::QuadricCoefficients<T> as(const std::array<double, 10>& q) {
    return {T(q[0]), T(q[1]), T(q[2]), T(q[3]), T(q[4]),
            T(q[5]), T(q[6]), T(q[7]), T(q[8]), T(q[9])};
}

Error check_finite(const double* x, int n, const char* field) {
    for (int i = 0; i < n; ++i) {
        if (std::isnan(x[i])) return {ErrorCode::not_a_number, field};
        if (std::isinf(x[i])) return {ErrorCode::infinite, field};
    }
    return {};
}
Error check_vector(Vec3 v, const char* field) {
    const double x[3] = {v.x, v.y, v.z};
    return check_finite(x, 3, field);
}
bool all_zero(const double* x, int n) {
    for (int i = 0; i < n; ++i)
        if (x[i] != 0) return false;
    return true;
}

SenseResult refused(Error e) {
    return {Sense::on, e};
}
SenseResult found(int s) {
    return {Sense(s), {}};
}

Error check(const Plane& s) {
    const double n[3] = {s.n.x, s.n.y, s.n.z};
    if (Error e = check_finite(n, 3, "n"); !e.ok()) return e;
    if (Error e = check_finite(&s.d, 1, "d"); !e.ok()) return e;
    if (all_zero(n, 3)) return {ErrorCode::zero_coefficients, "n"};
    return {};
}
Error check(const Quadric& s) {
    if (Error e = check_finite(s.q.data(), 10, "q"); !e.ok()) return e;
    if (all_zero(s.q.data(), 10)) return {ErrorCode::zero_coefficients, "q"};
    return {};
}

Error check_radius(double r) {
    if (Error e = check_finite(&r, 1, "r"); !e.ok()) return e;
    if (!(r > 0)) return {ErrorCode::bad_radius, "r"};
    return {};
}
Error check(const Sphere& s) {
    if (Error e = check_vector(s.C, "C"); !e.ok()) return e;
    return check_radius(s.r);
}
Error check(const Cylinder& s) {
    if (Error e = check_vector(s.C, "C"); !e.ok()) return e;
    if (Error e = check_vector(s.H, "H"); !e.ok()) return e;
    if (Error e = check_radius(s.r); !e.ok()) return e;
    if (s.H == s.C) return {ErrorCode::degenerate_axis, "H - C"};
    if (s.finite || s.caps)
        return {ErrorCode::bad_option, "finite (a cell's cylinder is infinite, uncapped)"};
    if (!detail::cylinder_across(s))
        return {ErrorCode::bad_option,
                "H - C (a cell's cylinder lies along a coordinate axis: write another as a "
                "quadric)"};
    return {};
}

// Each sum below is written once, over the number type of `zero` (Guarded, then BigFloat).
int value_sign(const Plane& s, Vec3 p) {
    return sign_of([&](auto zero, auto&& add) {
        using T = decltype(zero);
        detail::plane_value_terms(as<T>(s.n), T(s.d), as<T>(p), add);
    });
}
int value_sign(const Quadric& s, Vec3 p) {
    return sign_of([&](auto zero, auto&& add) {
        using T = decltype(zero);
        detail::quadric_value_terms(as<T>(s.q), as<T>(p), add);
    });
}

using detail::Centred;
int value_sign(const Centred& s, Vec3 p) {
    return sign_of([&](auto zero, auto&& add) {
        using T = decltype(zero);
        detail::centred_value_terms(s.across, as<T>(s.c), T(s.r), as<T>(p), add);
    });
}
int direction_sign(const Centred& s, Vec3 p, Vec3 u) {
    int slope = sign_of([&](auto zero, auto&& add) {
        using T = decltype(zero);
        detail::centred_slope_terms(s.across, as<T>(s.c), as<T>(p), as<T>(u), add);
    });
    if (slope != 0) return slope;
    return sign_of([&](auto zero, auto&& add) {
        using T = decltype(zero);
        detail::centred_curvature_terms(s.across, as<T>(u), add);
    });
}

template <class S>
Error check_inputs(const S& s, Vec3 p, const Vec3* u);

// A sphere's or a cylinder's sense (with the direction u where given).
template <class S>
SenseResult centred_sense(const S& shape, Vec3 p, const Vec3* u) {
    numeric::StandardEnvironment standard; // the filter's bound assumes it
    if (Error e = check_inputs(shape, p, u); !e.ok()) return refused(e);
    Centred s = detail::centred(shape);
    if (int at = value_sign(s, p); at != 0 || !u) return found(at);
    return found(direction_sign(s, p, *u));
}

template <class S>
Error check_inputs(const S& s, Vec3 p, const Vec3* u) {
    if (Error e = check(s); !e.ok()) return e;
    if (Error e = check_vector(p, "p"); !e.ok()) return e;
    if (!u) return {};
    if (Error e = check_vector(*u, "u"); !e.ok()) return e;
    if (*u == Vec3{0, 0, 0}) return {ErrorCode::zero_direction, "u"};
    return {};
}

} // namespace

Error check_sense(const Plane& s, Vec3 p, const Vec3* u) {
    return check_inputs(s, p, u);
}
Error check_sense(const Quadric& s, Vec3 p, const Vec3* u) {
    return check_inputs(s, p, u);
}

SenseResult sense(const Plane& s, Vec3 p) {
    numeric::StandardEnvironment standard; // the filter's bound assumes it
    if (Error e = check_sense(s, p); !e.ok()) return refused(e);
    return found(value_sign(s, p));
}

SenseResult sense(const Quadric& s, Vec3 p) {
    numeric::StandardEnvironment standard; // the filter's bound assumes it
    if (Error e = check_sense(s, p); !e.ok()) return refused(e);
    return found(value_sign(s, p));
}

SenseResult sense(const Plane& s, Vec3 p, Vec3 u) {
    numeric::StandardEnvironment standard; // the filter's bound assumes it
    if (Error e = check_sense(s, p, &u); !e.ok()) return refused(e);
    if (int at = value_sign(s, p); at != 0) return found(at);
    return found(sign_of([&](auto zero, auto&& add) {
        using T = decltype(zero);
        detail::plane_slope_terms(as<T>(s.n), as<T>(u), add);
    }));
}

SenseResult sense(const Quadric& s, Vec3 p, Vec3 u) {
    numeric::StandardEnvironment standard; // the filter's bound assumes it
    if (Error e = check_sense(s, p, &u); !e.ok()) return refused(e);
    if (int at = value_sign(s, p); at != 0) return found(at);
    int slope = sign_of([&](auto zero, auto&& add) {
        using T = decltype(zero);
        detail::quadric_slope_terms(as<T>(s.q), as<T>(p), as<T>(u), add);
    });
    if (slope != 0) return found(slope);
    return found(sign_of([&](auto zero, auto&& add) {
        using T = decltype(zero);
        detail::quadric_curvature_terms(as<T>(s.q), as<T>(u), add);
    }));
}

Error check_sense(const Sphere& s, Vec3 p, const Vec3* u) {
    return check_inputs(s, p, u);
}
Error check_sense(const Cylinder& s, Vec3 p, const Vec3* u) {
    return check_inputs(s, p, u);
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

const char* sense_name(Sense s) {
    switch (s) {
    case Sense::negative:
        return "negative";
    case Sense::on:
        return "on";
    case Sense::positive:
        return "positive";
    }
    return "?";
}

} // namespace linequad
