// libFuzzer target: every solver and the case parser, on inputs libFuzzer's own helpers never
// make (NaN, infinities, subnormals: the bytes are read as raw double bit patterns). The
// invariants are in src/invariants.cpp; an input that breaks one aborts with the case line, and
// belongs in tests/fuzz_regressions.jsonl once fixed.
#include "linequad/case_io.hpp"
#include "linequad/invariants.hpp"

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

using namespace linequad;

namespace {

void check(const Case& c) {
    std::string broken = broken_invariant(c);
    if (broken.empty()) return;
    std::fprintf(stderr, "invariant broken: %s\n", broken.c_str());
    std::abort();
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
