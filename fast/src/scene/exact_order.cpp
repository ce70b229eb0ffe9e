// A scene's roots from their shapes' exact forms, compared exactly (exact_form::compare_roots).
#include "scene/exact_order.hpp"

#include "shapes/all.hpp"

namespace linequad::detail {

using exact_form::SurdRoot;

namespace {

ExactRoots from(const exact_form::Classification<BigFloat>& c) {
    ExactRoots r;
    r.outcome = c.outcome, r.count = c.count;
    for (int k = 0; k < c.count; ++k)
        r.roots[k] = c.roots[k], r.D[k] = c.D;
    r.s0 = c.s0;
    r.s0_D = c.s0.S != 0 ? c.D : BigFloat(0.0);
    return r;
}

template <class S>
ExactRoots quadric_roots(const S& shape, int orientation, const Line& l) {
    auto q = ShapeTraits<S>::template exact_quadratic<BigFloat>(shape, l, orientation);
    return from(exact_form::classify(q, exact_form::parameter_range<BigFloat>(l.range), Need::all));
}

} // namespace

template <class S>
ExactRoots exact_roots(const Prepared<S>& p, const Line& l) {
    AsPrepared<S> src(p);
    if constexpr (is_composite<S>) {
        // Each patch's roots, named by its part, merged in exact order; a line along a patch's
        // surface is the answer (solve_shape's merge, exactly).
        ExactRoots all;
        int i = 0;
        bool along = false;
        std::apply(
            [&](const auto&... patch) {
                auto add = [&](const ExactRoots& r) {
                    Part part = ShapeTraits<S>::parts[i++];
                    if (along) return;
                    if (r.outcome == exact_form::Outcome::on_surface) {
                        all = r, along = true;
                        return;
                    }
                    for (int k = 0; k < r.count && all.count < max_hits; ++k) {
                        all.roots[all.count] = r.roots[k], all.D[all.count] = r.D[k];
                        all.roots[all.count++].part = part;
                    }
                };
                (add(quadric_roots(patch, 0, l)), ...);
            },
            ShapeTraits<S>::patches(src.shape));
        if (along) return all;
        for (int a = 1; a < all.count; ++a)
            for (int b = a;
                 b > 0 && compare_roots(all.roots[b], all.D[b], all.roots[b - 1], all.D[b - 1]) < 0;
                 --b)
                std::swap(all.roots[b], all.roots[b - 1]), std::swap(all.D[b], all.D[b - 1]);
        all.outcome = all.count > 0 ? exact_form::Outcome::hits : exact_form::Outcome::none;
        return all;
    } else {
        return quadric_roots(src.shape, src.validity().orientation, l);
    }
}

int compare_roots(const SurdRoot<BigFloat>& a, const BigFloat& Da, const SurdRoot<BigFloat>& b,
                  const BigFloat& Db) {
    return exact_form::compare_roots<BigFloat>({a.N, a.S, a.Den, Da}, {b.N, b.S, b.Den, Db});
}

#define LINEQUAD_EXACT_ROOTS(S) template ExactRoots exact_roots(const Prepared<S>&, const Line&);
LINEQUAD_FOR_EACH_SHAPE(LINEQUAD_EXACT_ROOTS)
#undef LINEQUAD_EXACT_ROOTS

} // namespace linequad::detail
