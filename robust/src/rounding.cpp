#include "rounding.hpp"

#include "linequad/exact.hpp"

#include <stdexcept>

namespace linequad::exact {

namespace {
constexpr mpfr_prec_t first_precision = 64;
constexpr mpfr_prec_t last_precision = 1 << 20; // never reached: a guard against a bug, not a limit
} // namespace

RoundingStats& rounding_stats() {
    thread_local RoundingStats stats;
    return stats;
}

SurdRounder::SurdRounder() {
    for (Mag* m : {&sqrtD_, &t1_, &t2_, &t3_, &t4_})
        mpfr_inits2(first_precision, m->lo, m->hi, (mpfr_ptr)0);
    prec_ = first_precision;
}

SurdRounder::~SurdRounder() {
    for (Mag* m : {&sqrtD_, &t1_, &t2_, &t3_, &t4_})
        mpfr_clears(m->lo, m->hi, (mpfr_ptr)0);
}

SurdRounder::Value& SurdRounder::next() {
    if (used_ == capacity) throw std::logic_error("SurdRounder: too many values");
    Value& v = values_[used_++];
    v.done = false;
    return v;
}

void SurdRounder::set_precision(mpfr_prec_t p) {
    prec_ = p;
    for (Mag* m : {&sqrtD_, &t1_, &t2_, &t3_, &t4_}) {
        mpfr_set_prec(m->lo, p);
        mpfr_set_prec(m->hi, p);
    }
}

void SurdRounder::set(Mag& m, const Dyadic& d) {
    m.sign = d.sign();
    // For a negative value, rounding up gives the smaller magnitude.
    mpfr_set_z_2exp(m.lo, d.m, d.e, m.sign >= 0 ? MPFR_RNDD : MPFR_RNDU);
    mpfr_set_z_2exp(m.hi, d.m, d.e, m.sign >= 0 ? MPFR_RNDU : MPFR_RNDD);
    mpfr_abs(m.lo, m.lo, MPFR_RNDN); // exact
    mpfr_abs(m.hi, m.hi, MPFR_RNDN);
}

void SurdRounder::mul(Mag& r, const Mag& a, const Mag& b) {
    r.sign = a.sign * b.sign;
    mpfr_mul(r.lo, a.lo, b.lo, MPFR_RNDD);
    mpfr_mul(r.hi, a.hi, b.hi, MPFR_RNDU);
}

void SurdRounder::div(Mag& r, const Mag& a, const Mag& b) {
    r.sign = a.sign * b.sign;
    mpfr_div(r.lo, a.lo, b.hi, MPFR_RNDD);
    mpfr_div(r.hi, a.hi, b.lo, MPFR_RNDU);
}

void SurdRounder::add_same_sign(Mag& r, const Mag& a, const Mag& b) {
    r.sign = a.sign != 0 ? a.sign : b.sign;
    mpfr_add(r.lo, a.lo, b.lo, MPFR_RNDD);
    mpfr_add(r.hi, a.hi, b.hi, MPFR_RNDU);
}

// Encloses the value at the current precision; true when both ends round to one double (or
// float; then so does the value between them: rounding to nearest is monotonic). mpfr_get_d and
// mpfr_get_flt round correctly over their format's whole range, subnormals and overflow to
// infinity included, each straight from the enclosure (a float is never the rounding of a
// rounded double).
bool SurdRounder::try_round(Value& v) {
    switch (v.form) {
    case Form::rational:
        set(t2_, v.X), set(t3_, v.Den);
        div(t1_, t2_, t3_);
        break;
    case Form::sum:
        set(t2_, v.Y);
        mul(t3_, t2_, sqrtD_);
        set(t2_, v.X);
        add_same_sign(t4_, t2_, t3_);
        set(t2_, v.Den);
        div(t1_, t4_, t2_);
        break;
    case Form::conjugate:
        set(t2_, v.Y);
        mul(t3_, t2_, sqrtD_);
        t3_.sign = -t3_.sign; // -Y sqrt(D), of the sign of X
        set(t2_, v.X);
        add_same_sign(t4_, t2_, t3_);
        set(t2_, v.Den);
        mul(t3_, t4_, t2_);
        set(t2_, v.N2);
        div(t1_, t2_, t3_);
        break;
    }
    if (t1_.sign == 0) {
        v.out = 0.0;
        return true;
    }
    auto get = [&](mpfr_srcptr x) -> double {
        return target_ == Precision::binary32 ? mpfr_get_flt(x, MPFR_RNDN)
                                              : mpfr_get_d(x, MPFR_RNDN);
    };
    double lo = get(t1_.lo), hi = get(t1_.hi);
    if (lo != hi) return false;
    v.out = t1_.sign > 0 ? lo : -lo;
    return true;
}

void SurdRounder::run(Precision target) {
    target_ = target;
    RoundingStats& stats = rounding_stats();
    if (prec_ != first_precision) set_precision(first_precision);
    std::size_t left = used_;
    for (int step = 1;; ++step) {
        if (D_.sign() > 0) {
            set(t4_, D_);
            sqrtD_.sign = 1;
            mpfr_sqrt(sqrtD_.lo, t4_.lo, MPFR_RNDD);
            mpfr_sqrt(sqrtD_.hi, t4_.hi, MPFR_RNDU);
        }
        for (std::size_t i = 0; i < used_; ++i) {
            Value& v = values_[i];
            if (v.done || !try_round(v)) continue;
            v.done = true;
            --left;
            ++stats.values;
            ++stats.by_steps[step < 8 ? step - 1 : 7];
            if (step > stats.max_steps) stats.max_steps = step;
        }
        if (left == 0) return;
        if (prec_ >= last_precision) throw std::runtime_error("SurdRounder: precision exhausted");
        set_precision(prec_ * 2);
    }
}

} // namespace linequad::exact
