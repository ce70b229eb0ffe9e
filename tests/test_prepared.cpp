// A prepared shape gives every solver's answer bit for bit as the shape itself does: the
// classification, t, points, bounds, certainty and rung, and the same error for bad input.
#include "support.hpp"

#include "linequad/batch.hpp"
#include "linequad/exact.hpp"
#include "linequad/families.hpp"

#include <limits>
#include <type_traits>
#include <vector>

using namespace linequad;
using namespace linequad::test;

namespace {

// Every solver, given the shape or its prepared form.
template <class ShapeOrPrepared>
std::vector<Result> every_answer(const ShapeOrPrepared& s, const Line& l, Query q) {
    return {seed::intersect(s, l, q), stable::intersect(s, l, q), certified::intersect(s, l, q),
            correct::intersect(s, l, q), exact::intersect(s, l, q)};
}

void check_same(const Result& a, const Result& b, const char* solver) {
    INFO(solver << "\nshape    " << describe(a) << "\nprepared " << describe(b));
    CHECK(format_result("0", solver, a) == format_result("0", solver, b));
    CHECK(a.rung == b.rung);
    CHECK(a.certainty == b.certainty);
    if (a.on_surface && b.on_surface) {
        CHECK(same_bits(a.s0, b.s0));
        CHECK(same_bits(a.s1, b.s1));
    }
}

} // namespace

TEST_CASE("prepared shapes: every solver's answer bit for bit, on every family and far out") {
    const char* const names[] = {"seed", "stable", "certified", "correct", "exact"};
    const Query queries[] = {{Need::all, true}, {Need::nearest, false}, {Need::any, false}};
    long compared = 0;
    for (int f = 0; f < family_count; ++f)
        for (int shape = 0; shape < shape_kinds; ++shape) {
            if (!family_applies(Family(f), shape)) continue;
            for (Range range : {Range::line, Range::ray, Range::segment})
                for (std::uint64_t i = 0; i < 24; ++i) {
                    Case c = make_case(Family(f), shape, range, 41, i);
                    // The line as generated, and moved 2^10, 2^100 and 2^400 along itself: the
                    // scene's scale then follows the line's origin, not the shape (the stable
                    // solvers rescale the prepared dual frame, or compute it when they cannot).
                    for (double far : {0.0, 0x1p+10, 0x1p+100, 0x1p+400}) {
                        Line l = c.line;
                        l.L0 = l.L0 - far * l.v;
                        l.range = Interval(l.range.t0 + far, l.range.t1 + far);
                        INFO(format_case(c) << "\nmoved back by " << far);
                        for (Query q : queries)
                            std::visit(
                                [&](const auto& s) {
                                    auto given = every_answer(s, l, q);
                                    auto prepared = every_answer(prepare(s), l, q);
                                    for (int k = 0; k < 5; ++k) {
                                        check_same(given[k], prepared[k], names[k]);
                                        ++compared;
                                    }
                                    CHECK(validate(s, l).code == validate(prepare(s), l).code);
                                },
                                c.shape);
                    }
                }
        }
    CHECK(compared > 50000);
}

TEST_CASE("prepared shapes: bad shapes keep their error, named as the shape's own") {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const Line good{{-10, 1, 2}, {1, 0, 0}};
    const Shape bad[] = {Cylinder{{0, 0, 0}, {0, 0, 0}, 1}, Cylinder{{0, 0, nan}, {0, 0, 1}, 1},
                         Cylinder{{0, 0, 0}, {0, 0, 1}, -1},
                         EllipticCylinder{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}},
                         EllipticCone{{0, 0, 0}, {3, 5, 0}, {1, 0, 0}, {0, 1, 0}}};
    for (const Shape& s : bad)
        std::visit(
            [&](const auto& shape) {
                auto p = prepare(shape);
                INFO(shape_name(Shape(shape)));
                CHECK_FALSE(p.ok());
                CHECK(p.error().code == validate(shape, good).code);
                CHECK(std::string(p.error().field) == validate(shape, good).field);
                Result r = correct::intersect(p, good, {});
                CHECK(r.error_code == p.error().code);
                // A bad line is named before a bad shape, prepared or not.
                Line zero{{0, 0, 0}, {0, 0, 0}};
                CHECK(stable::intersect(p, zero, {}).error_code == ErrorCode::zero_direction);
                CHECK(stable::intersect(shape, zero, {}).error_code == ErrorCode::zero_direction);
            },
            s);
}

TEST_CASE("results are small values: no larger than their fields need") {
    // Four hits (t, point, bound, kind, part, certainty: 43 bytes padded to 48), the interval,
    // the error's field and six one-byte fields (error code, count, on_surface, surface_part,
    // certainty, rung): 192 + 16 + 8 + 6 bytes, padded to 224. Four hits since a closed
    // two-nappe cone can have them (128 bytes with two).
    STATIC_REQUIRE(sizeof(Hit) == 48);
    STATIC_REQUIRE(sizeof(Result) == 224);
    STATIC_REQUIRE(std::is_trivially_copyable_v<Result>);
    STATIC_REQUIRE(std::is_trivially_copyable_v<Prepared<EllipticCone>>);
}
