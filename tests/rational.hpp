// Exact rationals (GMP) for the tests that check floating-point values against exact ones.
#pragma once

#include <gmp.h>

namespace linequad::test {

// An mpq_t that frees itself, with the ring operations.
struct Q {
    mpq_t q;
    Q() { mpq_init(q); }
    explicit Q(double x) {
        mpq_init(q);
        mpq_set_d(q, x); // exact: every finite double is a rational
    }
    Q(const Q& o) {
        mpq_init(q);
        mpq_set(q, o.q);
    }
    Q& operator=(const Q& o) {
        mpq_set(q, o.q);
        return *this;
    }
    ~Q() { mpq_clear(q); }
};
inline Q operator+(const Q& a, const Q& b) {
    Q r;
    mpq_add(r.q, a.q, b.q);
    return r;
}
inline Q operator-(const Q& a, const Q& b) {
    Q r;
    mpq_sub(r.q, a.q, b.q);
    return r;
}
inline Q operator*(const Q& a, const Q& b) {
    Q r;
    mpq_mul(r.q, a.q, b.q);
    return r;
}

} // namespace linequad::test
