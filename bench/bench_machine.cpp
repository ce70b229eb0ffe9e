// The machine's own ceiling for the batch kernels' AVX-512 over AVX2 ratio: independent fused
// multiply-adds, as many per second as the CPU retires, on four lanes (AVX2) and on eight
// (AVX-512F). The kernels do the same arithmetic per block on either width, so where a 512-bit
// operation runs as two 256-bit halves (one AVX-512 instruction per cycle where AVX2 issues two)
// this ratio is about 1, and the width buys them no arithmetic: what AVX-512 gains over AVX2
// comes from the instructions around it (masks, blends, and spills: 32 registers, not 16).
//
// Twelve chains each: enough to hide an FMA's latency (4 cycles) on two pipes, few enough that
// the 256-bit loop keeps them and its two constants in the 16 registers AVX2 has.
#include <benchmark/benchmark.h>

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>

#include <cstdint>

namespace {

constexpr int chains = 12;

// The same loop on each instruction set, in its own intrinsics (prefix _mm256 or _mm512).
// a <- a m + c converges to c / (1 - m) = 2^-2: no overflow, no subnormal, however long.
#define LINEQUAD_FMA_CHAINS(name, isa, V, prefix)                                                  \
    __attribute__((target(isa), noinline)) double name(std::int64_t rounds, double seed) {         \
        V a[chains];                                                                               \
        for (int i = 0; i < chains; ++i)                                                           \
            a[i] = prefix##_set1_pd(seed + i * 0x1p-30);                                           \
        const V m = prefix##_set1_pd(1 - 0x1p-20), c = prefix##_set1_pd(0x1p-22);                  \
        for (std::int64_t k = 0; k < rounds; ++k)                                                  \
            for (int i = 0; i < chains; ++i)                                                       \
                a[i] = prefix##_fmadd_pd(a[i], m, c);                                              \
        V s = a[0];                                                                                \
        for (int i = 1; i < chains; ++i)                                                           \
            s = prefix##_add_pd(s, a[i]);                                                          \
        return prefix##_cvtsd_f64(s);                                                              \
    }
LINEQUAD_FMA_CHAINS(fma_chains_avx2, "avx2,fma", __m256d, _mm256)
LINEQUAD_FMA_CHAINS(fma_chains_avx512, "avx512f", __m512d, _mm512)
#undef LINEQUAD_FMA_CHAINS

// items: double lanes of fused multiply-add per second (4 or 8 per instruction).
template <int lanes>
void fma_peak(benchmark::State& state) {
    const bool runs = lanes == 8 ? __builtin_cpu_supports("avx512f")
                                 : __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
    if (!runs) {
        state.SkipWithError("this CPU lacks the instruction set");
        return;
    }
    // Inputs the compiler cannot see, anew on each iteration: the chains are neither folded at
    // compile time nor run once for the whole loop (the functions are pure).
    std::int64_t rounds = 4096;
    double seed = 1;
    benchmark::DoNotOptimize(rounds);
    for (auto _ : state) {
        benchmark::DoNotOptimize(seed);
        benchmark::DoNotOptimize(lanes == 8 ? fma_chains_avx512(rounds, seed)
                                            : fma_chains_avx2(rounds, seed));
    }
    state.SetItemsProcessed(state.iterations() * rounds * chains * lanes);
    state.SetLabel(lanes == 8 ? "avx512" : "avx2");
}

BENCHMARK_TEMPLATE(fma_peak, 4)->Name("machine/fma_lanes/avx2");
BENCHMARK_TEMPLATE(fma_peak, 8)->Name("machine/fma_lanes/avx512");

} // namespace
#endif
