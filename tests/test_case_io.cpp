// The case and result formats: exact round trips, and errors that name the line's field.
#include "support.hpp"

#include <limits>

#include <cstring>
#include <random>

using namespace linequad;
using namespace linequad::test;

TEST_CASE("case format: numbers as hex floats / decimals and special values", "[case_io]") {
    Case c;
    std::string why;
    REQUIRE(parse_case(
        R"({"id":7,"shape":"cylinder","C":["0x1.8p+1",0.1,"-2e3"],"H":[0,0,"1"],)"
        R"("r":"0x1p-1074","L0":["inf","-inf","nan"],"v":[1,0,0],"range":"ray","finite":false})",
        &c, &why));
    const auto& cyl = std::get<Cylinder>(c.shape);
    CHECK(c.id == "7");
    CHECK(cyl.C.x == 3.0);
    CHECK(cyl.C.y == 0.1); // the decimal, rounded once
    CHECK(cyl.C.z == -2000);
    CHECK(cyl.r == 0x1p-1074);
    CHECK(std::isinf(c.line.L0.x));
    CHECK(std::isnan(c.line.L0.z));
    CHECK(c.line.range == Range::ray);
    CHECK_FALSE(cyl.finite);
}

TEST_CASE("case format: every double round-trips exactly", "[case_io]") {
    std::mt19937_64 rng(42);
    for (int i = 0; i < 2000; ++i) {
        auto any_double = [&] {
            for (;;) {
                std::uint64_t bits = rng();
                double x;
                std::memcpy(&x, &bits, sizeof x);
                if (!std::isnan(x)) return x;
            }
        };
        Case c;
        c.id = "\"r" + std::to_string(i) + "\"";
        c.shape = EllipticCone{{any_double(), any_double(), any_double()},
                               {any_double(), -0.0, 0x1p-1074},
                               {any_double(), any_double(), any_double()},
                               {any_double(), any_double(), any_double()},
                               i % 2 == 0};
        c.line = {{any_double(), any_double(), any_double()}, {any_double(), 1, 2}, Range::segment};
        std::string text = format_case(c), why;
        Case back;
        REQUIRE(parse_case(text, &back, &why));
        CHECK(format_case(back) == text);
        const auto& s = std::get<EllipticCone>(back.shape);
        CHECK(std::signbit(s.H.y)); // -0 survives
        CHECK(s.a == std::get<EllipticCone>(c.shape).a);
    }
}

TEST_CASE("result format round trip", "[case_io]") {
    Result r;
    r.count = 4;
    const double no_bound = std::numeric_limits<double>::quiet_NaN();
    r.hits[0] = {-0x1.23456789abcdep-3, {1, 2, 0x1p-1074}, no_bound,
                 HitKind::tangent,      Part::lateral,     false};
    r.hits[1] = {1e300, {-0.0, 4, 5}, no_bound, HitKind::cross, Part::base, false};
    r.hits[2] = {1e301, {1, 4, 5}, no_bound, HitKind::tangent, Part::lateral, false};
    r.hits[3] = {1e302, {2, 4, 5}, no_bound, HitKind::cross, Part::top, false};
    std::string line = format_result("\"x\"", "stable", r), why;
    ParsedResult back;
    REQUIRE(parse_result(line, &back, &why));
    CHECK(back.id == "\"x\"");
    CHECK(back.solver == "stable");
    REQUIRE(back.result.count == 4);
    CHECK(back.result.hits[1].part == Part::base);
    CHECK(back.result.hits[3].part == Part::top);
    CHECK(back.result.hits[0].t == r.hits[0].t);
    CHECK(back.result.hits[0].kind == HitKind::tangent);
    CHECK(back.result.hits[0].p == r.hits[0].p);
    CHECK(format_result("\"x\"", "stable", back.result) == line);

    Result on;
    on.on_surface = true;
    on.s0 = -INFINITY, on.s1 = 2.5;
    line = format_result("1", "exact", on);
    CHECK(
        line ==
        R"({"id":1,"solver":"exact","hits":[],"on_surface":[null,"0x1.4p+1"],"surface_part":"lateral"})");
    REQUIRE(parse_result(line, &back, &why));
    CHECK(back.result.on_surface);
    CHECK(back.result.s0 == -INFINITY);
    CHECK(back.result.s1 == 2.5);

    // Another library's own error code is kept by its name, and writes back under it.
    line = R"({"id":2,"solver":"ode","error":"cannot","code":"unrepresented"})";
    REQUIRE(parse_result(line, &back, &why));
    CHECK(back.result.error_code == ErrorCode::foreign);
    std::string once = format_result("2", "ode", back.result);
    CHECK(once.find(R"("code":"unrepresented")") != std::string::npos);
    REQUIRE(parse_result(once, &back, &why));
    CHECK(format_result("2", "ode", back.result) == once);
}

TEST_CASE("case format: malformed lines name the field", "[case_io]") {
    struct Bad {
        const char* line;
        const char* says;
    } bad[] = {
        {R"({"id":1,"shape":"cylinder","C":[0,0,0],"H":[0,0,1],"L0":[0,0,0],"v":[1,0,0]})",
         "field \"r\": missing"},
        {R"({"id":1,"shape":"torus"})", "field \"shape\""},
        {R"({"id":1,"shape":"cylinder","C":[0,0],"H":[0,0,1],"r":1,"L0":[0,0,0],"v":[1,0,0]})",
         "field \"C\""},
        {R"({"id":1,"shape":"cylinder","C":[0,0,"x"],"H":[0,0,1],"r":1,"L0":[0,0,0],"v":[1,0,0]})",
         "field \"C\""},
        {R"({"id":1,"shape":"cylinder","C":[0,0,0],"H":[0,0,1],"r":1,"L0":[0,0,0],"v":[1,0,0],"a":[1,0,0]})",
         "field \"a\""},
        {R"({"id":1,"shape":"cylinder","C":[0,0,0],"H":[0,0,1],"r":1,"L0":[0,0,0],"v":[1,0,0],"range":"beam"})",
         "field \"range\""},
        {R"({"id":1,"shape":"cylinder","C":[0,0,0],"H":[0,0,1],"r":1,"L0":[0,0,0],"v":[1,0,0],"finite":1})",
         "field \"finite\""},
        {R"({"id":1,"shape":"cylinder",)", "not valid JSON"},
        {R"([1,2,3])", "not a JSON object"},
        {R"({"id":1,"id":2})", "the field \"id\" appears twice"},
        {R"({"id":1,"shape":"cylinder","C":[0,0,"0x1p+"],"H":[0,0,1],"r":1,"L0":[0,0,0],"v":[1,0,0]})",
         "field \"C\""},
    };
    for (const Bad& b : bad) {
        Case c;
        std::string why;
        INFO(b.line);
        CHECK_FALSE(parse_case(b.line, &c, &why));
        CHECK_THAT(why, Catch::Contains(b.says));
    }
    // The id is kept even when the rest is wrong, so the error result can carry it.
    Case c;
    std::string why;
    CHECK_FALSE(parse_case(R"({"id":"keep","shape":"cone"})", &c, &why));
    CHECK(c.id == "\"keep\"");
    // A deeply nested line is refused, not a stack overflow.
    std::string deep = "{\"id\":" + std::string(100000, '[') + "}";
    CHECK_FALSE(parse_case(deep, &c, &why));
}
