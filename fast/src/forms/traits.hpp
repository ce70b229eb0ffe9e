// What the solvers share about shapes. Each shape's facts and derivations are written once, in
// its ShapeTraits specialisation (shapes/cylinder.hpp, elliptic_cylinder.hpp, elliptic_cone.hpp,
// frustum.hpp):
//   name, fields           the case format's name of the shape, and its table: the name and
//                          member of every field
//   validate(shape)        what is wrong with a shape whose fields are finite (and the
//                          orientation of its frame, which deciding it took)
//   scale_fields, fragile_fields  what a double solver names when the scene is out of its reach
//   prepare(shape, facts)  the facts prepare() keeps (Facts<S>, linequad/prepared.hpp)
//   seed_form              the seed's derivation as written
//   Stable<T>, stable_core the stable solver's core, for any lane type, and its construction
//   certified_form<B>      the stable quantities in a bounded type
//   exact_orientation<NT>, exact_quadratic<NT>  the exact, division-free form in any ring
//   has_line_form, line_form, quick_line_form  the correct solver's Newton rung and hit test
//                          views, where the shape's quadratic has one (signed squares), for
//                          double and for the batch kernels' lane types
// Every field is a position: it scales with the scene (the scene's magnitude and the checks for
// components too small for double arithmetic run over them).
#pragma once

#include "numeric/format.hpp"
#include "numeric/vector.hpp"

#include "linequad/prepared.hpp"
#include "linequad/result.hpp"
#include "linequad/shapes.hpp"

#include <array>
#include <cmath>
#include <optional>
#include <tuple>
#include <type_traits>

