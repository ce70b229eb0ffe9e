// The seed, stable and certified solvers, each written once over every shape: what differs from
// shape to shape is the shape's derivation (ShapeTraits<S>, shapes/), what a solve does with it
// is here. Source is the shape as the solver sees it: as given, or prepared (shapes/traits.hpp).
#pragma once

#include "forms/certified.hpp"
#include "forms/closure.hpp"
#include "forms/finish.hpp"
#include "forms/roots.hpp"
#include "numeric/big_float.hpp"
#include "shapes/all.hpp"

#include <optional>
#include <tuple>

#include <type_traits>

namespace linequad::detail {

// The checks every solve starts with: the line's, then the shape's (its Validity). The usual
// case in one test: every coordinate finite (0 times their sum is NaN otherwise; a sum that
// merely overflows takes the slow path, which finds nothing), v nonzero, the range not empty.
// Otherwise the checks one by one, which name the culprit.
template <class Source>
[[gnu::noinline]] Validity check_one_by_one(const Source& src, const Line& l) {
    if (Error e = check_line(l); !e.ok()) return {e};
    return src.validity();
}
template <class Source>
LINEQUAD_INLINE Validity check(const Source& src, const Line& l) {
    double sum = l.L0.x + l.L0.y + l.L0.z + l.v.x + l.v.y + l.v.z;
    if constexpr (!Source::prepared) sum += field_sum(src.shape);
    const Interval& r = l.range;
    bool usual = (0 * sum == 0) & ((l.v.x != 0) | (l.v.y != 0) | (l.v.z != 0)) & (r.t0 <= r.t1) &
                 (r.t0 < Binary64::inf) & (r.t1 > -Binary64::inf);
    if (usual) return src.validity_of_finite();
    return check_one_by_one(src, l);
}

// The scene's size: the shape's and the line's origin's.
template <class Source>
LINEQUAD_INLINE double scene_extent(const Source& src, const Line& l) {
    return std::max(max_abs(l.L0), src.magnitude());
}

// The solvers as types, each a skeleton generic over the shapes' traits.

// Stable's geometry with a rigorous bound on every quantity; certain or marked uncertain.
struct Certified {
    // What a proven answer says of itself (a patch of a composite shape shown empty without
    // solving it): its certainty, and the correct solver's rung.
    static constexpr Certainty says = Certainty::certain;
    static constexpr Rung rung = Rung::none;
    template <class Source>
    static Result solve(const Source& src, const Line& l, Query q);
};
template <class Source>
Result Certified::solve(const Source& src, const Line& l, Query q) {
    using Traits = ShapeTraits<typename Source::Shape>;
    if (Validity valid = check(src, l); !valid.error.ok()) return Result::failure(valid.error);
    double extent = scene_extent(src, l);
    // Prescaling is exact unless a component is tiny enough to lose bits: refuse those.
    if (fragile_scene(src, extent, l))
        return Result::failure(ErrorCode::out_of_range, Traits::fragile_fields);
    Prescale ps = prescale_for(extent, l.v);
    return quick_then_bounded([&](auto number) {
        using B = decltype(number);
        CertifiedForm<B> f = Traits::template certified_form<B>(src, ps, l);
        return certified_result(f, ps.t_scale(), l, q);
    });
}

// The input checks of a solver computing in R: a float solver's inputs must be floats.
template <class R, class Source>
LINEQUAD_INLINE Error real_error(const Source& src, const Line& l) {
    if constexpr (std::is_same_v<R, float>)
        return binary32_error(src.shape, l);
    else
        return {};
}

// Each seed as written (errata fixed): the textbook quadratic, evaluated in R (double for
// `seed`, float for `seed32`, as a renderer would).
template <class R>
struct SeedIn {
    static constexpr Certainty says = Certainty::unknown;
    static constexpr Rung rung = Rung::none;
    template <class Source>
    static Result solve(const Source& src, const Line& l, Query q);
};
using Seed = SeedIn<double>;
using Seed32 = SeedIn<float>;
template <class R>
template <class Source>
Result SeedIn<R>::solve(const Source& src, const Line& l, Query q) {
    if (Validity valid = check(src, l); !valid.error.ok()) return Result::failure(valid.error);
    if (Error e = real_error<R>(src, l); !e.ok()) return Result::failure(e);
    SeedFormT<R> f = ShapeTraits<typename Source::Shape>::template seed_form<R>(src, l);
    if (!f.usable) return Result::failure(ErrorCode::out_of_range, "coefficients");
    RootsT<R> roots = textbook_roots(f.a, f.b, f.c);
    auto magnitudes = [&] {
        double largest = std::max({src.magnitude(), max_abs(l.L0), max_abs(l.v)});
        double smallest = std::fmin(src.smallest(), std::fmin(min_nonzero(l.L0), min_nonzero(l.v)));
        return std::pair{largest, smallest};
    };
    if (seed_undecidable(roots, f.a, f.b * f.b - 4 * f.a * f.c, magnitudes))
        return Result::failure(ErrorCode::out_of_range, "coefficients");
    // A line on the surface is a claim of infinitely many hits: only with proof.
    auto on_surface = [&] {
        return answered_in<R>(without_certification(Certified::solve(src, l, q)));
    };
    if (roots.kind == RootsT<R>::on_surface) return on_surface();
    auto z_of = [&](const RootsT<R>& r, int i) { return f.z0 + r.t[i] * f.dz; };
    if (f.extent.caps.any())
        return finish_closed(roots, z_of, AxialQuadratic<R>{f.a, f.b, f.c, f.z0, f.dz, 0, 1},
                             f.extent, l, q, on_surface);
    return finish_roots(roots, R(1), z_of, f.extent, l, q);
}

// The scalar stable solve around a shape's core (its Stable<R>), in R (double for `stable`,
// float for `stable32`): the branches that the batch kernels send back here. For the cylinders
// A = 0 (a line along the axis) means no hit or a line on the surface; for the cone it is a line
// along a generator, a linear equation that stable_roots solves. A line on the surface needs
// proof: the certified result stands for it.
template <class R>
struct StableIn {
    static constexpr Certainty says = Certainty::unknown;
    static constexpr Rung rung = Rung::none;
    template <class Source>
    static Result solve(const Source& src, const Line& l, Query q);
};
using Stable = StableIn<double>;
using Stable32 = StableIn<float>;
template <class R>
template <class Source>
Result StableIn<R>::solve(const Source& src, const Line& l, Query q) {
    using Traits = ShapeTraits<typename Source::Shape>;
    using Roots = RootsT<R>;
    if (Validity valid = check(src, l); !valid.error.ok()) return Result::failure(valid.error);
    if (Error e = real_error<R>(src, l); !e.ok()) return Result::failure(e);
    double extent = scene_extent(src, l);
    PrescaleT<R> ps = prescale_for<R>(extent, l.v);
    auto k = Traits::template stable_core<R>(src, ps, in_real<R>(l.L0), in_real<R>(l.v));
    if (k.smaller_than(Guards<R>::min_relative_size))
        return Result::failure(ErrorCode::out_of_range, Traits::scale_fields);
    // A zero of A or D may be underflow when a component is tiny beside the scene, or when the
    // shape is and they are products of its sizes.
    auto fragile = [&] { return fragile_scene<R>(src, extent, l) || k.zero_may_underflow(); };
    auto on_surface = [&] {
        return answered_in<R>(without_certification(Certified::solve(src, l, q)));
    };
    Extent e = widened(k.extent(src.shape));
    Roots roots;
    if (k.parallel_is_miss && k.A == 0) {
        R C0 = k.C0_at_origin();
        roots.kind = C0 == 0 ? Roots::on_surface : Roots::none;
        if (undecidable(roots, fragile, k.A, C0))
            return Result::failure(ErrorCode::out_of_range, Traits::fragile_fields);
        if (roots.kind == Roots::on_surface) return on_surface();
        if (!e.caps.any()) return Result{};
        k.discriminant(); // along the axis, inside: through the discs, from the moved origin
        roots = Roots{};
    } else {
        k.discriminant();
        roots = stable_roots(k.A, k.B, k.C_moved, k.D);
        if (undecidable(roots, fragile, k.A, k.D) || (k.A == 0 && fragile()))
            return Result::failure(ErrorCode::out_of_range, Traits::fragile_fields);
        if (roots.kind == Roots::on_surface) return on_surface();
        shift_back(roots, k.tc, [&] { return k.C0_at_origin() / k.A; });
    }
    auto z_of = [&](const Roots& r, int i) { return k.z_of(r, i); };
    if (e.caps.any())
        return finish_closed(roots, z_of,
                             AxialQuadratic<R>{k.A, 2 * k.B, k.C_moved, k.axial_moved(),
                                               k.axial_rate(), k.tc, ps.t_scale()},
                             e, l, q, on_surface);
    return finish_roots(roots, ps.t_scale(), z_of, e, l, q);
}

// ---- Shapes made of patches (the capsule) ----

// A patch's roots, exactly (the exact rung's form and classification): for ordering two hits
// of different patches that round to the same t.
template <class P>
exact_form::Classification<BigFloat> patch_roots(const P& patch, const Line& l) {
    auto q = ShapeTraits<P>::template exact_quadratic<BigFloat>(patch, l, 0);
    return exact_form::classify(q, exact_form::parameter_range<BigFloat>(l.range), Need::all);
}

// One patch's hit in the merge: its patch, and its place among the patch's hits.
struct PatchHit {
    Hit hit;
    int patch, index;
};

// Whether hit a comes before hit b, two hits of different patches on one double: by the patches'
// exact roots. Rare, and out of line, so that the usual merge holds no exact numbers.
template <class... P>
[[gnu::noinline]] bool exactly_before(const std::tuple<P...>& patches, const Line& l,
                                      const PatchHit& a, const PatchHit& b) {
    auto roots_of = [&](int i) {
        std::optional<exact_form::Classification<BigFloat>> c;
        int at = 0;
        std::apply(
            [&](const auto&... p) { ((at++ == i ? void(c = patch_roots(p, l)) : void()), ...); },
            patches);
        return std::move(*c);
    };
    const exact_form::Classification<BigFloat> x = roots_of(a.patch), y = roots_of(b.patch);
    if (a.index >= x.count || b.index >= y.count) return a.patch < b.patch; // not exact roots
    const auto &p = x.roots[a.index], &s = y.roots[b.index];
    return exact_form::compare_roots<BigFloat>({p.N, p.S, p.Den, x.D}, {s.N, s.S, s.Den, y.D}) < 0;
}

// The hits of every patch, merged: each named by its patch's part, in the order of t; two on one
// double from different patches ordered by their exact roots; two at most (the shape is convex). A
// patch's error is the answer (the first patch, the side, names the capsule's fields), and so is a
// line along a patch's surface (only the side has one). Certain when every patch's answer is; the
// correct solver's rung, the highest any patch took.
template <class S, class... P>
Result merge_patches(const std::tuple<P...>& patches, const Result (&each)[sizeof...(P)],
                     const Line& l, Query q) {
    constexpr int n = int(sizeof...(P));
    for (const Result& r : each)
        if (!r.ok()) return r;
    for (int i = 0; i < n; ++i)
        if (each[i].on_surface) {
            Result r = each[i];
            r.surface_part = ShapeTraits<S>::parts[i];
            return r;
        }
    PatchHit hits[2 * n];
    int count = 0;
    Result r;
    bool certain = true, unknown = false;
    for (int i = 0; i < n; ++i) {
        certain = certain && each[i].certainty == Certainty::certain;
        unknown = unknown || each[i].certainty == Certainty::unknown;
        r.rung = std::max(r.rung, each[i].rung);
        for (int k = 0; k < each[i].count; ++k) {
            hits[count] = {each[i].hits[k], i, k};
            hits[count++].hit.part = ShapeTraits<S>::parts[i];
        }
    }
    r.certainty = unknown   ? Certainty::unknown
                  : certain ? Certainty::certain
                            : Certainty::uncertain;
    auto before = [&](const PatchHit& a, const PatchHit& b) {
        if (a.hit.t != b.hit.t || a.patch == b.patch) return a.hit.t < b.hit.t;
        return exactly_before(patches, l, a, b);
    };
    for (int i = 1; i < count; ++i) // a few hits: insertion
        for (int j = i; j > 0 && before(hits[j], hits[j - 1]); --j)
            std::swap(hits[j], hits[j - 1]);
    // A seam point that two patches each claim without proof (a certified solver whose seam test
    // is uncertain): their proven enclosures meet. It is one point, the round end's.
    int kept = 0;
    for (int i = 0; i < count; ++i) {
        if (kept > 0) {
            const Hit &a = hits[kept - 1].hit, &b = hits[i].hit;
            bool unproven = !(a.certain && b.certain);
            if (hits[kept - 1].patch != hits[i].patch && unproven &&
                std::fabs(b.t - a.t) <= a.bound + b.bound) {
                if (a.part == Part::lateral) hits[kept - 1] = hits[i];
                continue;
            }
        }
        hits[kept++] = hits[i];
    }
    count = kept;
    // A shape of patches is convex: its surface meets a line at two points at most. More (from a
    // solver that is not exact about the seams) keep the outermost: where it enters and leaves.
    if (count > 2) hits[1] = hits[count - 1], count = 2;
    int keep = q.need == Need::all ? count : std::min(count, 1);
    for (int k = 0; k < keep; ++k)
        r.hits[r.count++] = hits[k].hit;
    return r;
}

// Solver's answer for a shape as given or prepared: its own solve, or for a shape made of patches
// each patch's (as given: a patch keeps no facts), merged.
template <class Solver, class Source>
Result solve_shape(const Source& src, const Line& l, Query q) {
    using S = typename Source::Shape;
    if constexpr (is_composite<S>) {
        if (Validity valid = check(src, l); !valid.error.ok()) return Result::failure(valid.error);
        auto patches = ShapeTraits<S>::patches(src.shape);
        Result each[std::tuple_size_v<decltype(patches)>];
        int i = 0;
        // Every hit of a patch is asked for (but by a hit test), so that once the shape's most
        // hits are found (it is convex: two), or a hit test has one, no other patch can add one:
        // those are not solved, as a patch whose quadric the line provably misses is not. Each is
        // then as certain as the solver says a proven answer is.
        Query each_query = q;
        if (q.need == Need::nearest) each_query.need = Need::all;
        int found = 0;
        bool done = false;
        auto solve = [&](const auto& p) {
            // The first patch is always solved: it makes the solver's own checks of the input
            // (a float solver's, that every input is a float).
            if (i > 0 && (done || ShapeTraits<S>::patch_misses(src.shape, i, l))) {
                each[i].certainty = Solver::says, each[i++].rung = Solver::rung;
                return;
            }
            const Result& r = each[i++] =
                Solver::solve(AsGiven<std::decay_t<decltype(p)>>{p}, l, each_query);
            found += r.ok() ? r.count : 0;
            done = !r.ok() || r.on_surface || found >= (q.need == Need::any ? 1 : 2);
        };
        std::apply([&](const auto&... p) { (solve(p), ...); }, patches);
        return merge_patches<S>(patches, each, l, q);
    } else {
        return Solver::solve(src, l, q);
    }
}

} // namespace linequad::detail
