// What the shapes on a frame M = [a b c] around C share (the elliptic cylinder, the ellipsoid:
// the unit cylinder and the unit sphere mapped by the same M): what prepare() keeps, the rows of
// adj(M), the frame's exact orientation, the stable core's dual frame, and the Newton rung's line
// forms from the shape's form<precise>(). A shape's traits derive from OnFrame<S, their own type>.
#pragma once

#include "forms/exact_form.hpp"
#include "forms/frame.hpp"
#include "forms/line_form.hpp"
#include "forms/prescale.hpp"
#include "shapes/seed_frame.hpp"

namespace linequad::detail {

template <class S, class Traits>
struct OnFrame {
    static void prepare(const S& s, Facts<S>& f) {
        seed_inverse_frame(s.C, s.a, s.b, s.c, f.seed_inverse);
        f.exponent = scale_exponent(f.magnitude);
        double to_unit = Binary64::pow2(-f.exponent);
        f.dual = DualFrame(to_unit * s.a, to_unit * s.b, {to_unit * s.c, {}}).rows();
        f.lowest_exponent = lowest_exponent({s.a, s.b, s.c}, to_unit);
        store(adjugate_rows(AsGiven<S>{s}), f);
    }

    // The rows of adj(M) and det in bounded double-double: what prepare() keeps, or computed.
    template <class Source>
    static AdjugateRowsDD adjugate_rows(const Source& src) {
        if constexpr (Source::prepared)
            return adjugate_rows_dd(src.facts);
        else
            return adjugate_rows_dd(src.shape.a, src.shape.b, src.shape.c);
    }

    // sgn det[a b c], in NT (the oracle decides it in its own arithmetic).
    template <class NT>
    static int exact_orientation(const S& s) {
        using exact_form::lift;
        return sign(exact_form::AdjugateFrame<NT>(lift<NT>(s.a), lift<NT>(s.b), lift<NT>(s.c)).det);
    }

    // The stable core's dual frame of a, b, c (prescaled by ps), made when the core asks for it: a
    // prepared shape's, where it rescales to ps exactly (frame.hpp), else formed from a, b, c.
    template <class T, class Source, class Scale>
    static auto dual_frame(const Source& src, const Scale& ps, const Vec3T<T>& a, const Vec3T<T>& b,
                           const Vec3T<T>& c) {
        return [&]() -> DualFrameT<T> {
            if constexpr (Source::prepared && in_double<T>) {
                int delta = ps.k - src.facts.exponent;
                if (dual_frame_rescales(src.facts, delta))
                    return rescaled_dual_frame(src.facts, delta);
            }
            return {a, b, {c, {}}};
        };
    }

    // For the line L0 + t v in T: double, or a lane type (a line per lane).
    template <class T = double, class Source>
    static LineFormT<T> line_form(const Source& src, Vec3T<T> L0, Vec3T<T> v, int orientation) {
        return Traits::template form<true, T>(src, L0, v, orientation);
    }
    // The hit test's: the same values in doubles with bounds.
    template <class T = double, class Source>
    static LineFormT<T> quick_line_form(const Source& src, Vec3T<T> L0, Vec3T<T> v,
                                        int orientation) {
        return Traits::template form<false, T>(src, L0, v, orientation);
    }
};

} // namespace linequad::detail
