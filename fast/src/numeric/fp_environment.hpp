// The floating-point environment linequad's arithmetic is proven in: round to nearest, subnormals
// kept (neither flush-to-zero nor denormals-are-zero), every exception masked. A caller, or code
// it ran before (a library built with -ffast-math sets FTZ and DAZ at load; a plugin may leave the
// rounding mode upward), may leave another, and every error-free transform, bound and correctly
// rounded answer would then be silently wrong. Each entry point holds a StandardEnvironment for
// its call: one read of the control register when the environment is already standard, and the
// caller's own put back afterwards when it was not.
#pragma once

#include <cstdint>
#include <string>

#if defined(__x86_64__) || defined(__i386__)
#define LINEQUAD_X86_FP 1
#else
#include <cfenv>
#endif

namespace linequad::numeric {

// The controls of the environment, without its sticky status flags.
struct FpState {
    std::uint32_t simd = 0; // x86: MXCSR's controls (rounding, FTZ, DAZ, exception masks)
    std::uint16_t x87 = 0;  // x86: the x87 control word (long double's rounding and precision)
    bool operator==(const FpState& o) const { return simd == o.simd && x87 == o.x87; }
    bool operator!=(const FpState& o) const { return !(*this == o); }
};

#ifdef LINEQUAD_X86_FP
// MXCSR: bits 0-5 are sticky flags (not controls), 6 DAZ, 7-12 exception masks, 13-14 rounding,
// 15 FTZ. The standard value is every exception masked, round to nearest: 0x1F80. The x87
// control word's standard value on x86-64 Linux is 0x037F (masked, 64-bit significands, nearest).
inline constexpr std::uint32_t mxcsr_flags = 0x3F;
inline constexpr FpState standard_fp_state{0x1F80, 0x037F};

inline std::uint32_t read_mxcsr() {
    return __builtin_ia32_stmxcsr() & ~mxcsr_flags;
}
inline void write_mxcsr(std::uint32_t controls) {
    // Keeps the flags the code before raised, so that the caller finds them as it left them.
    __builtin_ia32_ldmxcsr(controls | (__builtin_ia32_stmxcsr() & mxcsr_flags));
}
inline std::uint16_t read_x87() {
    std::uint16_t cw;
    __asm__ volatile("fnstcw %0" : "=m"(cw));
    return cw;
}
inline void write_x87(std::uint16_t cw) {
    __asm__ volatile("fldcw %0" : : "m"(cw));
}
inline FpState fp_state() {
    return {read_mxcsr(), read_x87()};
}
inline void set_fp_state(FpState s) {
    write_mxcsr(s.simd);
    write_x87(s.x87);
}
#else
// Elsewhere the rounding mode is the one control the standard library names portably.
inline constexpr FpState standard_fp_state{FE_TONEAREST, 0};
inline FpState fp_state() {
    return {std::uint32_t(std::fegetround()), 0};
}
inline void set_fp_state(FpState s) {
    std::fesetround(int(s.simd));
}
#endif

// Puts the standard environment in place for its lifetime when the caller's differs in what
// double arithmetic uses (on x86-64, MXCSR; with x87 set, the x87 control word too, for code that
// may reach long double, as the oracle's libraries may), and the caller's back after. Cheap when
// it is standard already: a read of the register and a predictable branch.
template <bool x87 = false>
class StandardEnvironmentT {
  public:
    StandardEnvironmentT() {
#ifdef LINEQUAD_X86_FP
        FpState now{read_mxcsr(), x87 ? read_x87() : standard_fp_state.x87};
        if (__builtin_expect(now != standard_fp_state, 0)) {
            caller_ = now;
            write_mxcsr(standard_fp_state.simd);
            if (x87) write_x87(standard_fp_state.x87);
            changed_ = true;
        }
#else
        FpState now = fp_state();
        if (now != standard_fp_state)
            caller_ = now, set_fp_state(standard_fp_state), changed_ = true;
#endif
    }
    ~StandardEnvironmentT() {
        if (__builtin_expect(changed_, 0)) {
#ifdef LINEQUAD_X86_FP
            write_mxcsr(caller_.simd);
            if (x87) write_x87(caller_.x87);
#else
            set_fp_state(caller_);
#endif
        }
    }
    StandardEnvironmentT(const StandardEnvironmentT&) = delete;
    StandardEnvironmentT& operator=(const StandardEnvironmentT&) = delete;

  private:
    FpState caller_{};
    bool changed_ = false;
};
using StandardEnvironment = StandardEnvironmentT<false>;

// How `after` differs from `before`, in words ("rounding toward +infinity, flush-to-zero set"),
// or "" when it does not: what the audit reports of a solver that changed the environment.
inline std::string fp_change(FpState before, FpState after) {
    std::string out;
    auto add = [&](const std::string& s) { out += (out.empty() ? "" : ", ") + s; };
#ifdef LINEQUAD_X86_FP
    static const char* const rounding[4] = {"to nearest", "toward -infinity", "toward +infinity",
                                            "toward zero"};
    std::uint32_t rb = (before.simd >> 13) & 3, ra = (after.simd >> 13) & 3;
    if (rb != ra) add(std::string("rounding ") + rounding[ra]);
    auto bit = [&](int b, const char* name) {
        bool was = (before.simd >> b) & 1, is = (after.simd >> b) & 1;
        if (was != is) add(std::string(name) + (is ? " set" : " cleared"));
    };
    bit(15, "flush-to-zero");
    bit(6, "denormals-are-zero");
    if (((before.simd ^ after.simd) >> 7 & 0x3F) != 0) add("exception masks changed");
    if (before.x87 != after.x87) add("x87 control word changed");
#else
    if (before != after) add("rounding mode changed");
#endif
    return out;
}

} // namespace linequad::numeric
