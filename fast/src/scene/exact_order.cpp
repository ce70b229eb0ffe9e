// Two roots of different quadratics compared exactly. With sigma = sgn(Den_a Den_b),
//     sgn(t_a - t_b) = sigma sgn(A + B sqrt(Da) + C sqrt(Db)),
//     A = N_a Den_b - N_b Den_a,  B = S_a Den_b,  C = -S_b Den_a.
// With P = A + B sqrt(Da) (its sign by exact_form's sign_surd) and Q = C sqrt(Db), the sum has
// their common sign when they agree; otherwise the sign of the larger, from
//     P^2 - Q^2 = (A^2 + B^2 Da - C^2 Db) + 2 A B sqrt(Da).
#include "scene/exact_order.hpp"

#include "shapes/all.hpp"

namespace linequad::detail {

using exact_form::SurdRoot;

template <class S>
exact_form::Classification<BigFloat> exact_roots(const Prepared<S>& p, const Line& l) {
    AsPrepared<S> src(p);
    auto q = ShapeTraits<S>::template exact_quadratic<BigFloat>(src.shape, l,
                                                                src.validity().orientation);
    return exact_form::classify(q, exact_form::parameter_range<BigFloat>(l.range), Need::all);
}

int compare_roots(const SurdRoot<BigFloat>& a, const BigFloat& Da, const SurdRoot<BigFloat>& b,
                  const BigFloat& Db) {
    int sigma = sign(a.Den) * sign(b.Den);
    BigFloat A = a.N * b.Den - b.N * a.Den;
    BigFloat B = BigFloat(double(a.S)) * b.Den;
    BigFloat C = BigFloat(double(-b.S)) * a.Den;
    int sp = exact_form::sign_surd(A, B, Da);
    int sq = sign(Db) == 0 ? 0 : sign(C);
    if (sq == 0) return sigma * sp;
    if (sp == 0 || sp == sq) return sigma * sq;
    // P and Q of opposite signs: the sum has P's sign when |P| > |Q|.
    BigFloat X = A * A + B * B * Da - C * C * Db;
    BigFloat Y = BigFloat(2.0) * A * B;
    int larger = exact_form::sign_surd(X, Y, Da); // sgn(P^2 - Q^2)
    return sigma * (larger >= 0 ? (larger == 0 ? 0 : sp) : sq);
}

#define LINEQUAD_EXACT_ROOTS(S)                                                                    \
    template exact_form::Classification<BigFloat> exact_roots(const Prepared<S>&, const Line&);
LINEQUAD_EXACT_ROOTS(Cylinder)
LINEQUAD_EXACT_ROOTS(EllipticCylinder)
LINEQUAD_EXACT_ROOTS(EllipticCone)
LINEQUAD_EXACT_ROOTS(Frustum)
#undef LINEQUAD_EXACT_ROOTS

} // namespace linequad::detail
