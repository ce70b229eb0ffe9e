// libFuzzer target: every solver and the case parser, on inputs libFuzzer's own helpers never
// make (NaN, infinities, subnormals: the bytes are read as raw double bit patterns). The
// invariants are in src/invariants.cpp; an input that breaks one aborts with the case line, and
// belongs in tests/fuzz_regressions.jsonl once fixed.
#include "io/shape_types.hpp"
#include "linequad/case_io.hpp"
#include "linequad/invariants.hpp"

#include <array>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <type_traits>

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

// A field's coordinates from the next bytes.
void take_into(double& x, const std::uint8_t*& p, const std::uint8_t* end) {
    x = take(p, end);
}
void take_into(Vec3& x, const std::uint8_t*& p, const std::uint8_t* end) {
    x.x = take(p, end), x.y = take(p, end), x.z = take(p, end);
}
void take_into(std::array<double, 10>& q, const std::uint8_t*& p, const std::uint8_t* end) {
    for (double& x : q)
        x = take(p, end);
}

// The shape of kind `kind` (its index in Shape), its fields from the bytes in the case format's
// order: every shape is fuzzed, the ones added later too.
// Options, for the shapes that have them: finite, caps (refused when not finite), the cone's
// nappes; coincident (a plane's, a quadric's) from the caps bit.
struct Options {
    bool finite, caps;
    int nappes;
};
Shape take_shape(std::size_t kind, Options o, const std::uint8_t*& p, const std::uint8_t* end) {
    return with_shape_type(kind, [&](auto tag) -> Shape {
        using S = typename decltype(tag)::type;
        S s{};
        detail::for_each_field<S>([&](const auto& f) { take_into(s.*f.member, p, end); });
        if constexpr (has_extent_options<S>) s.finite = o.finite, s.caps = o.caps;
        if constexpr (has_nappes<S>) s.nappes = o.nappes;
        if constexpr (has_coincident<S>) s.coincident = o.caps;
        return s;
    });
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
    Options o{(data[0] & 4) != 0, (data[0] & 0x80) != 0, data[0] & 0x40 ? 2 : 1};
    c.shape = take_shape(data[0] % shape_count, o, p, end);
    Vec3 L0, v;
    take_into(L0, p, end), take_into(v, p, end);
    c.line = {L0, v, Range((data[0] >> 3) % 3)};
    check(c);
    return 0;
}
