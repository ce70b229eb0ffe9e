// The batch solvers return the scalar solvers' results bit for bit, on every family's cases,
// bad lines and the lanes that fall back to the scalar solver included, on every path this
// machine runs: stable and correct in eight (AVX-512) or four (AVX2) double lanes, stable32 in
// eight float lanes, and the scalar loop.
#include "support.hpp"

#include "correct/correct.hpp"
#include "linequad/batch.hpp"
#include "linequad/families.hpp"
#include "linequad/prepared.hpp"
#include "simd/batch_kernels.hpp"

#include <limits>
#include <map>
#include <set>
#include <string>
#include <type_traits>
#include <vector>

using namespace linequad;
using namespace linequad::test;

namespace {

// The batch solvers under test: stable and correct on double lines, stable32 on float lines.
enum class Batch { stable, correct, stable32 };
template <Batch B>
using RealOf = std::conditional_t<B == Batch::stable32, float, double>;

template <Batch B>
Result scalar(const Shape& s, const Line& l, Query q) {
    return std::visit(
        [&](const auto& shape) {
            if constexpr (B == Batch::stable32)
                return stable32::intersect(shape, l, q);
            else if constexpr (B == Batch::correct)
                return correct::intersect(shape, l, q);
            else
                return stable::intersect(shape, l, q);
        },
        s);
}
template <Batch B>
void batch(const Shape& s, const LineArraysT<RealOf<B>>& lines, Query q, Result* out, Lanes lanes) {
    std::visit(
        [&](const auto& shape) {
            if constexpr (B == Batch::stable32)
                stable32::intersect(shape, lines, q, out, lanes);
            else if constexpr (B == Batch::correct)
                correct::intersect(shape, lines, q, out, lanes);
            else
                stable::intersect(shape, lines, q, out, lanes);
        },
        s);
}

// The lines held in soa (x, y, z, vx, vy, vz), all of one range.
template <class R>
LineArraysT<R> arrays_of(std::vector<R> (&soa)[6], Interval range) {
    return {soa[0].data(), soa[1].data(), soa[2].data(), soa[3].data(),
            soa[4].data(), soa[5].data(), soa[0].size(), range};
}

// Every family's cases in R's precision, one shape against `per_shape` lines: two full batches
// and a scalar tail, with a zero direction and a NaN among them. Returns the lines compared.
template <Batch B>
std::size_t compare_with_scalar(std::size_t per_shape, Lanes lanes) {
    using R = RealOf<B>;
    constexpr Precision precision =
        std::is_same_v<R, float> ? Precision::binary32 : Precision::binary64;
    const R nan = std::numeric_limits<R>::quiet_NaN();
    std::size_t compared = 0;
    for (int shape_kind = 0; shape_kind < shape_kinds; ++shape_kind)
        for (int f = 0; f < family_count; ++f) {
            if (!family_applies(Family(f), shape_kind)) continue;
            for (Range range : {Range::line, Range::ray, Range::segment}) {
                std::vector<Case> cases;
                for (std::uint64_t i = 0; i < 400; ++i)
                    cases.push_back(
                        make_case(Family(f), shape_kind, range, 11, i, Frames::any, precision));
                for (std::size_t first = 0; first + per_shape <= cases.size(); first += per_shape) {
                    const Shape& shape = cases[first].shape;
                    std::vector<R> soa[6];
                    for (std::size_t j = first; j < first + per_shape; ++j) {
                        Line l = cases[j].line;
                        for (int a = 0; a < 3; ++a)
                            soa[a].push_back(R(l.L0[a])), soa[3 + a].push_back(R(l.v[a]));
                    }
                    for (int a = 3; a < 6; ++a)
                        soa[a][5] = 0; // bad lines go through too
                    soa[1][6] = nan;
                    LineArraysT<R> lines = arrays_of(soa, cases[first].line.range);
                    for (Query q : {Query{}, Query{Need::all, false}, Query{Need::nearest, true},
                                    Query{Need::nearest, false}, Query{Need::any, false}}) {
                        std::vector<Result> got(per_shape);
                        batch<B>(shape, lines, q, got.data(), lanes);
                        for (std::size_t j = 0; j < per_shape; ++j) {
                            Line l{{soa[0][j], soa[1][j], soa[2][j]},
                                   {soa[3][j], soa[4][j], soa[5][j]},
                                   lines.range};
                            Result want = scalar<B>(shape, l, q);
                            INFO(family_name(Family(f))
                                 << " shape " << shape_kind << " line " << j);
                            REQUIRE(format_result("0", "", got[j], q.points) ==
                                    format_result("0", "", want, q.points));
                            REQUIRE(got[j].rung == want.rung); // correct's: which rung answered
                            ++compared;
                        }
                    }
                }
            }
        }
    return compared;
}

} // namespace