namespace linequad::detail {

template <class S>
struct ShapeTraits;

// A field of the case format: its name and the member that holds it (a Vec3 or a number).
template <class S, class T>
struct Field {
    const char* name;
    T S::*member;
};
template <class S, class T>
constexpr Field<S, T> field(const char* name, T S::*member) {
    return {name, member};
}

template <class S, class Visit>
LINEQUAD_INLINE void for_each_field(Visit&& visit) {
    std::apply([&](const auto&... f) { (visit(f), ...); }, ShapeTraits<S>::fields);
}

inline double max_abs(double x) {
    return std::fabs(x);
}
// The smallest nonzero |component| (infinity when every one is zero).
inline double min_nonzero(double x) {
    return x != 0 ? std::fabs(x) : Binary64::inf;
}
inline double min_nonzero(Vec3 a) {
    return std::fmin(min_nonzero(a.x), std::fmin(min_nonzero(a.y), min_nonzero(a.z)));
}
inline bool has_nan(double x) {
    return std::isnan(x);
}
inline bool has_nan(Vec3 a) {
    return std::isnan(a.x) || std::isnan(a.y) || std::isnan(a.z);
}
inline bool is_finite(double x) {
    return std::isfinite(x);
}
inline double component_sum(double x) {
    return x;
}
inline double component_sum(Vec3 a) {
    return a.x + a.y + a.z;
}

// A field of N numbers (a quadric's coefficients), as the functions above take a Vec3.
// (std::max, not fmax: a libm call per coefficient. NaN never reaches these: fields are checked
// first.)
template <std::size_t N>
double max_abs(const std::array<double, N>& a) {
    double m = 0;
    for (double x : a)
        m = std::max(m, std::fabs(x));
    return m;
}
template <std::size_t N>
double min_nonzero(const std::array<double, N>& a) {
    double m = Binary64::inf;
    for (double x : a)
        m = std::min(m, min_nonzero(x));
    return m;
}
template <std::size_t N>
bool has_nan(const std::array<double, N>& a) {
    for (double x : a)
        if (std::isnan(x)) return true;
    return false;
}
template <std::size_t N>
bool is_finite(const std::array<double, N>& a) {
    for (double x : a)
        if (!std::isfinite(x)) return false;
    return true;
}
template <std::size_t N>
double component_sum(const std::array<double, N>& a) {
    double sum = 0;
    for (double x : a)
        sum += x;
    return sum;
}

// Shapes whose fields are not positions (a plane's normal, a quadric's coefficients) size and
// scale themselves: ShapeTraits<S>::magnitude (a length the shape is about, a power of two, or 0
// where it sets none) and ::scaled_exactly (the same surface with every position times f, a power
// of two, or none where that would lose bits). No position of theirs holds a tiny component:
// their smallest is infinity.
template <class S, class = void>
inline constexpr bool scales_itself = false;
template <class S>
inline constexpr bool scales_itself<
    S, std::void_t<decltype(ShapeTraits<S>::scaled_exactly(std::declval<const S&>(), 1.0))>> = true;

// The largest |coordinate| of the shape's positions: the scene's size as the shape sets it.
template <class S>
double shape_magnitude(const S& s) {
    if constexpr (scales_itself<S>) {
        return ShapeTraits<S>::magnitude(s);
    } else {
        double m = 0;
        for_each_field<S>([&](const auto& f) { m = std::max(m, max_abs(s.*f.member)); });
        return m;
    }
}
template <class S>
double smallest_component(const S& s) {
    if constexpr (scales_itself<S>) {
        return Binary64::inf;
    } else {
        double m = Binary64::inf;
        for_each_field<S>([&](const auto& f) { m = std::fmin(m, min_nonzero(s.*f.member)); });
        return m;
    }
}
// The shape with every position times f (a power of two: exactly, barring underflow, which
// fragile_scene() rules out for positions; a shape that scales itself says).
template <class S>
std::optional<S> scaled(S s, double f) {
    if constexpr (scales_itself<S>) {
        return ShapeTraits<S>::scaled_exactly(s, f);
    } else {
        for_each_field<S>([&](const auto& fl) { s.*fl.member = f * (s.*fl.member); });
        return s;
    }
}

// The sum of every coordinate of the shape's fields: finite when they all are (or it overflowed).
template <class S>
double field_sum(const S& s) {
    double sum = 0;
    for_each_field<S>([&](const auto& f) { sum += component_sum(s.*f.member); });
    return sum;
}

// NaN, then infinite, field by field in the table's order.
template <class S>
Error check_fields(const S& s) {
    Error e;
    for_each_field<S>([&](const auto& f) {
        if (!e.ok()) return;
        const auto& x = s.*f.member;
        if (has_nan(x))
            e = {ErrorCode::not_a_number, f.name};
        else if (!is_finite(x))
            e = {ErrorCode::infinite, f.name};
    });
    return e;
}

// x (or each coordinate) rounded to the nearest float. (Out of line: GCC 12's -O3 vectorises
// the rounding of consecutive vectors and drops their last two components, leaving them
// unrounded.)
double nearest_float(double x);
Vec3 nearest_float(Vec3 a);
template <std::size_t N>
std::array<double, N> nearest_float(std::array<double, N> a) {
    for (double& x : a)
        x = nearest_float(x);
    return a;
}

// For a float solver, after the usual checks: the first input that is not a float (the line's
// L0, v, t0, t1, then the shape's fields in the table's order). The usual case in one pass,
// without branches: whether any input differs from its nearest float; the field by field search,
// which names the culprit, only when one does.
struct Binary32Check {
    double off = 0; // the sum of |x - float(x)| over finite inputs (the solvers refuse others)
    LINEQUAD_INLINE void add(double x) { off += std::fabs(x - double(float(x))); }
    LINEQUAD_INLINE void add(const Vec3& a) { add(a.x), add(a.y), add(a.z); }
    template <std::size_t N>
    LINEQUAD_INLINE void add(const std::array<double, N>& a) {
        for (double x : a)
            add(x);
    }
    LINEQUAD_INLINE void add(const Interval& i) {
        if (i.has_t0()) add(i.t0);
        if (i.has_t1()) add(i.t1);
    }
    LINEQUAD_INLINE bool all_floats() const { return off == 0; }
};
inline bool holds_binary32(double x) {
    return Binary32::holds(x);
}
inline bool holds_binary32(Vec3 a) {
    return Binary32::holds(a.x) && Binary32::holds(a.y) && Binary32::holds(a.z);
}
template <std::size_t N>
bool holds_binary32(const std::array<double, N>& a) {
    for (double x : a)
        if (!Binary32::holds(x)) return false;
    return true;
}
template <class S>
[[gnu::noinline]] Error binary32_culprit(const S& s, const Line& l) {
    if (!holds_binary32(l.L0)) return {ErrorCode::not_binary32, "L0"};
    if (!holds_binary32(l.v)) return {ErrorCode::not_binary32, "v"};
    if (!holds_binary32(l.range.t0)) return {ErrorCode::not_binary32, "t0"};
    if (!holds_binary32(l.range.t1)) return {ErrorCode::not_binary32, "t1"};
    Error e;
    for_each_field<S>([&](const auto& f) {
        if (e.ok() && !holds_binary32(s.*f.member)) e = {ErrorCode::not_binary32, f.name};
    });
    return e;
}
template <class S>
LINEQUAD_INLINE Error binary32_error(const S& s, const Line& l) {
    Binary32Check check;
    check.add(l.L0), check.add(l.v), check.add(l.range);
    for_each_field<S>([&](const auto& f) { check.add(s.*f.member); });
    if (check.all_floats()) return {};
    return binary32_culprit(s, l);
}

// The line's own checks, before any of the shape's: L0, v (NaN, then infinite), the range's
// ends, v = 0, an empty range.
Error check_line(const Line& l);

// A shape's validity, and the orientation of its frame (elliptic shapes) that deciding it took.
struct Validity {
    Error error;
    int orientation = 0;
};
template <class S>
Validity validity_of(const S& s) {
    Error e = check_fields(s);
    if (!e.ok()) return {e};
    return ShapeTraits<S>::validate(s);
}

struct PreparedAccess {
    template <class S>
    static const Facts<S>& facts(const Prepared<S>& p) {
        return p.facts_;
    }
    template <class S>
    static Prepared<S> make(const S& s, const Facts<S>& f) {
        Prepared<S> p;
        p.shape_ = s, p.facts_ = f;
        return p;
    }
};

// A shape as a solver sees it. AsGiven works out each fact when a solver asks for it (a solver
// asks only for what it needs); AsPrepared reads it from what prepare() worked out, with the same
// functions. The solvers are written once over both, and give the same results
// (tests/test_prepared.cpp, and the fuzzer).
template <class S>
struct AsGiven {
    using Shape = S;
    static constexpr bool prepared = false;
    const S& shape;

