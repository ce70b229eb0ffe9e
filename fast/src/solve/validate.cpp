// Validation and prepare(): the checks every solver makes first, and the facts of a shape
// worked out once.
#include "shapes/all.hpp"

#include "linequad/solvers.hpp"

namespace linequad {

namespace detail {

Error check_line(const Line& l) {
    // 0 * (sum of every coordinate) is NaN iff one is NaN or infinite: one test for the usual
    // case, the field by field checks (which name the culprit) only when it fails.
    double sum = l.L0.x + l.L0.y + l.L0.z + l.v.x + l.v.y + l.v.z;
    if (!(0 * sum == 0)) {
        if (has_nan(l.L0)) return {ErrorCode::not_a_number, "L0"};
        if (!is_finite(l.L0)) return {ErrorCode::infinite, "L0"};
        if (has_nan(l.v)) return {ErrorCode::not_a_number, "v"};
        return {ErrorCode::infinite, "v"};
    }
    const Interval& r = l.range;
    if (std::isnan(r.t0)) return {ErrorCode::not_a_number, "t0"};
    if (std::isnan(r.t1)) return {ErrorCode::not_a_number, "t1"};
    if (l.v == Vec3{}) return {ErrorCode::zero_direction, "v"};
    if (!(r.t0 <= r.t1) || r.t0 == Binary64::inf || r.t1 == -Binary64::inf)
        return {ErrorCode::empty_range, "t0,t1"};
    return {};
}

} // namespace detail

template <class S, if_solvable<S>>
Error validate(const S& shape, const Line& line) {
    if (Error e = detail::check_line(line); !e.ok()) return e;
    return detail::source(shape).validity().error;
}

Error validate(const Shape& s, const Line& l) {
    return std::visit([&](const auto& shape) { return validate(shape, l); }, s);
}

template <class S>
Prepared<S> prepare(const S& shape) {
    using namespace detail;
    Facts<S> f;
    Validity v = validity_of(shape);
    f.error = v.error, f.orientation = v.orientation;
    if (f.error.ok()) {
        f.magnitude = shape_magnitude(shape);
        f.smallest = smallest_component(shape);
        ShapeTraits<S>::prepare(shape, f);
    }
    return PreparedAccess::make(shape, f);
}

namespace detail {
[[gnu::noinline]] double nearest_float(double x) {
    return float(x);
}
Vec3 nearest_float(Vec3 a) {
    return {nearest_float(a.x), nearest_float(a.y), nearest_float(a.z)};
}
} // namespace detail
using detail::nearest_float;

Shape rounded_to_binary32(const Shape& s) {
    Shape out = s;
    std::visit(
        [](auto& shape) {
            detail::for_each_field<std::decay_t<decltype(shape)>>(
                [&](const auto& f) { shape.*f.member = nearest_float(shape.*f.member); });
        },
        out);
    return out;
}

Line rounded_to_binary32(const Line& l) {
    return {nearest_float(l.L0),
            nearest_float(l.v),
            {nearest_float(l.range.t0), nearest_float(l.range.t1)}};
}

template <class S>
const char* shape_name() {
    return detail::ShapeTraits<S>::name;
}

const char* shape_name(const Shape& s) {
    return std::visit(
        [](const auto& shape) { return detail::ShapeTraits<std::decay_t<decltype(shape)>>::name; },
        s);
}

#define LINEQUAD_INSTANTIATE(S)                                                                    \
    template Error validate(const S&, const Line&);                                                \
    template Error validate(const Prepared<S>&, const Line&);                                      \
    template Prepared<S> prepare(const S&);                                                        \
    template const char* shape_name<S>();
LINEQUAD_FOR_EACH_SHAPE(LINEQUAD_INSTANTIATE)

} // namespace linequad