namespace {
// Every path up to the widest this machine has (a machine without AVX-512 tests the others).
std::vector<Lanes> paths() {
    std::vector<Lanes> out;
    for (Lanes l : {Lanes::scalar, Lanes::avx2, Lanes::avx512})
        if (l <= batch_lanes()) out.push_back(l);
    return out;
}
} // namespace

TEST_CASE("batch: stable equals the scalar solver bit for bit, for every shape and path",
          "[batch]") {
    for (Lanes lanes : paths()) {
        INFO("lanes: " << lanes_name(lanes));
        // 19 lines per shape: two batches of eight and a tail of three, or four of four and three.
        CHECK(compare_with_scalar<Batch::stable>(19, lanes) > 35000);
    }
}

TEST_CASE("batch: stable32 equals the scalar solver bit for bit, for every shape and path",
          "[batch]") {
    for (Lanes lanes : paths()) {
        INFO("lanes: " << lanes_name(lanes));
        CHECK(compare_with_scalar<Batch::stable32>(19, lanes) > 35000);
    }
}

TEST_CASE("batch: correct equals the scalar solver bit for bit and rung for rung, on every path",
          "[batch]") {
    for (Lanes lanes : paths()) {
        INFO("lanes: " << lanes_name(lanes));
        CHECK(compare_with_scalar<Batch::correct>(19, lanes) > 35000);
    }
}

TEST_CASE("batch: correct names a bad shape or range on every line as the scalar solver does",
          "[batch]") {
    // Sixteen lines (full blocks on every path) through a cylinder; each refusal names its field.
    std::vector<double> soa[6];
    for (int i = 0; i < 16; ++i) {
        double p[6] = {-10, 0.25 * i, 1, 1, 0, 0};
        for (int a = 0; a < 6; ++a)
            soa[a].push_back(p[a]);
    }
    auto lines_with = [&](Interval range) { return arrays_of(soa, range); };
    Cylinder good{{0, 0, 0}, {0, 0, 10}, 5}, flat{{0, 0, 0}, {0, 0, 10}, 0};
    struct Input {
        Cylinder shape;
        Interval range;
        ErrorCode want;
    };
    const double nan = std::numeric_limits<double>::quiet_NaN();
    for (const Input& in : {Input{flat, Range::line, ErrorCode::bad_radius},
                            Input{good, Interval(2, 1), ErrorCode::empty_range},
                            Input{good, Interval(nan, 1), ErrorCode::not_a_number},
                            Input{good, Range::ray, ErrorCode::none}}) {
        for (Lanes lanes : paths())
            for (Query q : {Query{}, Query{Need::nearest, false}, Query{Need::any, false}}) {
                Result got[16];
                correct::intersect(prepare(in.shape), lines_with(in.range), q, got, lanes);
                for (int i = 0; i < 16; ++i) {
                    Line l{{soa[0][i], soa[1][i], soa[2][i]}, {1, 0, 0}, in.range};
                    Result want = correct::intersect(in.shape, l, q);
                    INFO("lanes " << lanes_name(lanes) << " line " << i);
                    REQUIRE(got[i].error_code == in.want);
                    REQUIRE(format_result("0", "", got[i], q.points) ==
                            format_result("0", "", want, q.points));
                }
            }
    }
    // No lines: nothing written, nothing read.
    Result untouched;
    untouched.count = 7;
    correct::intersect(
        good, LineArrays{nullptr, nullptr, nullptr, nullptr, nullptr, nullptr, 0, Range::line},
        Query{}, &untouched);
    CHECK(untouched.count == 7);
}

