// Solvers from outside linequad: posing a case the way a library takes it, the exact reference
// for what it answers under its conventions, in-process calls guarded (crashes caught, the
// floating-point environment checked and put back), and plugins loaded into a worker process.
#include "linequad/audit_solver.hpp"

#include "linequad/batch.hpp"
#include "linequad/case_io.hpp"
#include "linequad/exact.hpp"

#include "io/process.hpp"
#include "io/shape_types.hpp"
#include "numeric/fp_environment.hpp"
#include "run/plugin_worker.hpp"
#include "shapes/all.hpp"

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
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
    case Answers::first_exit:
        return "first exit";
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

const char* start_inside_name(StartInside s) {
    switch (s) {
    case StartInside::as_answers:
        return "as it answers";
    case StartInside::no_hit:
        return "no hit";
    case StartInside::at_t0:
        return "a hit at t0";
    case StartInside::at_zero:
        return "a hit at 0";
    case StartInside::undefined:
        return "undefined (not asked)";
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

// call(), or crashed(the crash's name) where it faulted or aborted.
template <class Call, class Crashed>
auto guarded(Call call, Crashed crashed) -> decltype(call()) {
    CrashGuard guard;
    sigjmp_buf here;
    sigjmp_buf* outer = crash_target;
    crash_target = &here;
    // No mask to restore (a system call per solve): with SA_NODEFER nothing stays blocked.
    if (sigsetjmp(here, 0)) {
        crash_target = outer;
        return crashed(crash_name(crash_signal));
    }
    auto r = call();
    crash_target = outer;
    return r;
}
template <class S>
std::optional<Result> guarded(const ShapeCallable<S>& f, const S& s, const Line& l) {
    return guarded([&] { return f(s, l); },
                   [](const char* why) -> std::optional<Result> {
                       return Result::failure(ErrorCode::foreign, why);
                   });
}

} // namespace

void OwnOutput::write(std::string_view text) {
    std::lock_guard<std::mutex> hold(lock_);
    bytes_ += text.size();
    // Whole messages only (one cut in two would read as another), and the first ones: after the
    // first that does not fit, none.
    full_ = full_ || head_.size() + text.size() > kept;
    if (!full_) head_.append(text);
}

std::string OwnOutput::head() const {
    std::lock_guard<std::mutex> hold(lock_);
    return head_;
}

std::uint64_t OwnOutput::bytes() const {
    std::lock_guard<std::mutex> hold(lock_);
    return bytes_;
}

void OwnOutput::clear() {
    std::lock_guard<std::mutex> hold(lock_);
    head_.clear();
    bytes_ = 0;
    full_ = false;
}

bool ExternalSolver::takes_shape(std::size_t index) const {
    if (worker || chunk) return (worker_shapes >> index) & 1u;
    return with_shape_type(index,
                           [&](auto tag) { return bool(on<typename decltype(tag)::type>()); });
}

bool ExternalSolver::takes(const Shape& s) const {
    return takes_shape(s.index());
}

namespace {
// A chunk callable's answers, the floating-point environment put back after the call (and noted
// on each answer, as a call of the per-shape callables is).
void answer_chunk(const ExternalSolver::ChunkCallable& chunk, const std::vector<Case>& posed,
                  std::vector<ExternalAnswer>& out) {
    out.assign(posed.size(), ExternalAnswer{});
    numeric::FpState before = numeric::fp_state();
    chunk(posed, out);
    numeric::FpState after = numeric::fp_state();
    if (after != before) {
        const char* change = interned(numeric::fp_change(before, after));
        for (ExternalAnswer& a : out)
            a.environment = change;
        numeric::set_fp_state(before);
    }
}
} // namespace

ExternalAnswer ExternalSolver::answer(const Shape& s, const Line& l) const {
    if (worker || chunk) {
        Case c;
        c.shape = s, c.line = l, c.precision = precision;
        std::vector<ExternalAnswer> out;
        if (!answer_all({c}, out, nullptr) || out.empty()) return {};
        return out[0];
    }
    // In process: the call may change the floating-point environment; it is put back, and noted.
    numeric::FpState before = numeric::fp_state();
    ExternalAnswer a;
    a.result = std::visit(
        [&](const auto& x) -> std::optional<Result> {
            const auto& f = on<std::decay_t<decltype(x)>>();
            if (!f) return std::nullopt;
            return guarded(f, x, l);
        },
        s);
    numeric::FpState after = numeric::fp_state();
    if (after != before) {
        a.environment = interned(numeric::fp_change(before, after));
        numeric::set_fp_state(before);
    }
    return a;
}

bool ExternalSolver::has_sense() const {
    return worker ? worker_sense : bool(sense);
}

bool ExternalSolver::sides(const std::vector<Case>& at, std::vector<ExternalAnswer>& out) const {
    if (worker) return worker->sides(worker_index, at, out);
    out.assign(at.size(), ExternalAnswer{});
    if (!sense) {
        for (ExternalAnswer& a : out)
            a.result = Result::failure(ErrorCode::foreign, "it has no sense entry");
        return true;
    }
    CrashGuard guard;
    for (std::size_t i = 0; i < at.size(); ++i) {
        numeric::FpState before = numeric::fp_state();
        const char* crashed = "";
        int side = guarded([&] { return sense(at[i].shape, at[i].line.L0, at[i].line.v); },
                           [&](const char* why) { return crashed = why, 0; });
        ExternalAnswer& a = out[i];
        if (*crashed)
            a.result = Result::failure(ErrorCode::foreign, crashed);
        else if (side == -1 || side == 1)
            a.result = Result{}, a.side = side;
        else
            a.result = Result::failure(
                ErrorCode::foreign,
                interned("its sense answered " + std::to_string(side) + ", not -1 or 1"));
        numeric::FpState after = numeric::fp_state();
        if (after != before) {
            a.environment = interned(numeric::fp_change(before, after));
            numeric::set_fp_state(before);
        }
    }
    return true;
}

bool ExternalSolver::answer_all(const std::vector<Case>& posed, std::vector<ExternalAnswer>& out,
                                double* ns) const {
    if (worker) return worker->answer(worker_index, posed, out, ns);
    if (chunk) {
        auto t0 = std::chrono::steady_clock::now();
        answer_chunk(chunk, posed, out);
        auto t1 = std::chrono::steady_clock::now();
        if (ns) *ns = std::chrono::duration<double, std::nano>(t1 - t0).count();
        return true;
    }
    out.resize(posed.size());
    CrashGuard guard; // installed once for all of them, outside the timing
    auto t0 = std::chrono::steady_clock::now();
    for (std::size_t j = 0; j < posed.size(); ++j)
        out[j] = answer(posed[j].shape, posed[j].line);
    auto t1 = std::chrono::steady_clock::now();
    if (ns) *ns = std::chrono::duration<double, std::nano>(t1 - t0).count();
    return true;
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

std::optional<Case> posed_for(const ExternalSolver& s, const Case& c, std::string* why) {
    auto refuse = [&](const char* reason) -> std::optional<Case> {
        if (why) *why = reason;
        return std::nullopt;
    };
    Case out = c;
    switch (s.surface) {
    case Surface::as_posed:
        break;
    case Surface::closed: {
        if (!close_with_discs(out.shape))
            return refuse("a closed solid cannot be made of an infinite shape");
        break;
    }
    case Surface::infinite:
        make_whole(out.shape, 2);
        break;
    }
    switch (s.parametrisation) {
    case Parametrisation::line:
        break;
    case Parametrisation::unit_direction:
        if (!pose_unit_direction(out.line, c.precision))
            return refuse("the range's ends overflow as distances");
        break;
    case Parametrisation::segment:
        if (!pose_segment(out.line, c.precision))
            return refuse(
                "a segment needs a finite range whose ends and difference the format holds");
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

// Where the range starts against the solid, decided exactly: strictly inside, on its surface, or
// outside (or no start: an unbounded range).
enum class Start { outside, inside, on_surface };
Start start_of(const Case& c) {
    if (!c.line.range.has_t0()) return Start::outside;
    Line at = c.line;
    at.range = {c.line.range.t0, c.line.range.t0};
    Result a = exact::intersect(c.shape, at, {Need::all, false}, c.precision);
    if (a.ok() && (a.count > 0 || a.on_surface)) return Start::on_surface;
    return inside_before(c) ? Start::inside : Start::outside;
}

// Whether the posed shape bounds a solid: closed, or not finite.
bool solid(const Shape& s) {
    return bounds_solid(s);
}

// a + b (doubles whose sum is wanted in the format p) rounded once to p. In double, fl(a + b) is
// that. In float, fl(a + b) in double rounds to the float the exact sum rounds to unless it lands
// exactly on a midpoint between two floats (they are doubles), where the sum's rounding error
// decides.
double sum_rounded(double a, double b, Precision p) {
    double s = a + b;
    if (p == Precision::binary64 || !std::isfinite(s))
        return p == Precision::binary64 ? s : float(s);
    double bb = s - a, e = (a - (s - bb)) + (b - bb); // TwoSum: s + e = a + b exactly
    float f = float(s);
    if (e == 0 || double(f) == s) return f;
    float other = std::nextafter(f, double(f) < s ? INFINITY : -INFINITY);
    bool midpoint = (double(f) + double(other)) * 0.5 == s;
    if (!midpoint) return f;
    float up = std::max(f, other), down = std::min(f, other);
    return e > 0 ? up : down;
}

// The hit a start-inside convention makes: at t (t0, or 0), its point L(t) rounded once.
Result hit_at(const Case& c, double t) {
    auto at = [&](int k) {
        return c.precision == Precision::binary64
                   ? std::fma(t, c.line.v[k], c.line.L0[k])
                   : sum_rounded(c.line.L0[k], t * c.line.v[k], c.precision); // t v exact
    };
    Vec3 p{at(0), at(1), at(2)};
    Result r;
    r.hits[r.count++] = Hit{t, p, NAN, HitKind::cross, Part::lateral, false};
    return r;
}

// The hits without its tangent touches (a library for which a touch is no hit).
Result without_tangents(Result r) {
    int kept = 0;
    for (int i = 0; i < r.count; ++i)
        if (r.hits[i].kind != HitKind::tangent) r.hits[kept++] = r.hits[i];
    r.count = kept;
    return r;
}

Result reference_under(Answers a, TangentRule tangent, const Case& posed) {
    if (a == Answers::nearest && tangent == TangentRule::hit)
        return exact::intersect(posed.shape, posed.line, {Need::nearest, true}, posed.precision);
    Result all = exact::intersect(posed.shape, posed.line, {Need::all, true}, posed.precision);
    if (!all.ok() || all.on_surface) return all;
    if (tangent == TangentRule::no_hit) all = without_tangents(all);
    if (a == Answers::all) return all;
    if (a == Answers::nearest) {
        all.count = std::min<std::uint8_t>(all.count, 1);
        return all;
    }
    bool inside = inside_before(posed);
    Result first = all;
    first.count = 0;
    for (int i = 0; i < all.count; ++i) {
        if (a == Answers::first_entry) {
            // The first hit met from outside: a crossing into the solid, or a touch from outside.
            if (!inside) {
                first.hits[first.count++] = all.hits[i];
                break;
            }
            if (all.hits[i].kind == HitKind::cross) inside = false;
        } else if (all.hits[i].kind == HitKind::cross) {
            // The first crossing out of the solid.
            if (inside) {
                first.hits[first.count++] = all.hits[i];
                break;
            }
            inside = true;
        }
    }
    return first;
}

} // namespace

Result reference_for(Answers a, const Case& posed) {
    return reference_under(a, TangentRule::hit, posed);
}

Reference reference_for(const ExternalSolver& s, const Case& posed) {
    Reference ref;
    bool inside_convention = s.inside != StartInside::as_answers && solid(posed.shape);
    if (s.answers == Answers::first_exit) {
        if (!solid(posed.shape)) {
            ref.unrepresented = "first exit: an open surface bounds no solid";
            return ref;
        }
        if (start_of(posed) == Start::outside) {
            ref.not_asked = "first exit: the range does not start inside the solid";
            return ref;
        }
    } else if (inside_convention) {
        Start start = start_of(posed);
        bool applies = start == Start::inside ||
                       (start == Start::on_surface && s.inside != StartInside::no_hit &&
                        s.on_surface == StartOnSurface::as_inside);
        if (applies && s.inside == StartInside::undefined) {
            ref.not_asked = start == Start::inside ? "the range starts inside the solid (undefined)"
                                                   : "the range starts on the surface (undefined)";
            return ref;
        }
        if (applies) {
            ref.kinds = ref.parts = false; // a start inside is no point of the surface
            if (s.inside == StartInside::no_hit) ref.result = Result{};
            if (s.inside == StartInside::at_t0) ref.result = hit_at(posed, posed.line.range.t0);
            if (s.inside == StartInside::at_zero) ref.result = hit_at(posed, 0);
            return ref;
        }
    }
    ref.result = reference_under(s.answers, s.tangent, posed);
    if (s.contact_as_point && ref.result.ok() && ref.result.on_surface) {
        const Result& r = ref.result;
        if (std::isinf(r.s0)) {
            ref.unrepresented = "a contact from -infinity has no first point";
            return ref;
        }
        // The contact's first point: its t is the oracle's, its point not computed (the exact
        // start of a contact is a surd; the library's point there is not graded).
        Result first;
        first.hits[first.count++] = Hit{r.s0, {}, NAN, HitKind::tangent, r.surface_part, false};
        ref.result = first;
        ref.kinds = ref.points = false;
    }
    return ref;
}

bool answers_as_oracle(const ExternalSolver& s) {
    return s.answers == Answers::all && s.surface == Surface::as_posed &&
           s.parametrisation == Parametrisation::line && s.inside == StartInside::as_answers &&
           !s.contact_as_point && s.tangent == TangentRule::hit;
}

std::string reference_label(const ExternalSolver& s) {
    if (s.answers == Answers::all && s.inside == StartInside::as_answers && !s.contact_as_point &&
        s.tangent == TangentRule::hit)
        return "exact";
    std::string label = std::string("exact, ") + answers_name(s.answers);
    if (s.inside != StartInside::as_answers)
        label += std::string(", start inside: ") + start_inside_name(s.inside);
    if (s.inside != StartInside::as_answers && s.on_surface == StartOnSurface::by_direction)
        label += ", start on surface: by direction";
    if (s.contact_as_point) label += ", contact: first point";
    if (s.tangent == TangentRule::no_hit) label += ", tangent: no hit";
    return label;
}

void read_conventions(const ExternalSolver& s, const Case& posed, Result& got) {
    if (!(s.negative_zero > 0) || !got.ok()) return;
    double speed = std::hypot(std::hypot(posed.line.v.x, posed.line.v.y), posed.line.v.z);
    if (!(speed > 0) || !std::isfinite(speed)) return;
    // The distance of a t is |t| |v|: a t in [-negative_zero / |v|, 0) is a distance the library
    // means as 0.
    for (int i = 0; i < got.count; ++i)
        if (got.hits[i].t < 0 && -got.hits[i].t * speed <= s.negative_zero) got.hits[i].t = 0;
}

std::string conventions_text(const ExternalSolver& s) {
    std::vector<std::string> said;
    auto number = [](double x) {
        char text[32];
        std::snprintf(text, sizeof text, "%.3g", x);
        return std::string(text);
    };
    if (!s.tolerance.none()) {
        std::string t = "surfaces ";
        if (s.tolerance.absolute > 0) t += number(s.tolerance.absolute);
        if (s.tolerance.absolute > 0 && s.tolerance.relative > 0) t += " + ";
        if (s.tolerance.relative > 0) t += number(s.tolerance.relative) + " × the scene's size";
        said.push_back(t + " off at most");
    }
    if (s.tangent == TangentRule::no_hit) said.emplace_back("a tangent touch is no hit");
    if (s.inside != StartInside::as_answers && s.on_surface == StartOnSurface::by_direction)
        said.emplace_back(
            "a start on the surface: an entry at the start moving in, none moving out");
    if (s.negative_zero > 0)
        said.push_back("a distance down to -" + number(s.negative_zero) + " reads as 0");
    std::string out;
    for (const std::string& x : said)
        out += (out.empty() ? "" : "; ") + x;
    return out;
}

std::string declaration_problem(const ExternalSolver& s) {
    std::string which = "solver '" + s.name + "'";
    if (std::string p = solver_name_problem(s.name); !p.empty()) return which + " " + p;
    auto length = [&](const char* field, double x) -> std::string {
        if (std::isfinite(x) && x >= 0) return "";
        char text[64];
        std::snprintf(text, sizeof text, "%g", x);
        return which + ": " + field + " must be finite and at least 0, not " + text;
    };
    for (auto [field, x] :
         {std::pair<const char*, double>{"tolerance_absolute", s.tolerance.absolute},
          {"tolerance_relative", s.tolerance.relative},
          {"negative_zero", s.negative_zero}})
        if (std::string p = length(field, x); !p.empty()) return p;
    bool entry = s.answers == Answers::nearest || s.answers == Answers::first_entry;
    if (s.inside != StartInside::as_answers && !entry)
        return which + ": inside (" + start_inside_name(s.inside) +
               ") is for nearest or first-entry answers";
    if (s.on_surface != StartOnSurface::as_inside && s.inside == StartInside::as_answers)
        return which + ": start_on_surface says how a start-inside convention meets the surface; "
                       "it has none";
    return "";
}

Error input_problem(const ExternalSolver& s, const Case& posed) {
    if (s.precision != Precision::binary32) return {};
    return std::visit([&](const auto& x) { return detail::binary32_culprit(x, posed.line); },
                      posed.shape);
}

std::vector<std::string> replay_lines(const std::string& name, const Solver* own,
                                      const ExternalSolver* theirs, const Case& c) {
    Result reference = exact::intersect(c.shape, c.line, {}, c.precision);
    if (own)
        return {format_result(c.id, name, (*own)(c.shape, c.line)),
                format_result(c.id, "exact", reference)};
    if (!theirs) { // the batch path, one line per call as the audit grades it
        double x = c.line.L0.x, y = c.line.L0.y, z = c.line.L0.z;
        double vx = c.line.v.x, vy = c.line.v.y, vz = c.line.v.z;
        Result got;
        std::visit(
            [&](const auto& s) {
                stable::intersect(s, LineArrays{&x, &y, &z, &vx, &vy, &vz, 1, c.line.range},
                                  Query{}, &got);
            },
            c.shape);
        return {format_result(c.id, name, got), format_result(c.id, "exact", reference)};
    }
    const ExternalSolver& e = *theirs;
    auto unrepresented = [&](const std::string& why) {
        return std::vector<std::string>{
            format_failure(c.id, name, "unrepresented",
                           why.empty() ? "the solver cannot represent this case" : why)};
    };
    if (!e.takes(c.shape)) return unrepresented("the solver takes no such shape");
    Reference ref = reference_for(e, c);
    if (!ref.unrepresented.empty()) return unrepresented(ref.unrepresented);
    if (!ref.not_asked.empty())
        return {format_failure(c.id, name, "not_asked", ref.not_asked + ": not asked")};
    ExternalAnswer a = e.answer(c.shape, c.line);
    if (!a.result) return unrepresented(a.unrepresented);
    read_conventions(e, c, *a.result);
    std::string label = reference_label(e);
    Carries what{e.points && ref.points, e.kinds && ref.kinds, e.parts && ref.parts};
    return {format_result(c.id, name, *a.result, what),
            format_result(c.id, label, ref.result, label == "exact" ? Carries{} : what)};
}

// ---- plugins

ExternalSolver declared_as_external(const DeclaredSolver& d) {
    ExternalSolver e;
    e.name = d.name;
    e.precision = d.precision;
    e.answers = d.answers;
    e.parametrisation = d.parametrisation;
    e.surface = d.surface;
    e.inside = d.inside;
    e.contact_as_point = d.contact_as_point;
    e.on_surface = d.on_surface;
    e.tangent = d.tangent;
    e.tolerance = d.tolerance;
    e.negative_zero = d.negative_zero;
    e.points = d.points, e.kinds = d.kinds, e.parts = d.parts;
    e.mapping = d.mapping;
    e.worker_sense = d.sense;
    return e;
}

std::vector<ExternalSolver> load_plugin(const std::string& path, const PluginOptions& o) {
    // Kept as an absolute path: the report's replay commands work from any directory.
    std::string where = process::absolute(path);
    if (::access(where.c_str(), R_OK) != 0)
        throw std::runtime_error(path + ": cannot load it: " + std::strerror(errno));
    auto worker = std::make_shared<PluginWorker>(where, o);
    std::vector<ExternalSolver> out;
    for (std::size_t i = 0; i < worker->solvers().size(); ++i) {
        const DeclaredSolver& d = worker->solvers()[i];
        ExternalSolver e = declared_as_external(d);
        e.plugin = where;
        e.worker = worker;
        e.worker_index = int(i);
        e.worker_shapes = d.shapes;
        out.push_back(std::move(e));
    }
    return out;
}

} // namespace linequad::audit
