// Arithmetic in double that notes whether anything rounded: where nothing did, the value computed
// is the exact one, and so is its sign. The cheap exact form of what a frame and a line of small
// dyadic numbers make (a line along an axis, in a disc's plane, through a rim), whose products
// and sums are all doubles exactly; any other input is left to the filters, the expansions and
// BigFloat.
#pragma once

#include "numeric/bounded_dd.hpp"
#include "numeric/eft.hpp"

#include <cmath>
#include <optional>

namespace linequad {

// A double and whether it is exactly the value it stands for: a number type for the exact form's
// templates (forms/exact_form.hpp). Where `exact` is false its value means nothing.
struct ExactDouble {
    double v = 0;
    bool exact = true;

    ExactDouble() = default;
    explicit ExactDouble(double x) : v(x), exact(std::isfinite(x)) {}
    ExactDouble(double x, bool e) : v(x), exact(e) {}

    // x + y, exact where two_sum's error is zero and the sum finite (a sum never underflows).
    friend ExactDouble operator+(ExactDouble x, ExactDouble y) {
        TwoTerm t = two_sum(x.v, y.v);
        return {t.hi, x.exact && y.exact && t.lo == 0 && std::isfinite(t.hi)};
    }
    friend ExactDouble operator-(ExactDouble x, ExactDouble y) {
        return x + ExactDouble(-y.v, y.exact);
    }
    friend ExactDouble operator-(ExactDouble x) { return {-x.v, x.exact}; }
    // x y, exact where fma's error is zero and the product is zero only for a zero factor and
    // otherwise normal (2^-960 to 2^1000: a product near the subnormals may round with an error
    // fma cannot show).
    friend ExactDouble operator*(ExactDouble x, ExactDouble y) {
        TwoTerm p = two_prod(x.v, y.v);
        double a = std::fabs(p.hi);
        bool normal = a == 0 ? x.v == 0 || y.v == 0 : a >= 0x1p-960 && a <= 0x1p+1000;
        return {p.hi, x.exact && y.exact && p.lo == 0 && normal};
    }
    // The sign where exact, else undecided (bounded_dd.hpp's undecided_sign).
    friend int sign(ExactDouble x) {
        return !x.exact ? undecided_sign : x.v > 0 ? 1 : x.v < 0 ? -1 : 0;
    }
};

// The sign of a . (b x c), c = P - Q - R; none where an operation rounds.
inline std::optional<int> det3_sign_in_double(Vec3 a, Vec3 b, Vec3 P, Vec3 Q, Vec3 R) {
    using E = ExactDouble;
    E c[3], d(0.0);
    for (int k = 0; k < 3; ++k)
        c[k] = E(P[k]) - E(Q[k]) - E(R[k]);
    for (int k = 0; k < 3; ++k) {
        int i = (k + 1) % 3, j = (k + 2) % 3;
        d = d + E(a[k]) * (E(b[i]) * c[j] - E(b[j]) * c[i]);
    }
    if (!d.exact) return std::nullopt;
    return sign(d);
}

// The sign of (a - a') . (b - b'); none where an operation rounds.
inline std::optional<int> dot_sign_in_double(Vec3 a, Vec3 a_, Vec3 b, Vec3 b_) {
    using E = ExactDouble;
    E d(0.0);
    for (int k = 0; k < 3; ++k)
        d = d + (E(a[k]) - E(a_[k])) * (E(b[k]) - E(b_[k]));
    if (!d.exact) return std::nullopt;
    return sign(d);
}

} // namespace linequad
