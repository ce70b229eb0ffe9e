// The batch solvers return the scalar solvers' results bit for bit, on every family's cases,
// bad lines and the lanes that fall back to the scalar solver included, on every path this
// machine runs: stable in eight (AVX-512) or four (AVX2) double lanes, stable32 in eight float
// lanes, and the scalar loop.
#include "support.hpp"

#include "linequad/batch.hpp"
#include "linequad/families.hpp"

#include <limits>
#include <type_traits>
#include <vector>

using namespace linequad;
using namespace linequad::test;

namespace {

template <class R>
Result scalar(const Shape& s, const Line& l, Query q) {
    return std::visit(
        [&](const auto& shape) {
            if constexpr (std::is_same_v<R, float>)
                return stable32::intersect(shape, l, q);
            else
                return stable::intersect(shape, l, q);
        },
        s);
}
template <class R>
void batch(const Shape& s, const LineArraysT<R>& lines, Query q, Result* out, Lanes lanes) {
    std::visit(
        [&](const auto& shape) {
            if constexpr (std::is_same_v<R, float>)
                stable32::intersect(shape, lines, q, out, lanes);
            else
                stable::intersect(shape, lines, q, out, lanes);
        },
        s);
}

// Every family's cases in R's precision, one shape against `per_shape` lines: two full batches
// and a scalar tail, with a zero direction and a NaN among them. Returns the lines compared.
template <class R>
std::size_t compare_with_scalar(std::size_t per_shape, Lanes lanes) {
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
                    LineArraysT<R> lines{soa[0].data(), soa[1].data(),          soa[2].data(),
                                         soa[3].data(), soa[4].data(),          soa[5].data(),
                                         per_shape,     cases[first].line.range};
                    for (Query q :
                         {Query{}, Query{Need::nearest, false}, Query{Need::any, false}}) {
                        std::vector<Result> got(per_shape);
                        batch(shape, lines, q, got.data(), lanes);
                        for (std::size_t j = 0; j < per_shape; ++j) {
                            Line l{{soa[0][j], soa[1][j], soa[2][j]},
                                   {soa[3][j], soa[4][j], soa[5][j]},
                                   lines.range};
                            Result want = scalar<R>(shape, l, q);
                            INFO(family_name(Family(f))
                                 << " shape " << shape_kind << " line " << j);
                            REQUIRE(format_result("0", "", got[j], q.points) ==
                                    format_result("0", "", want, q.points));
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
        CHECK(compare_with_scalar<double>(19, lanes) > 35000);
    }
}

TEST_CASE("batch: stable32 equals the scalar solver bit for bit, for every shape and path",
          "[batch]") {
    for (Lanes lanes : paths()) {
        INFO("lanes: " << lanes_name(lanes));
        CHECK(compare_with_scalar<float>(19, lanes) > 35000);
    }
}
