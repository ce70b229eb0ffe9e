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
    mpq_init(D_);
    for (Mag* m : {&sqrtD_, &t1_, &t2_, &t3_, &t4_}) mpfr_inits2(first_precision, m->lo, m->hi, (mpfr_ptr)0);
    for (Value& v : values_) mpq_inits(v.num, v.X, v.Y, v.Den, (mpq_ptr)0);
    prec_ = first_precision;
}

SurdRounder::~SurdRounder() {
    mpq_clear(D_);
    for (Mag* m : {&sqrtD_, &t1_, &t2_, &t3_, &t4_}) mpfr_clears(m->lo, m->hi, (mpfr_ptr)0);
    for (Value& v : values_) mpq_clears(v.num, v.X, v.Y, v.Den, (mpq_ptr)0);
}

void SurdRounder::reset(mpq_srcptr D) {
    mpq_set(D_, D);
    sign_D_ = mpq_sgn(D);
    used_ = 0;
}

int SurdRounder::add(mpq_srcptr X, mpq_srcptr Y, mpq_srcptr Den) {
    if (used_ == capacity) throw std::logic_error("SurdRounder: too many values");
    Value& v = values_[used_];
    v.done = false;
    int sx = mpq_sgn(X), sy = Y ? mpq_sgn(Y) : 0;
    if (sy == 0 || sign_D_ == 0) {
        v.form = 0; // rational: exact division once
        mpq_div(v.num, X, Den);
    } else if (sx * sy >= 0) {
        v.form = 1; // X and Y sqrt(D) have one sign: the sum has no cancellation
        mpq_set(v.X, X), mpq_set(v.Y, Y), mpq_set(v.Den, Den);
    } else {
        v.form = 2; // opposite signs: multiply by the conjugate, X - Y sqrt(D) has no cancellation
        mpq_set(v.X, X), mpq_set(v.Y, Y), mpq_set(v.Den, Den);
        mpq_t y2d;
        mpq_init(y2d);
        mpq_mul(y2d, Y, Y);
        mpq_mul(y2d, y2d, D_);
        mpq_mul(v.num, X, X);
        mpq_sub(v.num, v.num, y2d);
        mpq_clear(y2d);
    }
    return int(used_++);
}

void SurdRounder::set_precision(mpfr_prec_t p) {
    prec_ = p;
    for (Mag* m : {&sqrtD_, &t1_, &t2_, &t3_, &t4_}) {
        mpfr_set_prec(m->lo, p);
        mpfr_set_prec(m->hi, p);
    }
}

void SurdRounder::set_q(Mag& m, mpq_srcptr q) {
    m.sign = mpq_sgn(q);
    // For a negative q, rounding up gives the smaller magnitude.
    mpfr_set_q(m.lo, q, m.sign >= 0 ? MPFR_RNDD : MPFR_RNDU);
    mpfr_set_q(m.hi, q, m.sign >= 0 ? MPFR_RNDU : MPFR_RNDD);
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

// Encloses the value at the current precision; true when both ends round to one double (then
// so does the value between them: rounding is monotonic). mpfr_get_d rounds correctly in the
// whole double range, subnormals and overflow to infinity included.
bool SurdRounder::try_round(Value& v) {
    Mag* r = &t1_;
    if (v.form == 0) {
        set_q(t1_, v.num);
    } else {
        set_q(t2_, v.Y);
        mul(t3_, t2_, sqrtD_); // Y sqrt(D)
        set_q(t2_, v.X);
        if (v.form == 1) {
            add_same_sign(t4_, t2_, t3_);
            set_q(t2_, v.Den);
            div(t1_, t4_, t2_);
        } else {
            t3_.sign = -t3_.sign; // - Y sqrt(D), of the sign of X
            add_same_sign(t4_, t2_, t3_);
            set_q(t2_, v.Den);
            mul(t3_, t4_, t2_);
            set_q(t2_, v.num);
            div(t1_, t2_, t3_);
        }
    }
    if (r->sign == 0) {
        v.out = 0.0;
        return true;
    }
    double lo = mpfr_get_d(r->lo, MPFR_RNDN), hi = mpfr_get_d(r->hi, MPFR_RNDN);
    if (lo != hi) return false;
    v.out = r->sign > 0 ? lo : -lo;
    return true;
}

void SurdRounder::run() {
    RoundingStats& stats = rounding_stats();
    set_precision(first_precision);
    int step = 1;
    for (std::size_t left = used_;; ++step) {
        if (sign_D_ > 0) {
            Mag d;
            d.sign = 1;
            mpfr_inits2(prec_, d.lo, d.hi, (mpfr_ptr)0);
            set_q(d, D_);
            sqrtD_.sign = 1;
            mpfr_sqrt(sqrtD_.lo, d.lo, MPFR_RNDD);
            mpfr_sqrt(sqrtD_.hi, d.hi, MPFR_RNDU);
            mpfr_clears(d.lo, d.hi, (mpfr_ptr)0);
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

double round_surd(const char* X, const char* Y, const char* D, const char* Den) {
    mpq_t x, y, d, den;
    mpq_inits(x, y, d, den, (mpq_ptr)0);
    mpq_set_str(x, X, 10), mpq_set_str(y, Y, 10), mpq_set_str(d, D, 10), mpq_set_str(den, Den, 10);
    mpq_canonicalize(x), mpq_canonicalize(y), mpq_canonicalize(d), mpq_canonicalize(den);
    SurdRounder r;
    r.reset(d);
    r.add(x, y, den);
    r.run();
    double out = r.result(0);
    mpq_clears(x, y, d, den, (mpq_ptr)0);
    return out;
}

} // namespace linequad::exact
