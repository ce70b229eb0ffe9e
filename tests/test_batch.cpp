// The batch solvers return the scalar solvers' results bit for bit, on every family's cases,
// bad lines and the lanes that fall back to the scalar solver included.
#include "support.hpp"

#include "linequad/batch.hpp"
#include "linequad/families.hpp"

#include <limits>
#include <vector>

using namespace linequad;
using namespace linequad::test;

namespace {
Result scalar(const Shape& s, const Line& l, Query q) {
    return std::visit([&](const auto& shape) { return stable::intersect(shape, l, q); }, s);
}
void batch(const Shape& s, const LineArrays& lines, Query q, Result* out) {
    std::visit([&](const auto& shape) { stable::intersect(shape, lines, q, out); }, s);
}
} // namespace

TEST_CASE("batch: stable equals the scalar solver bit for bit, for every shape", "[batch]") {
    INFO("AVX2 path: " << batch_uses_avx2());
    const double nan = std::numeric_limits<double>::quiet_NaN();
    std::size_t compared = 0;
    for (int shape_kind = 0; shape_kind < shape_kinds; ++shape_kind)
        for (int f = 0; f < family_count; ++f) {
            if (!family_applies(Family(f), shape_kind)) continue;
            for (Range range : {Range::line, Range::ray, Range::segment}) {
                std::vector<Case> cases;
                for (std::uint64_t i = 0; i < 400; ++i)
                    cases.push_back(make_case(Family(f), shape_kind, range, 11, i));
                for (std::size_t first = 0; first + 11 <= cases.size(); first += 11) {
                    // One shape, eleven lines (two full batches of four and a scalar tail).
                    const Shape& shape = cases[first].shape;
                    std::vector<double> soa[6];
                    for (std::size_t j = first; j < first + 11; ++j) {
                        Line l = cases[j].line;
                        if (j == first + 5) l.v = {0, 0, 0}; // bad lines go through too
                        if (j == first + 6) l.L0.y = nan;
                        for (int a = 0; a < 3; ++a)
                            soa[a].push_back(l.L0[a]), soa[3 + a].push_back(l.v[a]);
                    }
                    LineArrays lines{soa[0].data(),
                                     soa[1].data(),
                                     soa[2].data(),
                                     soa[3].data(),
                                     soa[4].data(),
                                     soa[5].data(),
                                     11,
                                     range};
                    for (Query q : {Query{}, Query{Need::nearest, false}}) {
                        std::vector<Result> got(11);
                        batch(shape, lines, q, got.data());
                        for (std::size_t j = 0; j < 11; ++j) {
                            Line l{{soa[0][j], soa[1][j], soa[2][j]},
                                   {soa[3][j], soa[4][j], soa[5][j]},
                                   range};
                            Result want = scalar(shape, l, q);
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
    CHECK(compared > 35000);
}
