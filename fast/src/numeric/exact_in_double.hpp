// Arithmetic in double that notes whether anything rounded: where nothing did, the value computed
// is the exact one, and so is its sign. The cheap exact test for what a frame of small integers
// makes (a line along an axis, in a disc's plane, through a rim), whose products and sums are all
// doubles exactly; any other input is left to the expansions and BigFloat.
#pragma once

#include "numeric/eft.hpp"

#include <cmath>
#include <optional>

namespace linequad {

class ExactInDouble {
  public:
    // x + y, exact where two_sum's error is zero and the sum is finite (a sum never underflows).
    LINEQUAD_INLINE double sum(double x, double y) {
        TwoTerm t = two_sum(x, y);
        exact_ = exact_ && t.lo == 0 && std::isfinite(t.hi);
        return t.hi;
    }
    LINEQUAD_INLINE double difference(double x, double y) { return sum(x, -y); }
    // x y, exact where fma's error is zero and the product is zero only for a zero factor and
    // otherwise normal (2^-960 to 2^1000: a product near the subnormals may round with an error
    // fma cannot show).
    LINEQUAD_INLINE double product(double x, double y) {
        TwoTerm p = two_prod(x, y);
        double a = std::fabs(p.hi);
        exact_ =
            exact_ && p.lo == 0 && (a == 0 ? x == 0 || y == 0 : a >= 0x1p-960 && a <= 0x1p+1000);
        return p.hi;
    }
    bool exact() const { return exact_; }

  private:
    bool exact_ = true;
};

// The sign of a . (b x c), c = P - Q - R; none where an operation rounds.
inline std::optional<int> det3_sign_in_double(Vec3 a, Vec3 b, Vec3 P, Vec3 Q, Vec3 R) {
    ExactInDouble e;
    double c[3];
    for (int k = 0; k < 3; ++k)
        c[k] = e.difference(e.difference(P[k], Q[k]), R[k]);
    double d = 0;
    for (int k = 0; k < 3; ++k) {
        int i = (k + 1) % 3, j = (k + 2) % 3;
        double cross = e.difference(e.product(b[i], c[j]), e.product(b[j], c[i]));
        d = e.sum(d, e.product(a[k], cross));
    }
    if (!e.exact()) return std::nullopt;
    return d > 0 ? 1 : d < 0 ? -1 : 0;
}

// The sign of (a - a') . (b - b'); none where an operation rounds.
inline std::optional<int> dot_sign_in_double(Vec3 a, Vec3 a_, Vec3 b, Vec3 b_) {
    ExactInDouble e;
    double d = 0;
    for (int k = 0; k < 3; ++k)
        d = e.sum(d, e.product(e.difference(a[k], a_[k]), e.difference(b[k], b_[k])));
    if (!e.exact()) return std::nullopt;
    return d > 0 ? 1 : d < 0 ? -1 : 0;
}

} // namespace linequad