    Validity validity() const { return validity_of(shape); }
    // When every field is known finite.
    Validity validity_of_finite() const { return ShapeTraits<S>::validate(shape); }
    double magnitude() const { return shape_magnitude(shape); }
    double smallest() const { return smallest_component(shape); }
};
template <class S>
struct AsPrepared {
    using Shape = S;
    static constexpr bool prepared = true;
    const S& shape;
    const Facts<S>& facts;

    explicit AsPrepared(const Prepared<S>& p) : shape(p.shape()), facts(PreparedAccess::facts(p)) {}
    Validity validity() const { return {facts.error, facts.orientation}; }
    Validity validity_of_finite() const { return validity(); }
    double magnitude() const { return facts.magnitude; }
    double smallest() const { return facts.smallest; }
};
template <class S>
AsGiven<S> source(const S& s) {
    return {s};
}
template <class S>
AsPrepared<S> source(const Prepared<S>& p) {
    return AsPrepared<S>(p);
}

// Which ends of a shape's axial extent a disc closes (lo: the base, hi: the top), and whether the
// closed shape is two solids meeting at z = 0 (a two-nappe cone's apex).
struct Closure {
    bool lo = false, hi = false;
    bool two_solids = false;
    // Ends owned by another part of a composite shape (a capsule's side ends at its seams, which
    // belong to the round ends): a root exactly there is not this part's. No disc.
    bool open_lo = false, open_hi = false;
    bool any() const { return lo || hi; }
};

// A cylinder's discs: one at each end, when it has caps.
inline Closure both_ends(bool caps) {
    return {caps, caps, false};
}

// Whether the shape is made of patches, each a quadric piece solved as a shape of its own
// (ShapeTraits<S>::patches; the capsule's side and round ends): every solver merges them
// (solve/solve.hpp, solve_shape).
template <class S, class = void>
struct IsComposite : std::false_type {};
template <class S>
struct IsComposite<S, std::void_t<decltype(ShapeTraits<S>::composite)>>
    : std::bool_constant<ShapeTraits<S>::composite> {};
// A shape's traits must be complete where this is asked (shapes/all.hpp included): an incomplete
// one would read as "not composite".
template <class S>
constexpr bool composite_shape() {
    static_assert(sizeof(ShapeTraits<S>) > 0, "include shapes/all.hpp");
    return IsComposite<S>::value;
}
template <class S>
inline constexpr bool is_composite = composite_shape<S>();

// f(patch) for the patch of a shape made of patches whose part is `part` (the first patch when
// none is).
template <class S, class F>
auto with_patch(const S& shape, Part part, F&& f) {
    auto patches = ShapeTraits<S>::patches(shape);
    constexpr std::size_t n = std::tuple_size_v<decltype(patches)>;
    std::size_t at = 0;
    for (std::size_t i = 0; i < n; ++i)
        if (ShapeTraits<S>::parts[i] == part) at = i, i = n;
    return std::apply(
        [&](const auto& first, const auto&... rest) {
            using R = decltype(f(first));
            R out = f(first);
            std::size_t i = 1;
            ((i++ == at ? void(out = f(rest)) : void()), ...);
            return out;
        },
        patches);
}

// Whether the batch kernels' lanes take the shape's Newton form: wherever it has one (every
// line_form is written for a lane type too).
template <class S>
inline constexpr bool line_form_in_lanes = ShapeTraits<S>::has_line_form;

// Whether a shape gives the Newton rung its local quadratic at any point (newton_form: a
// quadric's), in place of a line form.
template <class S, class = void>
inline constexpr bool has_newton_form = false;
template <class S>
inline constexpr bool
    has_newton_form<S, std::void_t<decltype(ShapeTraits<S>::newton_form(
                           std::declval<const S&>(), std::declval<const Line&>()))>> = true;
// Whether the batch correct solver's lanes take the shape (simd/correct_lanes.hpp): a line form
// or a newton form (LINEQUAD_FOR_EACH_CORRECT_LANES_SHAPE).
template <class S>
inline constexpr bool correct_in_lanes = line_form_in_lanes<S> || has_newton_form<S>;

// Whether discs close the shape's ends (the Newton rung's LineFormT::discs).
template <class S>
bool has_discs(const S& s) {
    return has_caps(s);
}

// The options every shape with an axis checks before its geometry: caps close a finite shape
// only.
template <class S>
Error check_caps(const S& s) {
    if constexpr (has_extent_options<S>)
        if (s.caps && !s.finite) return {ErrorCode::bad_option, "caps"};
    return {};
}

// The axial extent lo <= z <= hi in a derivation's own units (infinite ends when unbounded),
// for any lane type, and the discs that close it.
template <class T>
struct ExtentT {
    T lo, hi;
    Closure caps{};
};
using Extent = ExtentT<double>;
// An extent in R as the double one it equals (every R value is a double).
template <class R>
Extent widened(const ExtentT<R>& e) {
    return {e.lo, e.hi, e.caps};
}

} // namespace linequad::detail