TEST_CASE("batch: stable refuses a t or a point beyond double's range as the scalar solver does",
          "[batch]") {
    // An infinite cylinder of radius 2^999 and lines from x = 2^998 that cross it where t
    // overflows (v = (2^-40, 0, 1)), or where the point's z does (2^998 |t| 1.5 2^25 beyond
    // double's largest for the farther hit): the lanes keep such lines only if they refuse them
    // as assemble() does. The nearest of the reversed line is the near hit, whose point is finite.
    Cylinder wide{{0, 0, 0}, {0, 0, 0x1p999}, 0x1p999, false, false};
    const Vec3 directions[4] = {{1, 0, 0x1.8p25}, {-1, 0, -0x1.8p25}, {0x1p-40, 0, 1}, {1, 0, 1}};
    std::vector<double> soa[6];
    for (int i = 0; i < 16; ++i) {
        Vec3 L0{0x1p998, 0x1p990 * (i / 4), 0}, v = directions[i % 4];
        for (int a = 0; a < 3; ++a)
            soa[a].push_back(L0[a]), soa[3 + a].push_back(v[a]);
    }
    LineArrays lines = arrays_of(soa, Range::line);
    std::set<std::string> refused;
    int answered_nearest_not_all = 0;
    for (Lanes lanes : paths())
        for (Query q : {Query{}, Query{Need::all, false}, Query{Need::nearest, true},
                        Query{Need::nearest, false}, Query{Need::any, false}}) {
            Result got[16];
            stable::intersect(wide, lines, q, got, lanes);
            for (int i = 0; i < 16; ++i) {
                Line l{{soa[0][i], soa[1][i], soa[2][i]},
                       {soa[3][i], soa[4][i], soa[5][i]},
                       Range::line};
                Result want = stable::intersect(wide, l, q);
                INFO("lanes " << lanes_name(lanes) << " line " << i);
                REQUIRE(format_result("0", "", got[i], q.points) ==
                        format_result("0", "", want, q.points));
                if (!want.ok()) refused.insert(want.error_field);
                if (q.need == Need::nearest && q.points && want.ok() &&
                    !stable::intersect(wide, l, Query{}).ok())
                    ++answered_nearest_not_all;
            }
        }
    // The cases are what they claim: both refusals, and a nearest hit beside a refused farther one.
    CHECK(refused == std::set<std::string>{"p", "t"});
    CHECK(answered_nearest_not_all > 0);
}

#if defined(LINEQUAD_HAVE_AVX2_KERNELS)
namespace {

// The kernel on N lanes: correct_x4 or correct_x8.
template <int N, class S>
unsigned proven_lanes(const Prepared<S>& p, const double* const soa[6], Interval range, Query q) {
    detail::CorrectBlock<N> block;
    int orientation = detail::source(p).validity().orientation;
    if constexpr (N == 8)
        detail::correct_x8(p, orientation, soa, 0, range, q, block);
    else
        detail::correct_x4(p, orientation, soa, 0, range, q, block);
    return block.proven;
}

// Whether the scalar solver answers a line of moderate size from its first rung as given: the
// quick rung for a hit test (which correct::intersect tries first), the Newton rung otherwise,
// from its enclosures alone (a root its bounds leave next to an extent's end the scalar ladder
// places with exact signs, which the lanes leave to it).
template <class S>
bool rung_proves(const Prepared<S>& p, const Line& l, Query q) {
    using Traits = detail::ShapeTraits<S>;
    auto src = detail::source(p);
    detail::Unit unit{1, 1, l};
    Result r;
    if constexpr (detail::has_newton_form<S>) { // a hit test is the same rung, without points
        std::optional form = Traits::newton_form(src.shape, l);
        if (q.need == Need::any) q.points = false;
        return form && detail::surface_newton_rung<detail::Binary64>(*form, unit, l, q, r, nullptr);
    } else {
        int orientation = src.validity().orientation;
        if (q.need != Need::any)
            return detail::newton_rung<detail::Binary64>(
                Traits::line_form(src, l.L0, l.v, orientation), unit, l, q, r);
        return detail::hit_test_rung(Traits::quick_line_form(src, l.L0, l.v, orientation), unit, r);
    }
}

// Every family's cases in blocks of N lines against the block's first shape: each lane is
// proven exactly where the scalar solver answers from its first rung as given (a usual line of
// moderate size whose rung proves every decision and rounding). Returns {lanes, proven} for
// each kind of shape the lanes take.
template <int N>
std::map<int, std::pair<long, long>> lanes_against_scalar_rung() {
    std::map<int, std::pair<long, long>> by_shape;
    for (int shape_kind = 0; shape_kind < shape_kinds; ++shape_kind)
        for (int f = 0; f < family_count; ++f) {
            if (!family_applies(Family(f), shape_kind)) continue;
            for (Range range : {Range::line, Range::ray, Range::segment})
                for (std::uint64_t first = 0; first < 200; first += N) {
                    Case head = make_case(Family(f), shape_kind, range, 13, first);
                    std::vector<double> soa[6];
                    for (std::uint64_t i = first; i < first + N; ++i) {
                        Line l = make_case(Family(f), shape_kind, range, 13, i).line;
                        for (int a = 0; a < 3; ++a)
                            soa[a].push_back(l.L0[a]), soa[3 + a].push_back(l.v[a]);
                    }
                    const double* const arrays[6] = {soa[0].data(), soa[1].data(), soa[2].data(),
                                                     soa[3].data(), soa[4].data(), soa[5].data()};
                    std::visit(
                        [&](const auto& shape) {
                            using S = std::decay_t<decltype(shape)>;
                            if constexpr (detail::correct_in_lanes<S>) {
                                Prepared<S> p = prepare(shape);
                                if (!p.ok()) return;
                                for (Query q : {Query{}, Query{Need::nearest, false},
                                                Query{Need::any, false}}) {
                                    unsigned bits = proven_lanes<N>(p, arrays, head.line.range, q);
                                    for (int k = 0; k < N; ++k) {
                                        Line l{{soa[0][k], soa[1][k], soa[2][k]},
                                               {soa[3][k], soa[4][k], soa[5][k]},
                                               head.line.range};
                                        double extent = detail::scene_extent(detail::source(p), l);
                                        bool as_given = validate(p, l).code == ErrorCode::none &&
                                                        detail::moderate(extent, l);
                                        bool want = as_given && rung_proves(p, l, q);
                                        INFO(family_name(Family(f))
                                             << " shape " << shape_kind << " line " << first + k);
                                        REQUIRE(bool((bits >> k) & 1) == want);
                                        auto& [lanes, proven] = by_shape[shape_kind];
                                        ++lanes, proven += want;
                                    }
                                }
                            }
                        },
                        head.shape);
                }
        }
    return by_shape;
}

} // namespace

