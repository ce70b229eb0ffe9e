// A scene's roots from their shapes' exact forms, compared exactly (exact_form::compare_roots).
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
    return exact_form::compare_roots<BigFloat>({a.N, a.S, a.Den, Da}, {b.N, b.S, b.Den, Db});
}

#define LINEQUAD_EXACT_ROOTS(S)                                                                    \
    template exact_form::Classification<BigFloat> exact_roots(const Prepared<S>&, const Line&);
LINEQUAD_FOR_EACH_SHAPE(LINEQUAD_EXACT_ROOTS)
#undef LINEQUAD_EXACT_ROOTS

} // namespace linequad::detail
