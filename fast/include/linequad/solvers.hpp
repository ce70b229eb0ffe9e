// The solvers. Each takes a shape (any of linequad::Shape's alternatives, or the variant
// itself) or a prepared shape, a line and what the caller needs:
//     linequad::Result r = linequad::stable::intersect(cylinder, line, {Need::nearest, true});
// and by name, for programs that pick one at run time (the CLI, the audit).
#pragma once

#include "linequad/prepared.hpp"
#include "linequad/result.hpp"
#include "linequad/shapes.hpp"

#include <string_view>
#include <type_traits>
#include <vector>

namespace linequad {

namespace detail {
template <class T, class Variant>
struct is_alternative;
template <class T, class... S>
struct is_alternative<T, std::variant<S...>> : std::disjunction<std::is_same<T, S>...> {};
template <class T>
struct is_prepared : std::false_type {};
template <class S>
struct is_prepared<Prepared<S>> : std::true_type {};
} // namespace detail

// A shape or a prepared shape: what every solver takes.
template <class T>
inline constexpr bool is_solvable_v =
    detail::is_alternative<T, Shape>::value || detail::is_prepared<T>::value;
template <class T>
using if_solvable = std::enable_if_t<is_solvable_v<T>, int>;

// The same checks every solver makes first (fast and exact alike): NaN and infinite
// coordinates, v = 0, the range, r <= 0, H = C, and singular frames (decided exactly).
template <class S, if_solvable<S> = 0>
Error validate(const S& shape, const Line& line);
Error validate(const Shape& shape, const Line& line);

namespace seed {
// Each seed as written: normalised axis or M = T R S inverted as a 4x4 matrix, the textbook
// roots; errata fixed, nothing improved.
template <class S, if_solvable<S> = 0>
Result intersect(const S& shape, const Line& line, Query query = {});
Result intersect(const Shape& shape, const Line& line, Query query = {});
} // namespace seed

namespace stable {
// The same geometry without cancellation: see each shape's derivation in fast/src/shapes/.
template <class S, if_solvable<S> = 0>
Result intersect(const S& shape, const Line& line, Query query = {});
Result intersect(const Shape& shape, const Line& line, Query query = {});
} // namespace stable

namespace certified {
// Stable's geometry with a rigorous bound on every quantity: each hit carries a bound on its t
// error and is certain or marked uncertain; the classification is never wrong when certain.
template <class S, if_solvable<S> = 0>
Result intersect(const S& shape, const Line& line, Query query = {});
Result intersect(const Shape& shape, const Line& line, Query query = {});
} // namespace certified

namespace correct {
// The exact classification, with t and points correctly rounded: the oracle's answer, bit for
// bit, from a ladder of proven rungs (Newton, double-double, exact).
template <class S, if_solvable<S> = 0>
Result intersect(const S& shape, const Line& line, Query query = {});
Result intersect(const Shape& shape, const Line& line, Query query = {});
} // namespace correct

// The float solvers: inputs must be floats (ErrorCode::not_binary32 names the first that is not),
// and every t, point and interval end of the answer is a float, held in a double.
namespace seed32 {
// seed evaluated in float, as a renderer would write it.
template <class S, if_solvable<S> = 0>
Result intersect(const S& shape, const Line& line, Query query = {});
Result intersect(const Shape& shape, const Line& line, Query query = {});
} // namespace seed32

namespace stable32 {
// stable's geometry evaluated in float (its guards at float's range); a line on the surface
// from the certified double solver, rounded to float.
template <class S, if_solvable<S> = 0>
Result intersect(const S& shape, const Line& line, Query query = {});
Result intersect(const Shape& shape, const Line& line, Query query = {});
} // namespace stable32

namespace correct32 {
// The exact classification, with t and points correctly rounded to float (ties to even,
// subnormals and overflow as IEEE rounds them): the oracle's float answer, bit for bit.
template <class S, if_solvable<S> = 0>
Result intersect(const S& shape, const Line& line, Query query = {});
Result intersect(const Shape& shape, const Line& line, Query query = {});
} // namespace correct32

struct Solver {
    std::string_view name;
    std::string_view summary;
    Result (*solve)(const Shape&, const Line&, Query);
    // What it answers in: a binary32 solver takes float inputs only, and is graded in floats.
    Precision precision = Precision::binary64;

    Result operator()(const Shape& s, const Line& l, Query q = {}) const { return solve(s, l, q); }
};

// seed, stable, certified and correct, then the float solvers, in that order.
const std::vector<Solver>& fast_solvers();

struct BuildInfo {
    const char* version;
    const char* compiler;
    const char* fast_flags; // the flags fast/ was compiled with
};
BuildInfo build_info();

} // namespace linequad