TEST_CASE("batch: correct's lanes prove exactly the lines the scalar first rung proves",
          "[batch]") {
    std::vector<std::map<int, std::pair<long, long>>> runs;
    if (batch_lanes() >= Lanes::avx2) runs.push_back(lanes_against_scalar_rung<4>());
#if defined(LINEQUAD_HAVE_AVX512_KERNELS)
    if (batch_lanes() >= Lanes::avx512) runs.push_back(lanes_against_scalar_rung<8>());
#endif
    for (const auto& by_shape : runs) {
        // Every shape but the capsule (made of patches: the scalar solver's).
        CHECK(by_shape.size() == std::size_t(shape_kinds - 1));
        for (auto [shape_kind, counts] : by_shape) {
            auto [lanes, proven] = counts;
            INFO("shape " << shape_kind << ": " << proven << " of " << lanes << " lanes proven");
            CHECK(lanes > 3000);
            // Most lines are proven on the first rung in every family (the README's rung
            // table): the lanes must do the work, not hand it back.
            CHECK(proven > lanes / 2);
        }
    }
}

// Steep lines beside a closed frustum's apex (beyond its top), parallel to the axis or nearly:
// one root on each nappe, both near the apex, and at the smallest offsets too near it for their
// R's signs, where root_on_nappe takes the nappe from R's rate along the line. The lanes must
// close each line on the solid's nappe as the scalar rung does, proving exactly what it proves.
TEST_CASE("batch: correct's lanes close steep lines beside a frustum's apex as the rung does",
          "[batch]") {
    if (batch_lanes() < Lanes::avx2) {
        WARN("this machine runs no AVX2 lanes");
        return;
    }
    const Frustum s{{0, 0, 0}, 1, {0, 0, 1}, 0.5, true, true}; // the apex at z = 2
    Prepared<Frustum> p = prepare(s);
    long lanes = 0, proven = 0;
    for (int k = 1; k <= 80; ++k)
        for (double tilt : {0.0, 0x1p-30, -0x1p-60}) {
            std::vector<double> soa[6];
            for (int lane = 0; lane < 4; ++lane) { // offsets 2^-k, 3 2^-k, ... around the axis
                double d = std::ldexp(1.0 + 2 * lane, -k);
                Line l{{lane % 2 ? d : -d, lane / 2 ? d : 0.5 * d, -3}, {tilt, 0, 1}};
                for (int a = 0; a < 3; ++a)
                    soa[a].push_back(l.L0[a]), soa[3 + a].push_back(l.v[a]);
            }
            const double* const arrays[6] = {soa[0].data(), soa[1].data(), soa[2].data(),
                                             soa[3].data(), soa[4].data(), soa[5].data()};
            for (Query q : {Query{}, Query{Need::nearest, false}, Query{Need::any, false}}) {
                unsigned bits = proven_lanes<4>(p, arrays, Range::line, q);
                for (int lane = 0; lane < 4; ++lane) {
                    Line l{{soa[0][lane], soa[1][lane], soa[2][lane]},
                           {soa[3][lane], soa[4][lane], soa[5][lane]}};
                    bool want = rung_proves(p, l, q);
                    INFO("k " << k << " tilt " << tilt << " lane " << lane);
                    REQUIRE(bool((bits >> lane) & 1) == want);
                    ++lanes, proven += want;
                }
            }
        }
    // The rung proves the nearest hit and the hit test of nearly every line down to offsets of
    // 2^-25 (600 lanes); nearer the apex its bounds no longer hold the two roots apart.
    INFO(proven << " of " << lanes << " lanes proven");
    CHECK(proven > 500);
}
#endif
