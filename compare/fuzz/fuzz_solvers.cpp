// libFuzzer target: every solver and the case parser, on inputs libFuzzer's own helpers never
// make (NaN, infinities, subnormals: the bytes are read as raw double bit patterns).
//
// Invariants checked on every input, for every solver:
//  - the verdict on bad input equals the oracle's (validation is shared and exact); a fast
//    solver may refuse more (out_of_range) but never accept what the oracle refuses;
//  - a result has at most two hits, sorted by t, each t and point finite (the oracle may give
//    +-inf, the correct rounding of a root beyond double's range; never NaN), each t inside the
//    range; an on-surface interval is ordered and inside the range;
//  - the oracle itself obeys the same, and its Mpzf and Gmpq kernels agree bit for bit;
//  - when the oracle says no hit and no interval, no solver reports an on-surface interval.
#include "linequad/case_io.hpp"
#include "linequad/exact.hpp"
#include "linequad/registry.hpp"

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <string>

using namespace linequad;

namespace {

void require(bool ok, const char* what, const Case& c, const std::string& solver, const Result& r) {
    if (ok) return;
    std::fprintf(stderr, "invariant broken: %s\nsolver %s\ncase %s\nresult %s\n", what,
                 solver.c_str(), format_case(c).c_str(), format_result(c.id, solver, r).c_str());
    std::abort();
}

bool in_range(double t, Range r) {
    return r == Range::line || (t >= 0 && (r == Range::ray || t <= 1));
}

void check_shape(const Case& c, const std::string& name, const Result& r) {
    if (!r.ok()) return;
    require(r.count >= 0 && r.count <= 2, "at most two hits", c, name, r);
    require(!(r.on_surface && r.count), "hits or an interval, not both", c, name, r);
    bool oracle = name == "exact";
    for (int i = 0; i < r.count; ++i) {
        const Hit& h = r.hits[i];
        require(oracle ? !std::isnan(h.t) : std::isfinite(h.t), "finite t", c, name, r);
        require(in_range(h.t, c.line.range), "t inside the range", c, name, r);
        bool nan_p = std::isnan(h.p.x) || std::isnan(h.p.y) || std::isnan(h.p.z);
        require(oracle ? !nan_p : is_finite(h.p), "finite point", c, name, r);
    }
    require(r.count < 2 || r.hits[0].t <= r.hits[1].t, "hits sorted by t", c, name, r);
    if (r.on_surface) {
        require(!std::isnan(r.s0) && !std::isnan(r.s1) && r.s0 <= r.s1, "ordered interval", c, name,
                r);
        require(c.line.range == Range::line || r.s0 >= 0, "interval inside the range", c, name, r);
        require(c.line.range != Range::segment || r.s1 <= 1, "interval inside the segment", c, name,
                r);
    }
}

void check(const Case& c) {
    Result oracle = exact::intersect(c.shape, c.line);
    check_shape(c, "exact", oracle);
    Result gmpq = exact::intersect_gmpq(c.shape, c.line);
    require(format_result(c.id, "", gmpq) == format_result(c.id, "", oracle), "Mpzf and Gmpq agree",
            c, "exact_gmpq", gmpq);
    for (const Solver& s : all_solvers()) {
        std::string name(s.name);
        Result r = s(c.shape, c.line);
        check_shape(c, name, r);
        if (!oracle.ok()) {
            require(!r.ok() && r.error.code == oracle.error.code, "same verdict on bad input", c,
                    name, r);
        } else if (!r.ok()) {
            require(r.error.code == ErrorCode::out_of_range, "refuses only what double cannot hold",
                    c, name, r);
        } else if (!oracle.any_hit()) {
            require(!r.on_surface, "no invented on-surface interval", c, name, r);
        }
    }
}

double take(const std::uint8_t*& p, const std::uint8_t* end) {
    std::uint64_t bits = 0;
    std::size_t n = std::min<std::size_t>(8, std::size_t(end - p));
    std::memcpy(&bits, p, n);
    p += n;
    double x;
    std::memcpy(&x, &bits, sizeof x);
    return x;
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    if (size == 0) return 0;
    if (data[0] == '{') { // a case line for the parser
        Case c;
        std::string why;
        if (parse_case(std::string_view(reinterpret_cast<const char*>(data), size), &c, &why))
            check(c);
        return 0;
    }
    const std::uint8_t *p = data + 1, *end = data + size;
    Case c;
    c.id = "\"fuzz\"";
    bool finite = data[0] & 4;
    Vec3 v[6];
    for (Vec3& x : v)
        x = {take(p, end), take(p, end), take(p, end)};
    double r = take(p, end);
    switch (data[0] % 3) {
    case 0:
        c.shape = Cylinder{v[0], v[1], r, finite};
        break;
    case 1:
        c.shape = EllipticCylinder{v[0], v[1], v[2], v[3], finite};
        break;
    default:
        c.shape = EllipticCone{v[0], v[1], v[2], v[3], finite};
        break;
    }
    c.line = {v[4], v[5], Range((data[0] >> 3) % 3)};
    check(c);
    return 0;
}
