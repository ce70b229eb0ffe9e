// Every input the fuzzer has broken an invariant with, replayed: each bug it found stays fixed.
#include "support.hpp"

#include "linequad/families.hpp"

#include "linequad/invariants.hpp"

#include <fstream>

using namespace linequad;

TEST_CASE("fuzz regressions: every invariant holds on the inputs that once broke one", "[fuzz]") {
    std::ifstream in(LINEQUAD_FUZZ_REGRESSIONS);
    REQUIRE(in);
    std::string line, why;
    int n = 0;
    while (std::getline(in, line)) {
        Case c;
        REQUIRE(parse_case(line, &c, &why));
        INFO(c.id);
        CHECK(broken_invariant(c) == "");
        ++n;
    }
    CHECK(n >= 5);
}

TEST_CASE("invariants: generated cases of every family keep them", "[fuzz]") {
    for (int f = 0; f < family_count; ++f)
        for (int shape = 0; shape < test::shape_kinds; ++shape)
            if (family_applies(Family(f), shape))
                for (std::uint64_t i = 0; i < 40; ++i) {
                    Case c = make_case(Family(f), shape, Range(i % 3), 17, i);
                    INFO(format_case(c));
                    REQUIRE(broken_invariant(c) == "");
                }
}
