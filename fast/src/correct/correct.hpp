// The correct solver: the exact answer, correctly rounded. The classification (how many hits,
// their kinds, the on-surface interval) is the exact one, and t, the hit points and the interval
// ends are each the double nearest the exact value (ties to even), as the oracle gives them.
//
// It follows Ziv's strategy for correctly rounded functions, on the division-free form of each
// shape's derivation (shapes/*.hpp, whose coefficients are polynomials in the inputs):
//  1. Newton (newton_rung.cpp): each root estimated in double, then one Newton step from the
//     estimate with the residual in double-double proves a root's existence, which root it is,
//     and an enclosure about 2^-100 wide; the extent, the range, t and the points are decided
//     on it. Every decision and every rounding must be proven; otherwise
//  2. double-double: the quadratic, its classification and the roots in BoundedDD, which
//     carries a proven error bound. Every sign must be certain and every output's interval must
//     lie inside one rounding cell; otherwise
//  3. exact: the same template in BigFloat (exact dyadic arithmetic, no GMP), every sign exact,
//     and each output rounded by deciding, exactly, on which side of the midpoints between
//     neighbouring doubles it lies.
// Result::rung says which rung answered. A closed shape (caps on) starts at the double-double
// rung: the Newton rung's proof covers the lateral roots only; so does a frustum, whose quadratic
// has no Newton form (shapes/frustum.hpp).
#pragma once

#include "correct/ladder.hpp"
#include "correct/newton_rung.hpp"
#include "correct/rungs.hpp"
#include "shapes/all.hpp"
#include "solve/solve.hpp"

namespace linequad::detail {

// Every answer of the ladder is certain, each t within half an ulp; and says which rung gave it.
inline void mark_certain(Result& r, Rung rung) {
    r.certainty = Certainty::certain;
    r.rung = rung;
    for (int i = 0; i < r.count; ++i) {
        r.hits[i].certain = true;
        r.hits[i].bound = Binary64::half_ulp(r.hits[i].t);
    }
}

// Sizes of scene and direction at which no quantity the Newton rung forms (products of at most
// twelve inputs) leaves double's normal range: 2^-64 to 2^64. Its bounds hold at any size; this
// only spares such scenes the scaling, which the rung's arithmetic would not need.
inline bool in_moderate_range(double x) {
    return x >= 0x1p-64 && x <= 0x1p+64;
}
inline bool moderate(double extent, const Line& l) {
    return in_moderate_range(extent) && in_moderate_range(max_abs(l.v));
}

struct Correct {
    template <class Src>
    static Result solve(const Src& src, const Line& l, Query q) {
        Validity valid = check(src, l);
        if (!valid.error.ok()) return Result::failure(valid.error);
        double extent = scene_extent(src, l);
        if (q.need == Need::any) q.points = false; // a hit test computes no point
        // The quick rung first, where the scene's products stay in double's normal range.
        using Traits = ShapeTraits<typename Src::Shape>;
        if constexpr (Traits::has_line_form) {
            if (q.need == Need::any && !closed(src.shape) && moderate(extent, l)) {
                Result r;
                LineForm form = Traits::quick_line_form(src, l, valid.orientation);
                if (hit_test_rung(form, Unit{1, 1, l}, r)) {
                    r.certainty = Certainty::certain;
                    r.rung = Rung::newton;
                    return r;
                }
            }
        }
        return ladder(src, valid.orientation, extent, l, q);
    }

    // The rungs in turn, each only where the one before cannot prove its answer.
    template <class Src>
    static Result ladder(const Src& src, int orientation, double extent, const Line& l, Query q) {
        using S = typename Src::Shape;
        using Traits = ShapeTraits<S>;
        Result r; // the one result, returned in place
        // The Newton rung on the scene as `unit` has it; r is left empty when the rung declines.
        auto newton = [&](const auto& scene, const Unit& unit) {
            if constexpr (Traits::has_line_form) {
                LineForm form = Traits::line_form(scene, unit.line, orientation);
                if (newton_rung(form, unit, l, q, r)) {
                    mark_certain(r, Rung::newton);
                    return true;
                }
                r = Result();
            }
            return false;
        };
        // The Newton rung's bounds hold at any scale (underflow is in them, overflow makes them
        // infinite), so a scene of moderate size is solved as given; others are scaled first,
        // so that tiny or huge scenes are not left to the slower rungs.
        bool as_given = moderate(extent, l);
        bool lateral_only = Traits::has_line_form && !closed(src.shape);
        if (lateral_only && as_given && newton(src, Unit{1, 1, l})) return r;
        if (std::optional<Unit> u = unit_scale(src, extent, l)) {
            S unit = scaled(src.shape, 1 / u->pos_factor);
            if (lateral_only && !as_given && newton(AsGiven<S>{unit}, *u)) return r;
            auto dd = Traits::template exact_quadratic<BoundedDD>(unit, u->line, orientation);
            if (double_double_rung(dd, *u, q, r)) {
                mark_certain(r, Rung::double_double);
                return r;
            }
        }
        r = exact_rung(Traits::template exact_quadratic<BigFloat>(src.shape, l, orientation), l, q);
        mark_certain(r, Rung::exact);
        return r;
    }
};

} // namespace linequad::detail
