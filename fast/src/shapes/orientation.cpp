// The exact orientation of an affine frame: the sign of det[a b c], decided by a floating-point
// filter, then by Shewchuk expansions of the products, or by BigFloat when products of three
// would underflow.
#include "forms/frame.hpp"

#include "numeric/big_float.hpp"
#include "numeric/exact_in_double.hpp"
#include "numeric/expansion.hpp"

#include <cmath>
#include <initializer_list>

namespace linequad {

namespace {

// The sign of a . (b x c) when its floating-point value is certain, else 0. `permanent` is
// triple_product_magnitude(a, b, c): Shewchuk's bound on the rounding error of a . (b x c) is
// (7u + 56u^2) times it; 2^-49 (16u) covers that and, for the cone, the rounding of c = H - C
// (at most u (|H| + |C|) per component, accounted for by passing |H| + |C| for |c|). Products of
// two may underflow even when the determinant is large: b.y c.x = 2^-1452 becomes 0, and a.z =
// 2^954 then loses 2^-498 (nor does the permanent see it). Each underflow costs at most
// eta = 2^-1075 before the multiplication by a component of a, so (2 |a|_1 + 3) eta bounds
// what underflow can hide, in the value and in the permanent; (|a|_1 + 2) 2^-1072 covers it.
// Near overflow nothing is certain.
int filtered_sign(double det, double permanent, Vec3 a) {
    if (!(permanent < 0x1p+900)) return 0; // NaN too
    double norm1 = std::fabs(a.x) + std::fabs(a.y) + std::fabs(a.z);
    double bound = 0x1p-49 * permanent + (norm1 + 2) * 0x1p-1072;
    if (std::fabs(det) > bound) return det > 0 ? 1 : -1;
    return 0;
}

// Expansions of three-fold products are exact only while nothing underflows. Each vector is
// scaled by its own power of two, which cannot change the determinant's sign; that is enough
// when every nonzero component of a vector is within 2^300 of its largest, so that products of
// three keep their lowest bits above 2^-1074. Wider vectors (a frame spanning a thousand
// binades) go to BigFloat, which has no range limits.
Vec3 unit_scaled(Vec3 u, double m) {
    return m == 0 ? u : ldexp(u, -std::ilogb(m));
}

bool narrow(std::initializer_list<Vec3> vectors) {
    double big = 0, small = INFINITY;
    for (Vec3 u : vectors)
        for (double x : {u.x, u.y, u.z})
            if (x != 0) big = std::fmax(big, std::fabs(x)), small = std::fmin(small, std::fabs(x));
    return big == 0 || std::ilogb(big) - std::ilogb(small) <= 300;
}

void add_det_terms(Expansion<128>& e, double s, Vec3 a, Vec3 b, Vec3 c) {
    e.add_product(s * a.x, b.y, c.z), e.add_product(-s * a.x, b.z, c.y);
    e.add_product(s * a.y, b.z, c.x), e.add_product(-s * a.y, b.x, c.z);
    e.add_product(s * a.z, b.x, c.y), e.add_product(-s * a.z, b.y, c.x);
}

Vec3T<BigFloat> big(Vec3 u) {
    return {BigFloat(u.x), BigFloat(u.y), BigFloat(u.z)};
}

// Where the filter cannot decide: in double where nothing rounds (a frame of small integers);
// else, det being linear in its last column, det[a b P-Q-R] = det[a b P] - det[a b Q] -
// det[a b R], the three scaled by one power of two, then summed exactly.
int unfiltered_sign(Vec3 a, Vec3 b, Vec3 P, Vec3 Q, Vec3 R) {
    if (a == Vec3{} || b == Vec3{}) return 0;
    if (std::optional<int> s = det3_sign_in_double(a, b, P, Q, R)) return *s; // small integers

    if (!narrow({a}) || !narrow({b}) || !narrow({P, Q, R}))
        return sign(dot(big(a), cross(big(b), big(P) - big(Q) - big(R))));
    double m = std::fmax(max_abs(P), std::fmax(max_abs(Q), max_abs(R)));
    P = unit_scaled(P, m), Q = unit_scaled(Q, m), R = unit_scaled(R, m);
    a = unit_scaled(a, max_abs(a)), b = unit_scaled(b, max_abs(b));
    Expansion<128> e;
    add_det_terms(e, 1, a, b, P);
    add_det_terms(e, -1, a, b, Q);
    add_det_terms(e, -1, a, b, R);
    return e.sign();
}

} // namespace

// The cone's frame uses c = H - C, which is not a double. The filter takes c rounded (at most
// u (|H| + |C|) per component: passing that sum for |c| covers it within its 16u).
int cone_det_sign_exact(Vec3 a, Vec3 b, Vec3 C, Vec3 H) {
    Vec3 habs{std::fabs(H.x) + std::fabs(C.x), std::fabs(H.y) + std::fabs(C.y),
              std::fabs(H.z) + std::fabs(C.z)};
    if (int s = filtered_sign(dot(a, cross(b, H - C)), triple_product_magnitude(a, b, habs), a))
        return s;
    return unfiltered_sign(a, b, H, C, Vec3{});
}

// The same with two roundings of P - Q - R, each at most u (|P| + |Q| + |R|) per component.
int det3_sign_exact(Vec3 a, Vec3 b, Vec3 P, Vec3 Q, Vec3 R) {
    Vec3 cabs = magnitudes(P) + magnitudes(Q) + magnitudes(R);
    if (int s = filtered_sign(dot(a, cross(b, P - Q - R)), triple_product_magnitude(a, b, cabs), a))
        return s;
    return unfiltered_sign(a, b, P, Q, R);
}

int det3_sign_exact(Vec3 a, Vec3 b, Vec3 c) {
    if (int s = filtered_sign(dot(a, cross(b, c)), triple_product_magnitude(a, b, c), a)) return s;
    return unfiltered_sign(a, b, c, Vec3{}, Vec3{});
}

} // namespace linequad
