// A plugin that misbehaves, one solver per way (a crash, an exit, a hang, an exception, output, a
// changed rounding mode, a helper process left behind, its descriptors closed), to show that
// nothing it does reaches linequad's own answers or loses the report (tests/test_worker.cpp). Each
// solver answers a textbook nearest hit of an open finite cylinder, and on a tenth of the cases
// (chosen by the bits of L0, so the same cases every run) does what its name says.
#include "linequad/audit_plugin.h"

#include <cfenv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <signal.h>
#include <stdexcept>
#include <string>
#include <unistd.h>
#include <vector>

namespace {

// A tenth of the points (by their bits: the same ones every run), and another tenth.
std::uint64_t point_bits(const double* p) {
    std::uint64_t bits;
    std::memcpy(&bits, &p[0], sizeof bits);
    return bits ^ (bits >> 29);
}
bool picked(const lq_line* l) {
    return point_bits(l->L0) % 10 == 3;
}

double dot3(const double* a, const double* b) {
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

void textbook(const lq_shape* s, const lq_line* l, lq_answer* out) {
    const double *C = s->p, *H = s->p + 3, r = s->p[6];
    double axis[3] = {H[0] - C[0], H[1] - C[1], H[2] - C[2]};
    double h = std::sqrt(dot3(axis, axis));
    for (double& a : axis)
        a /= h;
    double w[3] = {l->L0[0] - C[0], l->L0[1] - C[1], l->L0[2] - C[2]};
    double vd = dot3(l->v, axis), wd = dot3(w, axis);
    double a = dot3(l->v, l->v) - vd * vd, b = 2 * (dot3(l->v, w) - vd * wd);
    double c = dot3(w, w) - wd * wd - r * r, disc = b * b - 4 * a * c;
    out->status = LQ_HITS;
    if (a == 0 || disc < 0) return;
    for (double t : {(-b - std::sqrt(disc)) / (2 * a), (-b + std::sqrt(disc)) / (2 * a)}) {
        double z = wd + t * vd;
        if (t < l->t0 || t > l->t1 || z < 0 || z > h) continue;
        out->hits[out->count++].t = t;
        return;
    }
}

int depth(int n) { // unbounded recursion that the optimiser cannot turn into a loop
    volatile char frame[1024];
    frame[0] = char(n);
    return depth(n + 1) + frame[0];
}

template <int Kind>
int solve(void*, const lq_shape* s, const lq_line* l, lq_answer* out) {
    if (s->kind != LQ_CYLINDER || s->caps || !s->finite) {
        out->status = LQ_UNREPRESENTED;
        std::strcpy(out->error, "open finite cylinders only");
        return 0;
    }
    bool now = picked(l);
    switch (Kind) {
    case 0: // leaves the rounding mode upward, every call
        std::fesetround(FE_UPWARD);
        break;
    case 1:
        if (now) {
            std::vector<int> none;
            return none.at(7); // throws std::out_of_range through the C ABI
        }
        break;
    case 2:
        if (now) *static_cast<volatile int*>(nullptr) = 1;
        break;
    case 3:
        if (now) return depth(0);
        break;
    case 4:
        if (now) std::exit(0);
        break;
    case 5:
        if (now) {
            ::signal(SIGTERM, SIG_IGN); // deaf to the polite way to stop it
            for (volatile int spin = 0;; spin = spin + 1) {
            }
        }
        break;
    case 6: // talks on standard output and error
        std::printf("chatty: solving\n");
        std::fflush(stdout);
        std::fprintf(stderr, "chatty: to stderr\n");
        break;
    case 7:
        if (now) std::abort();
        break;
    case 8: // starts a helper that keeps every descriptor it inherited, then aborts
        if (now) {
            pid_t helper = ::fork();
            if (helper == 0) {
                ::sleep(60);
                ::_exit(0);
            }
            if (const char* list = std::getenv("LQ_TEST_HELPER_PIDS")) {
                int fd = ::open(list, O_WRONLY | O_APPEND | O_CREAT, 0644);
                std::string line = std::to_string(helper) + "\n";
                if (fd >= 0) (void)!::write(fd, line.data(), line.size()), ::close(fd);
            }
            std::abort();
        }
        break;
    case 9: // closes every descriptor it did not open, as a daemon does, and opens others there
        if (now) {
            for (int fd = 3; fd < 1024; ++fd)
                ::close(fd);
            for (int i = 0; i < 3; ++i)
                (void)::open("/dev/null", O_RDONLY);
        }
        break;
    }
    textbook(s, l, out);
    return 0;
}

// A tracker's sides (ABI 4's sense entry) that crash on a tenth of the points and write a side
// that is no side on another tenth; elsewhere the sign of a plane's f, or of a quadric's.
int no_hit(void*, const lq_shape*, const lq_line*, lq_answer* out) {
    std::memset(out, 0, sizeof *out);
    return 0;
}
int bad_side(void*, const lq_shape* s, const double p[3], const double*, int* side) {
    std::uint64_t bits = point_bits(p);
    if (bits % 10 == 3) {
        volatile int* nowhere = nullptr;
        *side = *nowhere;
    }
    if (bits % 10 == 5) {
        *side = 7;
        return 0;
    }
    const double* q = s->p;
    double f = s->kind == LQ_PLANE
                   ? q[0] * p[0] + q[1] * p[1] + q[2] * p[2] - q[3]
                   : q[0] * p[0] * p[0] + q[1] * p[1] * p[1] + q[2] * p[2] * p[2] +
                         q[3] * p[0] * p[1] + q[4] * p[1] * p[2] + q[5] * p[2] * p[0] +
                         q[6] * p[0] + q[7] * p[1] + q[8] * p[2] + q[9];
    *side = f > 0 ? 1 : -1;
    return 0;
}

const lq_solver solvers[] = {
    {"rounds_up", 64, LQ_NEAREST, LQ_LINE, LQ_AS_POSED, 0, 1u, "leaves FE_UPWARD", solve<0>,
     nullptr, 0, 0, nullptr},
    {"throws", 64, LQ_NEAREST, LQ_LINE, LQ_AS_POSED, 0, 1u, "vector::at", solve<1>, nullptr, 0, 0,
     nullptr},
    {"segfaults", 64, LQ_NEAREST, LQ_LINE, LQ_AS_POSED, 0, 1u, "null pointer", solve<2>, nullptr, 0,
     0, nullptr},
    {"overflows", 64, LQ_NEAREST, LQ_LINE, LQ_AS_POSED, 0, 1u, "recursion", solve<3>, nullptr, 0, 0,
     nullptr},
    {"exits", 64, LQ_NEAREST, LQ_LINE, LQ_AS_POSED, 0, 1u, "exit(0)", solve<4>, nullptr, 0, 0,
     nullptr},
    {"hangs", 64, LQ_NEAREST, LQ_LINE, LQ_AS_POSED, 0, 1u, "spins, SIGTERM ignored", solve<5>,
     nullptr, 0, 0, nullptr},
    {"chatty", 64, LQ_NEAREST, LQ_LINE, LQ_AS_POSED, 0, 1u, "prints", solve<6>, nullptr, 0, 0,
     nullptr},
    {"aborts", 64, LQ_NEAREST, LQ_LINE, LQ_AS_POSED, 0, 1u, "abort()", solve<7>, nullptr, 0, 0,
     nullptr},
    {"forks_then_aborts", 64, LQ_NEAREST, LQ_LINE, LQ_AS_POSED, 0, 1u, "fork(), abort()", solve<8>,
     nullptr, 0, 0, nullptr},
    {"closes_descriptors", 64, LQ_NEAREST, LQ_LINE, LQ_AS_POSED, 0, 1u, "close(3..1023)", solve<9>,
     nullptr, 0, 0, nullptr},
    {"bad_sides", 64, LQ_ALL, LQ_LINE, LQ_AS_POSED, 0, (1u << LQ_PLANE) | (1u << LQ_QUADRIC),
     "no hit; its sense crashes or writes 7", no_hit, nullptr, 0, 0, nullptr, 0, 0, 0, 0, 0,
     bad_side},
};

} // namespace

#ifdef HOSTILE_FTZ
// What a library built with -ffast-math does when it is loaded (crtfastmath's constructor): flush
// subnormal results to zero and read subnormal inputs as zero, for the whole process. Written out,
// so that the test does not depend on whether this compiler links crtfastmath into a module.
__attribute__((constructor)) static void set_flush_to_zero() {
    __builtin_ia32_ldmxcsr(__builtin_ia32_stmxcsr() | 0x8040);
}
#endif

extern "C" int linequad_audit_plugin(int abi, const lq_solver** out) {
    if (abi != LQ_ABI) return -1;
    *out = solvers;
    return int(sizeof solvers / sizeof solvers[0]);
}
