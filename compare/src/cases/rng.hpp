// The families' random numbers: SplitMix64 streams, and exact constructions on integers.
#pragma once

#include "linequad/vec3.hpp"

#include <cmath>
#include <cstdint>
#include <random>
#include <utility>

namespace linequad {

inline std::uint64_t splitmix(std::uint64_t x) {
    x += 0x9e3779b97f4a7c15ull;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
    return x ^ (x >> 31);
}

// SplitMix64 (Steele, Lea and Flood) as a generator: a counter passed through splitmix. A case's
// stream starts from one hash of (family, shape, range, seed, index), so that every case is a
// pure function of them and costs no seeding (a Mersenne Twister's 312-word state, filled per
// case, had been half of case generation).
struct SplitMix64 {
    using result_type = std::uint64_t;
    std::uint64_t state;
    static constexpr result_type min() { return 0; }
    static constexpr result_type max() { return ~result_type(0); }
    result_type operator()() {
        result_type x = splitmix(state);
        state += 0x9e3779b97f4a7c15ull;
        return x;
    }
};

struct Rng {
    SplitMix64 g;
    double real(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(g); }
    int integer(int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(g); }
    bool coin() { return g() & 1; }
    Vec3 vec(double s) { return {real(-s, s), real(-s, s), real(-s, s)}; }
    Vec3 ivec(int s) {
        return {double(integer(-s, s)), double(integer(-s, s)), double(integer(-s, s))};
    }
    double dyadic(int bits) {
        return std::ldexp(double(integer(0, (1 << bits) - 1)), -bits);
    } // [0, 1)
};

// One of the four exact quarter turns: (cos, sin) of 0, 90, 180, 270 degrees.
inline std::pair<double, double> quarter(Rng& r) {
    static const double c[4] = {1, 0, -1, 0};
    int q = r.integer(0, 3);
    return {c[q], c[(q + 3) % 4]};
}

// The rotation of an integer quaternion q times N = |q|^2: an integer matrix whose columns are
// orthogonal and of length N, so that dyadic multiples of them stay exact.
struct IntegerRotation {
    Vec3 col[3];
    double N;
};

inline IntegerRotation integer_rotation(Rng& r) {
    double q[4];
    do {
        for (double& x : q)
            x = r.integer(-2, 2);
    } while (q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3] == 0);
    auto [w, x, y, z] = q;
    return {{{w * w + x * x - y * y - z * z, 2 * (x * y + w * z), 2 * (x * z - w * y)},
             {2 * (x * y - w * z), w * w - x * x + y * y - z * z, 2 * (y * z + w * x)},
             {2 * (x * z + w * y), 2 * (y * z - w * x), w * w - x * x - y * y + z * z}},
            w * w + x * x + y * y + z * z};
}

} // namespace linequad
