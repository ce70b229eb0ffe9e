// Solvers from outside linequad: posing a case the way a library takes it, the exact reference
// for what it answers, a guard against its crashes, and plugins loaded through the C ABI.
#include "linequad/audit_solver.hpp"

#include "linequad/audit_plugin.h"
#include "linequad/case_io.hpp"
#include "linequad/exact.hpp"

#include <dlfcn.h>

#include <cmath>
#include <csetjmp>
#include <csignal>
#include <cstring>
#include <stdexcept>

namespace linequad::audit {

const char* answers_name(Answers a) {
    switch (a) {
    case Answers::all:
        return "all hits";
    case Answers::nearest:
        return "nearest hit";
    case Answers::first_entry:
        return "first entry";
    }
    return "?";
}

const char* parametrisation_name(Parametrisation p) {
    switch (p) {
    case Parametrisation::line:
        return "t along v";
    case Parametrisation::unit_direction:
        return "distance along v/|v|";
    case Parametrisation::segment:
        return "fraction of from-to";
    }
    return "?";
}

const char* surface_name(Surface s) {
    switch (s) {
    case Surface::as_posed:
        return "as posed";
    case Surface::closed:
        return "closed solids";
    case Surface::infinite:
        return "infinite surfaces";
    }
    return "?";
}

// ---- crashes

namespace {

// A library that aborts or faults inside a call is stopped there and the call counted as
// crashed; the process goes on. The handlers stay installed while any guarded call runs.
thread_local sigjmp_buf* crash_target = nullptr;
thread_local volatile sig_atomic_t crash_signal = 0;
constexpr int guarded_signals[] = {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT};

// The handlers in force while guarded calls may run, and those they replaced.
thread_local int guard_depth = 0;
struct sigaction replaced[std::size(guarded_signals)];

extern "C" void on_crash(int sig) {
    if (!crash_target) {
        // Not inside an external solver: the crash is the program's own, for the handler that
        // was there before (a test framework's, a sanitizer's, the default).
        for (std::size_t i = 0; i < std::size(guarded_signals); ++i)
            if (guarded_signals[i] == sig) sigaction(sig, &replaced[i], nullptr);
        std::raise(sig);
        return;
    }
    crash_signal = sig;
    siglongjmp(*crash_target, 1);
}

const char* crash_name(int sig) {
    switch (sig) {
    case SIGSEGV:
        return "crashed (SIGSEGV)";
    case SIGBUS:
        return "crashed (SIGBUS)";
    case SIGFPE:
        return "crashed (SIGFPE)";
    case SIGILL:
        return "crashed (SIGILL)";
    default:
        return "crashed (abort)";
    }
}

} // namespace

CrashGuard::CrashGuard() {
    if (guard_depth++ > 0) return;
    struct sigaction sa {};
    sa.sa_handler = on_crash;
    sigemptyset(&sa.sa_mask);
    sa.sa_flags = SA_NODEFER; // the handler jumps out: leave the signal unblocked
    for (std::size_t i = 0; i < std::size(guarded_signals); ++i)
        sigaction(guarded_signals[i], &sa, &replaced[i]);
}

CrashGuard::~CrashGuard() {
    if (--guard_depth > 0) return;
    for (std::size_t i = 0; i < std::size(guarded_signals); ++i)
        sigaction(guarded_signals[i], &replaced[i], nullptr);
}

namespace {

template <class S>
std::optional<Result> guarded(const ShapeCallable<S>& f, const S& s, const Line& l) {
    CrashGuard guard;
    sigjmp_buf here;
    sigjmp_buf* outer = crash_target;
    crash_target = &here;
    // No mask to restore (a system call per solve): with SA_NODEFER nothing stays blocked.
    if (sigsetjmp(here, 0)) {
        crash_target = outer;
        return Result::failure(ErrorCode::foreign, crash_name(crash_signal));
    }
    std::optional<Result> r = f(s, l);
    crash_target = outer;
    return r;
}

} // namespace

bool ExternalSolver::takes(const Shape& s) const {
    return std::visit(
        [&](const auto& x) -> bool {
            using S = std::decay_t<decltype(x)>;
            if constexpr (std::is_same_v<S, Cylinder>) return bool(cylinder);
            if constexpr (std::is_same_v<S, EllipticCylinder>) return bool(elliptic_cylinder);
            if constexpr (std::is_same_v<S, EllipticCone>) return bool(elliptic_cone);
            if constexpr (std::is_same_v<S, Frustum>) return bool(frustum);
        },
        s);
}

std::optional<Result> ExternalSolver::operator()(const Shape& s, const Line& l) const {
    return std::visit(
        [&](const auto& x) -> std::optional<Result> {
            using S = std::decay_t<decltype(x)>;
            const ShapeCallable<S>* f = nullptr;
            if constexpr (std::is_same_v<S, Cylinder>) f = &cylinder;
            if constexpr (std::is_same_v<S, EllipticCylinder>) f = &elliptic_cylinder;
            if constexpr (std::is_same_v<S, EllipticCone>) f = &elliptic_cone;
            if constexpr (std::is_same_v<S, Frustum>) f = &frustum;
            if (!*f) return std::nullopt;
            return guarded(*f, x, l);
        },
        s);
}

// ---- posing

namespace {

// A value of the case's format: x rounded to it.
double in_format(double x, Precision p) {
    return p == Precision::binary32 ? double(float(x)) : x;
}

// from and to, moved by at most half an ulp of to so that v = to - from is exact in R: then a
// library that forms from + f (to - from), or is handed both ends, sees the line (from, v).
template <class R>
bool exact_segment(double from_in, double to_in, double* from_out, double* v_out) {
    R a = R(from_in), b = R(to_in);
    R d = b - a;
    // Fast2Sum: with |b| >= |a|, b - d is exact, so from = b - d gives from + d = b exactly;
    // otherwise d + a is exact, and to becomes a + d.
    R from = std::fabs(b) >= std::fabs(a) ? R(b - d) : a;
    R to = from + d;
    if (!std::isfinite(d) || !std::isfinite(to) || to - d != from) return false;
    *from_out = double(from), *v_out = double(d);
    return true;
}

bool pose_segment(Line& l, Precision p) {
    if (!l.range.has_t0() || !l.range.has_t1() || !(l.range.t0 <= l.range.t1)) return false;
    double L0[3], v[3];
    for (int k = 0; k < 3; ++k) {
        double from = l.L0[k] + l.range.t0 * l.v[k], to = l.L0[k] + l.range.t1 * l.v[k];
        bool ok = p == Precision::binary32 ? exact_segment<float>(from, to, &L0[k], &v[k])
                                           : exact_segment<double>(from, to, &L0[k], &v[k]);
        if (!ok) return false;
    }
    l = Line{{L0[0], L0[1], L0[2]}, {v[0], v[1], v[2]}, Range::segment};
    return true;
}

bool pose_unit_direction(Line& l, Precision p) {
    double n = std::hypot(std::hypot(l.v.x, l.v.y), l.v.z);
    if (!(n > 0) || !std::isfinite(n)) return true; // the library sees v as it is, and refuses
    l.v = {in_format(l.v.x / n, p), in_format(l.v.y / n, p), in_format(l.v.z / n, p)};
    // Ends at 0 and infinity stay; a finite end becomes a distance, which must stay finite.
    auto scaled = [&](double t) { return t == 0 || std::isinf(t) ? t : in_format(t * n, p); };
    Interval range{scaled(l.range.t0), scaled(l.range.t1)};
    if (std::isfinite(l.range.t0) != std::isfinite(range.t0) ||
        std::isfinite(l.range.t1) != std::isfinite(range.t1))
        return false;
    l.range = range;
    return true;
}

} // namespace

std::optional<Case> posed_for(const ExternalSolver& s, const Case& c) {
    Case out = c;
    switch (s.surface) {
    case Surface::as_posed:
        break;
    case Surface::closed: {
        bool finite = std::visit([](const auto& x) { return x.finite; }, out.shape);
        if (!finite) return std::nullopt;
        std::visit([](auto& x) { x.caps = true; }, out.shape);
        break;
    }
    case Surface::infinite:
        std::visit(
            [](auto& x) {
                x.finite = false, x.caps = false;
                if constexpr (std::is_same_v<std::decay_t<decltype(x)>, EllipticCone>) x.nappes = 2;
            },
            out.shape);
        break;
    }
    switch (s.parametrisation) {
    case Parametrisation::line:
        break;
    case Parametrisation::unit_direction:
        if (!pose_unit_direction(out.line, c.precision)) return std::nullopt;
        break;
    case Parametrisation::segment:
        if (!pose_segment(out.line, c.precision)) return std::nullopt;
        break;
    }
    return out;
}

// ---- the reference

namespace {

int crossings(const Result& r) {
    int n = 0;
    for (int i = 0; i < r.count; ++i)
        n += r.hits[i].kind == HitKind::cross;
    return n;
}

// Whether the line is inside the closed solid just before t0: the parity of its crossings
// before t0, each decided exactly by the oracle (those on (-inf, t0], less one at t0 itself).
bool inside_before(const Case& c) {
    if (!c.line.range.has_t0()) return false;
    Line before = c.line, at = c.line;
    before.range = {-INFINITY, c.line.range.t0};
    at.range = {c.line.range.t0, c.line.range.t0};
    Result b = exact::intersect(c.shape, before, {Need::all, false}, c.precision);
    Result a = exact::intersect(c.shape, at, {Need::all, false}, c.precision);
    if (!b.ok() || !a.ok() || b.on_surface || a.on_surface) return false;
    return (crossings(b) - crossings(a)) % 2 != 0;
}

} // namespace

Result reference_for(Answers a, const Case& posed) {
    if (a == Answers::nearest)
        return exact::intersect(posed.shape, posed.line, {Need::nearest, true}, posed.precision);
    Result all = exact::intersect(posed.shape, posed.line, {Need::all, true}, posed.precision);
    if (a == Answers::all || !all.ok() || all.on_surface) return all;
    // The first hit met from outside: a crossing into the solid, or a touch from outside.
    bool inside = inside_before(posed);
    Result first = all;
    first.count = 0;
    for (int i = 0; i < all.count; ++i) {
        if (!inside) {
            first.hits[first.count++] = all.hits[i];
            break;
        }
        if (all.hits[i].kind == HitKind::cross) inside = false;
    }
    return first;
}

// ---- plugins

namespace {

lq_shape to_c(const Shape& s) {
    lq_shape out{};
    auto put = [&](int at, Vec3 v) {
        for (int k = 0; k < 3; ++k)
            out.p[at + k] = v[k];
    };
    std::visit(
        [&](const auto& x) {
            using S = std::decay_t<decltype(x)>;
            out.finite = x.finite, out.caps = x.caps, out.nappes = 1;
            if constexpr (std::is_same_v<S, Cylinder>)
                out.kind = LQ_CYLINDER, put(0, x.C), put(3, x.H), out.p[6] = x.r;
            if constexpr (std::is_same_v<S, EllipticCylinder>)
                out.kind = LQ_ELLIPTIC_CYLINDER, put(0, x.C), put(3, x.a), put(6, x.b), put(9, x.c);
            if constexpr (std::is_same_v<S, EllipticCone>)
                out.kind = LQ_ELLIPTIC_CONE, put(0, x.C), put(3, x.H), put(6, x.a), put(9, x.b),
                out.nappes = x.nappes;
            if constexpr (std::is_same_v<S, Frustum>)
                out.kind = LQ_FRUSTUM, put(0, x.C0), out.p[3] = x.r0, put(4, x.C1), out.p[7] = x.r1;
        },
        s);
    return out;
}

ErrorCode code_named(const std::string& name) {
    for (int c = int(ErrorCode::not_a_number); c < int(ErrorCode::foreign); ++c)
        if (name == code_name(ErrorCode(c))) return ErrorCode(c);
    return ErrorCode::foreign;
}

// The plugin's answer as a Result; one that breaks the ABI's rules is the solver's own error,
// named for what is wrong with it.
std::optional<Result> from_c(const lq_answer& a, int rc) {
    auto own = [](const char* why) { return Result::failure(ErrorCode::foreign, why); };
    if (rc != 0) return own("the plugin's solve returned nonzero");
    switch (a.status) {
    case LQ_UNREPRESENTED:
        return std::nullopt;
    case LQ_REFUSED: {
        std::string name(a.error, strnlen(a.error, sizeof a.error));
        if (name.empty()) name = "refused without a name";
        ErrorCode code = code_named(name);
        return Result::failure(code, code == ErrorCode::foreign ? interned(name) : "plugin");
    }
    case LQ_ON_SURFACE: {
        Result r;
        r.on_surface = true, r.s0 = a.s0, r.s1 = a.s1;
        if (a.surface_part < 0 || a.surface_part > 2) return own("a surface part out of range");
        r.surface_part = Part(a.surface_part);
        return r;
    }
    case LQ_HITS: {
        if (a.count < 0 || a.count > max_hits) return own("a hit count out of range");
        Result r;
        for (int i = 0; i < a.count; ++i) {
            const lq_hit& h = a.hits[i];
            if (h.kind < 0 || h.kind > 1 || h.part < 0 || h.part > 2)
                return own("a hit kind or part out of range");
            r.hits[r.count++] =
                Hit{h.t, {h.p[0], h.p[1], h.p[2]}, NAN, HitKind(h.kind), Part(h.part), false};
        }
        return r;
    }
    }
    return own("an answer status out of range");
}

template <class S>
ShapeCallable<S> plugin_callable(const lq_solver& s, int kind) {
    if (!(s.shapes & (1u << kind))) return {};
    return [&s](const S& shape, const Line& l) -> std::optional<Result> {
        lq_shape cs = to_c(shape);
        lq_line cl{{l.L0.x, l.L0.y, l.L0.z}, {l.v.x, l.v.y, l.v.z}, l.range.t0, l.range.t1};
        lq_answer a{};
        int rc = s.solve(s.self, &cs, &cl, &a);
        return from_c(a, rc);
    };
}

} // namespace

std::vector<ExternalSolver> load_plugin(const std::string& path) {
    auto fail = [&](const std::string& why) { return std::runtime_error(path + ": " + why); };
    // Kept loaded for the life of the program: the solvers point into it.
    void* lib = dlopen(path.find('/') == std::string::npos ? ("./" + path).c_str() : path.c_str(),
                       RTLD_NOW | RTLD_LOCAL);
    if (!lib) throw fail(std::string("cannot load it: ") + dlerror());
    auto entry = reinterpret_cast<lq_plugin_entry>(dlsym(lib, "linequad_audit_plugin"));
    if (!entry) throw fail("exports no linequad_audit_plugin (see linequad/audit_plugin.h)");
    const lq_solver* solvers = nullptr;
    int n = entry(LQ_ABI, &solvers);
    if (n < 0) throw fail("does not speak the plugin ABI " + std::to_string(LQ_ABI));
    if (n == 0 || !solvers) throw fail("offers no solver");
    std::vector<ExternalSolver> out;
    for (int i = 0; i < n; ++i) {
        const lq_solver& s = solvers[i];
        std::string which = "solver " + std::to_string(i);
        if (!s.name || !*s.name) throw fail(which + " has no name");
        which = "solver '" + std::string(s.name) + "'";
        if (s.precision != 64 && s.precision != 32)
            throw fail(which + ": precision must be 64 or 32, not " + std::to_string(s.precision));
        if (s.answers < LQ_ALL || s.answers > LQ_FIRST_ENTRY)
            throw fail(which + ": answers out of range");
        if (s.parametrisation < LQ_LINE || s.parametrisation > LQ_SEGMENT)
            throw fail(which + ": parametrisation out of range");
        if (s.surface < LQ_AS_POSED || s.surface > LQ_INFINITE)
            throw fail(which + ": surface out of range");
        if (!s.solve) throw fail(which + " has no solve function");
        if (!(s.shapes & 15u)) throw fail(which + " takes no shape");
        ExternalSolver e;
        e.name = s.name;
        e.precision = s.precision == 32 ? Precision::binary32 : Precision::binary64;
        e.answers = Answers(s.answers);
        e.parametrisation = Parametrisation(s.parametrisation);
        e.surface = Surface(s.surface);
        e.points = s.carries & LQ_POINTS, e.kinds = s.carries & LQ_KINDS;
        e.parts = s.carries & LQ_PARTS;
        e.mapping = s.mapping ? s.mapping : "";
        e.plugin = path;
        e.cylinder = plugin_callable<Cylinder>(s, LQ_CYLINDER);
        e.elliptic_cylinder = plugin_callable<EllipticCylinder>(s, LQ_ELLIPTIC_CYLINDER);
        e.elliptic_cone = plugin_callable<EllipticCone>(s, LQ_ELLIPTIC_CONE);
        e.frustum = plugin_callable<Frustum>(s, LQ_FRUSTUM);
        out.push_back(std::move(e));
    }
    return out;
}

} // namespace linequad::audit
