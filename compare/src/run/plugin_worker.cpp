// The plugin worker: the parent's side (PluginWorker) and the worker's (plugin_worker_main).
#include "run/plugin_worker.hpp"

#include "linequad/audit_plugin.h"
#include "linequad/case_io.hpp"

#include "io/jsonl.hpp"
#include "io/process.hpp"
#include "io/shape_types.hpp"
#include "numeric/fp_environment.hpp"
#include "run/stop.hpp"

#include <array>
#include <dlfcn.h>
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <sys/mman.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstring>
#include <exception>
#include <mutex>
#include <set>
#include <stdexcept>
#include <thread>

extern char** environ;

namespace linequad::audit {

namespace {

using Clock = std::chrono::steady_clock;
using numeric::FpState;

// ---- what parent and worker share

constexpr std::uint32_t request_magic = 0x4C515251; // "LQRQ"
constexpr std::uint32_t reply_magic = 0x4C515250;   // "LQRP"
constexpr std::uint32_t capacity = 1024;            // cases per request
constexpr int request_fd = 3, reply_fd = 4, shared_fd = 5;
constexpr std::size_t max_hello_bytes = std::size_t(1) << 20;

struct Request {
    std::uint32_t magic, seq, solver, first, count, batch;
    std::uint32_t check_socket; // after it, the worker checks its socket (see socket_intact)
    std::uint32_t sides;        // 1: the sense entry, a case's line its point and direction
};
struct Reply {
    std::uint32_t magic, seq, status, unused;
    std::uint64_t ns;
};
enum ReplyStatus : std::uint32_t { all_answered = 0, batch_declined = 1 };

// How one call ended, beside its answer.
enum Outcome : std::int32_t { answered = 0, returned_nonzero = 1, threw = 2, threw_other = 3 };
struct alignas(64) Note { // one cache line each: the worker writes the next while the parent reads
    std::int32_t outcome;
    std::uint32_t simd; // the environment the call left, when it changed it
    std::uint16_t x87;
    std::uint8_t changed;
};
// An exception's what(), apart from the notes: the parent reads a case's only when it threw, so
// that the notes it reads for every case stay small.
struct Thrown {
    char text[161];
};

// The worker writes `done` after every call: the parent reads answers as they come, and charges
// a crash or a hang to the first case not done. It learns that a request has ended from
// `finished`, in a cache line of its own, written once per request: spinning on a line the worker
// writes at every call would move that line between the cores at every call.
// Requests and replies pass through the shared memory too, in rings of a few (a request's seq
// picks its slot): each side looks for what it waits on for a moment before it sleeps, and rings
// the other's doorbell (a byte on the socket) only when the other has said it sleeps. A sleeping
// process (a halted virtual CPU, in a virtual machine) takes tens of microseconds to wake, longer
// than a batch takes to answer; a system call per request was most of what a batch cost. Who
// sleeps stores its flag, then looks once more; who wakes stores its data, then looks at the
// flag: both in sequential consistency, so that one of them sees the other (no lost wake-up).
constexpr std::uint32_t ring = 4;
struct Header {
    alignas(64) std::atomic<std::uint32_t> done;     // cases [0, done) answered
    alignas(64) std::atomic<std::uint32_t> finished; // the last request answered, by its seq
    Reply replies[ring];
    alignas(64) std::atomic<std::uint32_t> posted; // the last request sent, by its seq
    Request requests[ring];
    alignas(64) std::atomic<std::uint32_t> worker_sleeps;
    alignas(64) std::atomic<std::uint32_t> parent_sleeps;
    // When the worker finds its socket closed or replaced by the plugin, it ends, leaving here
    // the requests (by seq) since it last found it intact: (lost_after, lost_through]. A call
    // of one of them is to blame, not the next case. lost_through ~0: while loading.
    alignas(64) std::atomic<std::uint32_t> lost_after;
    std::atomic<std::uint32_t> lost_through;
};
constexpr std::uint32_t lost_while_loading = ~0u;

// Spins (with pause) while `waiting` says so, for at most `limit`; true when it stopped waiting.
template <class Waiting>
bool spin_while(Waiting&& waiting, std::chrono::microseconds limit) {
    auto start = Clock::now();
    for (;;) {
        for (int i = 0; i < 64; ++i) {
            if (!waiting()) return true;
            __builtin_ia32_pause();
        }
        if (Clock::now() - start > limit) return false;
    }
}

struct Layout {
    std::size_t shapes, lines, answers, notes, thrown, size;
    Layout() {
        shapes = sizeof(Header);
        lines = shapes + capacity * sizeof(lq_shape);
        answers = lines + capacity * sizeof(lq_line);
        notes = answers + capacity * sizeof(lq_answer);
        thrown = notes + capacity * sizeof(Note);
        size = thrown + capacity * sizeof(Thrown);
    }
};

struct Shared {
    void* base = nullptr;
    Layout at;
    Header* header() const { return static_cast<Header*>(base); }
    template <class T>
    T* array(std::size_t offset) const {
        return reinterpret_cast<T*>(static_cast<char*>(base) + offset);
    }
    lq_shape* shapes() const { return array<lq_shape>(at.shapes); }
    lq_line* lines() const { return array<lq_line>(at.lines); }
    lq_answer* answers() const { return array<lq_answer>(at.answers); }
    Note* notes() const { return array<Note>(at.notes); }
    Thrown* thrown() const { return array<Thrown>(at.thrown); }
};

// Writes all of it on the socket; a reader that has gone away is an error (EPIPE), not a SIGPIPE
// that would end this process.
bool write_exactly(int fd, const void* p, std::size_t n) {
    const char* c = static_cast<const char*>(p);
    while (n > 0) {
        ssize_t put = ::send(fd, c, n, MSG_NOSIGNAL);
        if (put < 0 && errno == EINTR) continue;
        if (put < 0 && errno == EAGAIN) {
            pollfd out{fd, POLLOUT, 0};
            ::poll(&out, 1, 100);
            continue;
        }
        if (put <= 0) return false;
        c += put, n -= std::size_t(put);
    }
    return true;
}

// A plugin's text, bounded and printable: at most `max` bytes up to its first NUL, control
// characters as spaces.
std::string plugin_text(const char* s, std::size_t max) {
    if (!s) return "";
    std::string out(s, strnlen(s, max));
    for (char& c : out)
        if (static_cast<unsigned char>(c) < 0x20 || c == 0x7F) c = ' ';
    return out;
}

// ---- the worker's side

// What the worker offers of one solver, whichever ABI the plugin speaks.
struct Offered {
    const char* name;
    int precision, answers, parametrisation, surface, carries;
    unsigned shapes;
    const char* mapping;
    int (*solve)(void*, const lq_shape*, const lq_line*, lq_answer*);
    void* self;
    int inside = 0, contact = 0;
    int (*solve_batch)(void*, int, const lq_shape*, const lq_line*, lq_answer*) = nullptr;
    int on_surface = 0, tangent = 0;
    double tolerance_absolute = 0, tolerance_relative = 0, negative_zero = 0;
    int (*sense)(void*, const lq_shape*, const double*, const double*, int*) = nullptr;
};

// A double for the hello line exactly, NaN and infinities included (JSON numbers hold neither):
// the parent checks the value.
std::string exact_text(double x) {
    char text[64];
    std::snprintf(text, sizeof text, "%a", x);
    return text;
}

jsonl::Json state_json(FpState s) {
    return {{"simd", s.simd}, {"x87", s.x87}};
}

// The worker's socket as it was given: a plugin may close every descriptor it did not open (as a
// daemon does) or open another file onto the same number, and the worker must tell that apart
// from its parent going away.
struct stat given_socket {};

bool socket_intact() {
    for (int fd : {request_fd, reply_fd}) {
        struct stat now {};
        if (::fstat(fd, &now) != 0 || now.st_dev != given_socket.st_dev ||
            now.st_ino != given_socket.st_ino)
            return false;
    }
    return true;
}

// The last request answered before the socket was last found intact.
std::uint32_t intact_through = 0;

// Checks the socket (two system calls, dear beside a request of cheap solves: so not after each
// request, but where the parent asks, before sleeping and when the socket fails); ends the
// worker, leaving word of the requests since the last check, when a call has taken it.
void check_socket(Header* h, std::uint32_t answered_through) {
    if (socket_intact()) {
        intact_through = answered_through;
        return;
    }
    h->lost_after.store(intact_through);
    h->lost_through.store(answered_through);
    _exit(5);
}

void say_hello(const jsonl::Json& hello) {
    std::string line = jsonl::dump(hello) + "\n";
    if (!write_exactly(reply_fd, line.data(), line.size())) _exit(3);
}

[[noreturn]] void refuse_to_load(const std::string& why) {
    say_hello({{"ok", false}, {"error", why}});
    _exit(2);
}

// Ends the worker when its parent is gone (a killed audit), even while a plugin's call hangs.
void watch_parent() {
    pid_t parent = ::getppid();
    std::thread([parent] {
        for (;;) {
            std::this_thread::sleep_for(std::chrono::milliseconds(100));
            if (::getppid() != parent) _exit(71);
        }
    }).detach();
}

// The plugin loaded and its entry asked for its solvers (ABI 2, else 1): what it offers, and the
// floating-point environment before and after. Refuses (ending the worker) when it cannot.
struct Loaded {
    std::vector<Offered> offered;
    int abi = LQ_ABI;
    FpState before{}, after{};
};
Loaded load(const std::string& path) {
    Loaded out;
    out.before = numeric::fp_state();
    void* lib = ::dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!lib) refuse_to_load(std::string("cannot load it: ") + ::dlerror());
    auto entry = reinterpret_cast<lq_plugin_entry>(::dlsym(lib, "linequad_audit_plugin"));
    if (!entry) refuse_to_load("exports no linequad_audit_plugin (see linequad/audit_plugin.h)");
    const lq_solver* array = nullptr;
    int n = -1;
    try {
        // Each ABI from the newest: a plugin answers -1 to one it was not built for.
        for (out.abi = LQ_ABI; out.abi >= 1; --out.abi)
            if ((n = entry(out.abi, &array)) >= 0) break;
    } catch (const std::exception& e) {
        refuse_to_load(std::string("its linequad_audit_plugin threw: ") + e.what());
    } catch (...) {
        refuse_to_load("its linequad_audit_plugin threw");
    }
    if (n < 0) refuse_to_load("does not speak the plugin ABI 4, 3, 2 or 1");
    if (n == 0 || !array) refuse_to_load("offers no solver");
    if (n > 256) refuse_to_load("offers " + std::to_string(n) + " solvers (at most 256)");
    out.after = numeric::fp_state();
    for (int i = 0; i < n; ++i) {
        if (out.abi == 1) {
            const lq_solver_v1& s = reinterpret_cast<const lq_solver_v1*>(array)[i];
            out.offered.push_back({s.name, s.precision, s.answers, s.parametrisation, s.surface,
                                   s.carries, s.shapes, s.mapping, s.solve, s.self});
        } else if (out.abi == 2) {
            const lq_solver_v2& s = reinterpret_cast<const lq_solver_v2*>(array)[i];
            out.offered.push_back({s.name, s.precision, s.answers, s.parametrisation, s.surface,
                                   s.carries, s.shapes, s.mapping, s.solve, s.self, s.inside,
                                   s.contact, s.solve_batch});
        } else if (out.abi == 3) {
            const lq_solver_v3& s = reinterpret_cast<const lq_solver_v3*>(array)[i];
            out.offered.push_back({s.name, s.precision, s.answers, s.parametrisation, s.surface,
                                   s.carries, s.shapes, s.mapping, s.solve, s.self, s.inside,
                                   s.contact, s.solve_batch, s.start_on_surface, s.tangent,
                                   s.tolerance_absolute, s.tolerance_relative, s.negative_zero});
        } else {
            const lq_solver& s = array[i];
            out.offered.push_back(
                {s.name, s.precision, s.answers, s.parametrisation, s.surface, s.carries, s.shapes,
                 s.mapping, s.solve, s.self, s.inside, s.contact, s.solve_batch, s.start_on_surface,
                 s.tangent, s.tolerance_absolute, s.tolerance_relative, s.negative_zero, s.sense});
        }
    }
    return out;
}

// The first line the worker writes: what the plugin declares, for the parent to check.
jsonl::Json hello(const Loaded& l) {
    jsonl::Json solvers = jsonl::Json::array();
    for (const Offered& o : l.offered)
        solvers.push_back({{"name", o.name ? std::string(o.name, strnlen(o.name, 4096)) : ""},
                           {"has_name", o.name != nullptr},
                           {"precision", o.precision},
                           {"answers", o.answers},
                           {"parametrisation", o.parametrisation},
                           {"surface", o.surface},
                           {"carries", o.carries},
                           {"shapes", o.shapes},
                           {"mapping", plugin_text(o.mapping, 4096)},
                           {"solve", o.solve != nullptr},
                           {"inside", o.inside},
                           {"contact", o.contact},
                           {"start_on_surface", o.on_surface},
                           {"tangent", o.tangent},
                           {"tolerance_absolute", exact_text(o.tolerance_absolute)},
                           {"tolerance_relative", exact_text(o.tolerance_relative)},
                           {"negative_zero", exact_text(o.negative_zero)},
                           {"batch", o.solve_batch != nullptr},
                           {"sense", o.sense != nullptr}});
    return {{"ok", true},
            {"abi", l.abi},
            {"before", state_json(l.before)},
            {"loaded", state_json(l.after)},
            {"solvers", solvers}};
}

// The worker answering requests: each call in the environment loading left, noted if it leaves
// another; an exception caught and named; `done` advanced after every call.
class Answerer {
  public:
    Answerer(const Shared& shared, FpState loaded) : sh_(shared), loaded_(loaded) {}
    // Request q with solver o; its reply (the calls' time, and whether a packet was declined).
    Reply answer(const Request& q, const Offered& o) const {
        Reply r{reply_magic, q.seq, all_answered, 0, 0};
        auto start = Clock::now();
        if (q.sides) {
            for (std::uint32_t i = q.first; i < q.count; ++i)
                one(i, [&](lq_answer& a) { return side(i, o, a); });
        } else if (q.batch && o.solve_batch) {
            if (!packet(q, o)) r.status = batch_declined;
        } else {
            for (std::uint32_t i = q.first; i < q.count; ++i)
                one(i, [&](lq_answer& a) {
                    return o.solve(o.self, &sh_.shapes()[i], &sh_.lines()[i], &a);
                });
        }
        r.ns = std::uint64_t(
            std::chrono::duration_cast<std::chrono::nanoseconds>(Clock::now() - start).count());
        return r;
    }

  private:
    void settle() const {
        if (numeric::fp_state() != loaded_) numeric::set_fp_state(loaded_);
    }
    void note_environment(Note& note) const {
        FpState now = numeric::fp_state();
        note.changed = now != loaded_;
        note.simd = now.simd, note.x87 = now.x87;
    }
    // Case i by `call` (its solve, or its sense), into answer i; `done` advanced after it.
    template <class Call>
    void one(std::uint32_t i, Call call) const {
        lq_answer& a = sh_.answers()[i];
        Note& note = sh_.notes()[i];
        a = lq_answer{};
        settle();
        try {
            note.outcome = call(a) == 0 ? answered : returned_nonzero;
        } catch (const std::exception& e) {
            note.outcome = threw;
            char* text = sh_.thrown()[i].text;
            std::strncpy(text, e.what() ? e.what() : "", sizeof(Thrown::text) - 1);
            text[sizeof(Thrown::text) - 1] = 0;
        } catch (...) {
            note.outcome = threw_other;
        }
        note_environment(note);
        sh_.header()->done.store(i + 1, std::memory_order_release);
    }
    // The sense entry on case i's shape, at its line's point and direction: the side it writes
    // is handed back in the answer's `count` (a solver without the entry declines).
    int side(std::uint32_t i, const Offered& o, lq_answer& a) const {
        if (!o.sense) return 1;
        const lq_line& l = sh_.lines()[i];
        int at = 0;
        int rc = o.sense(o.self, &sh_.shapes()[i], l.L0, l.v, &at);
        a.count = at;
        return rc;
    }
    // A packet through the batch entry: true when it answered.
    bool packet(const Request& q, const Offered& o) const {
        for (std::uint32_t i = q.first; i < q.count; ++i)
            sh_.answers()[i] = lq_answer{}, sh_.notes()[i] = Note{};
        settle();
        int rc = -1;
        try {
            rc = o.solve_batch(o.self, int(q.count - q.first), sh_.shapes() + q.first,
                               sh_.lines() + q.first, sh_.answers() + q.first);
        } catch (...) {
            rc = -1;
        }
        note_environment(sh_.notes()[q.first]);
        sh_.header()->done.store(q.count, std::memory_order_release);
        return rc == 0;
    }
    const Shared& sh_;
    FpState loaded_;
};

// Waits for request `next` to be posted: a moment spinning, then asleep until the parent rings.
// False when the parent has gone.
bool wait_for_request(Header* h, std::uint32_t next) {
    auto waiting = [&] { return std::int32_t(h->posted.load() - next) < 0; };
    while (!spin_while(waiting, std::chrono::microseconds(300))) {
        check_socket(h, next - 1); // asleep on a socket taken, it would never wake
        h->worker_sleeps.store(1);
        if (waiting()) {
            char bell[64];
            ssize_t n = ::read(request_fd, bell, sizeof bell);
            if (n == 0 || (n < 0 && errno != EINTR)) {
                check_socket(h, next - 1); // taken while it slept, by a helper the plugin forked
                return false;
            }
        }
        h->worker_sleeps.store(0);
    }
    return true;
}

} // namespace

int plugin_worker_main(const std::string& path) {
    ::signal(SIGPIPE, SIG_IGN); // a parent gone: writes fail, and the worker ends
    watch_parent();
    struct stat st {};
    Shared shared;
    if (::fstat(shared_fd, &st) != 0 || std::size_t(st.st_size) < shared.at.size) {
        std::fprintf(stderr, "linequad plugin-worker: run by linequad itself, not by hand\n");
        return 2;
    }
    shared.base = ::mmap(nullptr, shared.at.size, PROT_READ | PROT_WRITE, MAP_SHARED, shared_fd, 0);
    if (shared.base == MAP_FAILED || ::fstat(request_fd, &given_socket) != 0) return 2;
    Header* h = shared.header();
    Loaded loaded = load(path);
    if (!socket_intact()) {
        h->lost_through.store(lost_while_loading);
        _exit(5);
    }
    say_hello(hello(loaded));
    Answerer answerer(shared, loaded.after);
    for (std::uint32_t next = 1;; ++next) {
        if (!wait_for_request(h, next)) return 0; // the parent is done
        Request q = h->requests[next % ring];
        if (q.magic != request_magic || q.seq != next || q.solver >= loaded.offered.size() ||
            q.count > capacity || q.first > q.count)
            return 4;
        h->replies[next % ring] = answerer.answer(q, loaded.offered[q.solver]);
        if (q.check_socket) check_socket(h, next);
        h->finished.store(next);
        if (h->parent_sleeps.load()) {
            char bell = 1;
            if (!write_exactly(reply_fd, &bell, 1)) {
                check_socket(h, next);
                return 0;
            }
        }
    }
}

// ---- the parent's side

std::string solver_name_problem(const std::string& name) {
    if (name.empty()) return "has no name";
    if (name.size() > 64) return "has a name longer than 64 characters";
    for (char c : name)
        if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '.' || c == '+' ||
              c == '-'))
            return "has a character other than letters, digits and _ . + - in its name";
    if (!std::isalnum(static_cast<unsigned char>(name[0])))
        return "has a name that starts with a punctuation mark";
    return "";
}

namespace {

// The linequad program that runs workers (see PluginOptions::program).
std::string worker_program(const PluginOptions& o) {
    if (!o.program.empty()) return o.program;
    if (const char* e = std::getenv("LINEQUAD_PROGRAM"); e && *e) return e;
    std::string me = process::self();
    std::size_t slash = me.rfind('/');
    if (me.substr(slash == std::string::npos ? 0 : slash + 1) == "linequad") return me;
    return LINEQUAD_INSTALLED_PROGRAM;
}

// A distinct text of a plugin's own (an exception's what(), an unrepresented reason) as a stable
// C string for Result::error_field; after a thousand of them, one name for the rest, so that a
// plugin cannot grow the report (or this process) without bound.
const char* own_words(const std::string& text) {
    static std::mutex m;
    static std::set<std::string, std::less<>> seen;
    std::lock_guard<std::mutex> lock(m);
    if (seen.size() >= 1000 && !seen.count(text)) return interned("(another text of its own)");
    return seen.insert(text).first->c_str();
}

ErrorCode code_named(const std::string& name) {
    for (int c = int(ErrorCode::not_a_number); c < int(ErrorCode::foreign); ++c)
        if (name == code_name(ErrorCode(c))) return ErrorCode(c);
    return ErrorCode::foreign;
}

// The plugin's answer as a Result; one that breaks the ABI's rules is the solver's own error,
// named for what is wrong with it. Unrepresented: nullopt, with the library's reason.
} // namespace

ExternalAnswer from_plugin_answer(const lq_answer& a) {
    ExternalAnswer out;
    read_plugin_answer(a, out);
    return out;
}

void read_plugin_answer(const lq_answer& a, ExternalAnswer& out) {
    auto own = [&](const char* why) { out.result = Result::failure(ErrorCode::foreign, why); };
    out.unrepresented = "";
    switch (a.status) {
    case LQ_UNREPRESENTED:
        out.result.reset();
        out.unrepresented = own_words(plugin_text(a.error, sizeof a.error));
        return;
    case LQ_REFUSED: {
        std::string words = plugin_text(a.error, sizeof a.error);
        if (words.empty()) words = "refused without a name";
        ErrorCode code = code_named(words);
        out.result =
            Result::failure(code, code == ErrorCode::foreign ? own_words(words) : "plugin");
        return;
    }
    case LQ_ON_SURFACE: {
        if (a.surface_part < 0 || a.surface_part > 2) return own("a surface part out of range");
        Result& r = out.result.emplace();
        r.on_surface = true, r.s0 = a.s0, r.s1 = a.s1;
        r.surface_part = Part(a.surface_part);
        return;
    }
    case LQ_HITS: {
        if (a.count < 0 || a.count > max_hits) return own("a hit count out of range");
        Result& r = out.result.emplace();
        for (int i = 0; i < a.count; ++i) {
            const lq_hit& h = a.hits[i];
            if (h.kind < 0 || h.kind > 1 || h.part < 0 || h.part > 2)
                return own("a hit kind or part out of range");
            r.hits[r.count++] =
                Hit{h.t, {h.p[0], h.p[1], h.p[2]}, NAN, HitKind(h.kind), Part(h.part), false};
        }
        return;
    }
    }
    own("an answer status out of range");
}

// The shape's fields in the order of its table (linequad/audit_plugin.h lists them), a point as
// three numbers, then its options (a closed solid by definition: finite, no caps, one nappe).
lq_shape to_plugin_shape(const Shape& s) {
    lq_shape out{};
    out.kind = int(s.index());
    std::visit(
        [&](const auto& x) {
            using S = std::decay_t<decltype(x)>;
            int at = 0;
            auto put = [&](const auto& value) {
                using V = std::decay_t<decltype(value)>;
                if constexpr (std::is_same_v<V, Vec3>) {
                    for (int k = 0; k < 3; ++k)
                        out.p[at++] = value[k];
                } else if constexpr (std::is_same_v<V, std::array<double, 10>>) {
                    for (double c : value)
                        out.p[at++] = c;
                } else {
                    out.p[at++] = value;
                }
            };
            detail::for_each_field<S>([&](const auto& f) { put(x.*f.member); });
            if constexpr (has_coincident<S>) put(x.coincident ? 1.0 : 0.0);
            out.finite = has_finite_extent(x), out.caps = has_caps(x), out.nappes = nappes_of(x);
        },
        s);
    return out;
}

namespace {

// What a plugin wrote, kept for the report: its first lines, and how much in all.
struct Written {
    static constexpr std::size_t keep_bytes = 600;
    static constexpr int keep_lines = 5;
    std::string head;
    std::uint64_t bytes = 0;
    int lines = 0;
    void add(std::string_view s) {
        bytes += s.size();
        for (char c : s) {
            if (lines >= keep_lines || head.size() >= keep_bytes) return;
            if (c == '\n') ++lines;
            head += (static_cast<unsigned char>(c) < 0x20 && c != '\n') ? ' ' : c;
        }
    }
};

} // namespace

struct PluginWorker::Impl {
    std::string plugin, program;
    double timeout;
    std::vector<DeclaredSolver> solvers;
    std::string solvers_text; // the hello's solvers, to check a restarted worker against
    std::string load_environment;
    FpState loaded{};
    std::vector<Written> written;     // per solver
    int writing = -1;                 // the solver whose request is in flight (-1: loading)
    std::string broken;               // why no worker can be started any more
    std::vector<int> restarts;        // per solver: workers it ended (a crash, an exit, a hang)
    std::vector<int> batch_fallbacks; // per solver: packets asked again one case at a time

    pid_t pid = -1;
    // One socket both ways (requests, replies; a send never raises SIGPIPE), and the pipe of the
    // worker's standard output and error.
    int channel = -1, output = -1, memory = -1;
    Shared shared;
    std::uint32_t seq = 0;
    std::mutex one_request;

    ~Impl() {
        stop_worker();
        if (shared.base) ::munmap(shared.base, shared.at.size);
        if (memory >= 0) ::close(memory);
    }

    void close_pipes() {
        for (int* fd : {&channel, &output})
            if (*fd >= 0) ::close(*fd), *fd = -1;
    }

    // Ends the worker (if it runs) and everything it started: it leads a process group of its
    // own, so a helper a plugin forked (which would hold the worker's socket open and outlive the
    // audit) ends with it. Returns how the worker ended.
    int stop_worker() {
        int status = 0;
        if (pid > 0) {
            ::kill(-pid, SIGKILL);
            ::kill(pid, SIGKILL);
            while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
            }
            pid = -1;
        }
        drain_output();
        close_pipes();
        return status;
    }

    // Whether the worker has ended, left unreaped: while it is a zombie its process group's id
    // cannot be taken by another process, so stop_worker() ends the group (helpers it forked)
    // safely before reaping it, and returns how it ended.
    bool has_ended() const {
        siginfo_t info{};
        return pid > 0 && ::waitid(P_PID, id_t(pid), &info, WEXITED | WNOHANG | WNOWAIT) == 0 &&
               info.si_pid == pid;
    }

    // The worker's status once its reply pipe closed: reaped if it ended (waiting a little for
    // it), killed if it lives on without it.
    int reap() {
        for (int i = 0; i < 100; ++i) {
            if (has_ended()) return stop_worker();
            std::this_thread::sleep_for(std::chrono::milliseconds(2));
        }
        return stop_worker();
    }

    void drain_output() {
        if (output < 0) return;
        char buf[4096];
        for (;;) {
            ssize_t n = ::read(output, buf, sizeof buf);
            if (n < 0 && errno == EINTR) continue;
            if (n <= 0) return;
            if (writing >= 0 && std::size_t(writing) < written.size())
                written[std::size_t(writing)].add({buf, std::size_t(n)});
            else
                for (Written& w : written) // while loading: every solver's
                    w.add({buf, std::size_t(n)});
            if (written.empty()) load_output.add({buf, std::size_t(n)});
        }
    }
    Written load_output; // before the solvers are known

    void create_memory() {
        memory = ::memfd_create("linequad-plugin", MFD_CLOEXEC);
        if (memory < 0 || ::ftruncate(memory, off_t(shared.at.size)) != 0)
            throw std::runtime_error(
                plugin + ": cannot make the worker's shared memory: " + std::strerror(errno));
        shared.base =
            ::mmap(nullptr, shared.at.size, PROT_READ | PROT_WRITE, MAP_SHARED, memory, 0);
        if (shared.base == MAP_FAILED) {
            shared.base = nullptr;
            throw std::runtime_error(
                plugin + ": cannot map the worker's shared memory: " + std::strerror(errno));
        }
    }

    // Starts a worker: "" when it runs and has said hello, else why not.
    std::string spawn_worker() {
        // A new worker counts requests from 1, and nothing of the last one's is left to read.
        std::memset(shared.base, 0, sizeof(Header));
        seq = 0;
        int sv[2], out[2];
        if (::socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, sv) != 0)
            return std::string("socketpair: ") + std::strerror(errno);
        if (::pipe2(out, O_CLOEXEC) != 0) {
            ::close(sv[0]), ::close(sv[1]);
            return std::string("pipe: ") + std::strerror(errno);
        }
        // The child's ends above the numbers they are given there, so that no dup2 of one lands
        // on another before it is moved.
        int child[3] = {::fcntl(sv[1], F_DUPFD_CLOEXEC, 16), ::fcntl(memory, F_DUPFD_CLOEXEC, 16),
                        ::fcntl(out[1], F_DUPFD_CLOEXEC, 16)};
        ::close(sv[1]), ::close(out[1]);
        channel = sv[0], output = out[0];
        ::fcntl(channel, F_SETFL, O_NONBLOCK);
        ::fcntl(output, F_SETFL, O_NONBLOCK);

        posix_spawn_file_actions_t fa;
        posix_spawn_file_actions_init(&fa);
        posix_spawn_file_actions_addopen(&fa, 0, "/dev/null", O_RDONLY, 0);
        posix_spawn_file_actions_adddup2(&fa, child[2], 1);
        posix_spawn_file_actions_adddup2(&fa, child[2], 2);
        posix_spawn_file_actions_adddup2(&fa, child[0], request_fd);
        posix_spawn_file_actions_adddup2(&fa, child[0], reply_fd);
        posix_spawn_file_actions_adddup2(&fa, child[1], shared_fd);
        posix_spawn_file_actions_addclosefrom_np(&fa, shared_fd + 1);
        posix_spawnattr_t attr;
        posix_spawnattr_init(&attr);
        // Its own process group: a terminal's Ctrl-C reaches linequad, which ends the worker.
        sigset_t none, defaults;
        sigemptyset(&none);
        sigemptyset(&defaults);
        for (int sig : {SIGINT, SIGTERM, SIGPIPE, SIGXFSZ, SIGHUP})
            sigaddset(&defaults, sig);
        posix_spawnattr_setpgroup(&attr, 0);
        posix_spawnattr_setsigmask(&attr, &none);
        posix_spawnattr_setsigdefault(&attr, &defaults);
        posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETPGROUP | POSIX_SPAWN_SETSIGMASK |
                                            POSIX_SPAWN_SETSIGDEF);
        std::vector<std::string> argv = {program, "plugin-worker", plugin};
        std::vector<char*> args;
        for (std::string& a : argv)
            args.push_back(a.data());
        args.push_back(nullptr);
        int rc = posix_spawn(&pid, program.c_str(), &fa, &attr, args.data(), environ);
        posix_spawn_file_actions_destroy(&fa);
        posix_spawnattr_destroy(&attr);
        for (int fd : child)
            ::close(fd);
        if (rc != 0) {
            pid = -1;
            close_pipes();
            return "cannot start the worker " + program + ": " + std::strerror(rc);
        }
        return read_hello();
    }

    // The worker's first line: what the plugin declares (or why it could not be loaded).
    std::string read_hello() {
        std::string line;
        auto deadline = Clock::now() + std::chrono::duration<double>(std::max(30.0, timeout));
        writing = -1;
        for (;;) {
            pollfd fds[2] = {{channel, POLLIN, 0}, {output, POLLIN, 0}};
            ::poll(fds, 2, 50);
            drain_output();
            char buf[4096];
            ssize_t n = ::read(channel, buf, sizeof buf);
            if (n > 0) {
                line.append(buf, std::size_t(n));
                std::size_t nl = line.find('\n');
                if (nl != std::string::npos) {
                    if (nl + 1 != line.size()) return "the worker said more than hello";
                    line.pop_back();
                    break;
                }
                if (line.size() > max_hello_bytes) return "the worker's hello is too long";
                continue;
            }
            if (n == 0 || (n < 0 && errno != EAGAIN && errno != EINTR)) {
                int status = reap();
                if (shared.header()->lost_through.load() == lost_while_loading)
                    return "it closed the worker's descriptors while loading" + loading_output();
                return "the worker ended while loading it: " + process::describe_status(status) +
                       loading_output();
            }
            if (stop_requested()) return "stopped while loading it";
            if (Clock::now() > deadline) {
                stop_worker();
                return "it did not load within " + std::to_string(int(std::max(30.0, timeout))) +
                       " s" + loading_output();
            }
        }
        return take_hello(line);
    }

    std::string loading_output() {
        std::string s = load_output.head;
        for (const Written& w : written)
            if (s.empty()) s = w.head;
        while (!s.empty() && (s.back() == '\n' || s.back() == ' '))
            s.pop_back();
        return s.empty() ? "" : " (it wrote: " + s + ")";
    }

    std::string take_hello(const std::string& line) {
        jsonl::Json hello;
        std::string why;
        if (!jsonl::parse(line, &hello, &why) || !hello.is_object())
            return "the worker's hello is not JSON: " + why;
        try {
            if (!hello.at("ok").get<bool>()) return hello.at("error").get<std::string>();
            std::string text = jsonl::dump(hello.at("solvers"));
            if (!solvers.empty()) // a restart: the same plugin must declare the same solvers
                return text == solvers_text ? "" : "it declared other solvers when loaded again";
            solvers_text = text;
            FpState before{hello.at("before").at("simd").get<std::uint32_t>(),
                           std::uint16_t(hello.at("before").at("x87").get<unsigned>())};
            loaded = {hello.at("loaded").at("simd").get<std::uint32_t>(),
                      std::uint16_t(hello.at("loaded").at("x87").get<unsigned>())};
            load_environment = numeric::fp_change(before, loaded);
            int index = 0;
            for (const jsonl::Json& s : hello.at("solvers")) {
                std::string which = "solver " + std::to_string(index++);
                if (!s.at("has_name").get<bool>()) return which + " has no name";
                DeclaredSolver d;
                d.name = s.at("name").get<std::string>();
                if (std::string p = solver_name_problem(d.name); !p.empty())
                    return which + " " + p + " (" + jsonl::dump(jsonl::Json(d.name)) + ")";
                which = "solver '" + d.name + "'";
                int precision = s.at("precision").get<int>();
                if (precision != 64 && precision != 32)
                    return which + ": precision must be 64 or 32, not " + std::to_string(precision);
                d.precision = precision == 32 ? Precision::binary32 : Precision::binary64;
                int answers = s.at("answers").get<int>();
                if (answers < LQ_ALL || answers > LQ_FIRST_EXIT)
                    return which + ": answers out of range";
                int abi = hello.at("abi").get<int>();
                if (answers == LQ_FIRST_EXIT && abi < 2)
                    return which + ": LQ_FIRST_EXIT needs ABI 2";
                d.answers = Answers(answers);
                int p = s.at("parametrisation").get<int>();
                if (p < LQ_LINE || p > LQ_SEGMENT) return which + ": parametrisation out of range";
                d.parametrisation = Parametrisation(p);
                int surface = s.at("surface").get<int>();
                if (surface < LQ_AS_POSED || surface > LQ_INFINITE)
                    return which + ": surface out of range";
                d.surface = Surface(surface);
                int inside = s.at("inside").get<int>(), contact = s.at("contact").get<int>();
                if (inside < LQ_INSIDE_AS_ANSWERS || inside > LQ_INSIDE_UNDEFINED ||
                    (inside == LQ_INSIDE_UNDEFINED && abi < 3))
                    return which + ": inside out of range (" + std::to_string(inside) + ")";
                if (contact != LQ_CONTACT_INTERVAL && contact != LQ_CONTACT_FIRST_POINT)
                    return which + ": contact out of range (" + std::to_string(contact) + ")";
                d.inside = StartInside(inside);
                d.contact_as_point = contact == LQ_CONTACT_FIRST_POINT;
                int on_surface = s.at("start_on_surface").get<int>();
                if (on_surface != LQ_ON_SURFACE_AS_INSIDE &&
                    on_surface != LQ_ON_SURFACE_BY_DIRECTION)
                    return which + ": start_on_surface out of range (" +
                           std::to_string(on_surface) + ")";
                d.on_surface = StartOnSurface(on_surface);
                int tangent = s.at("tangent").get<int>();
                if (tangent != LQ_TANGENT_HIT && tangent != LQ_TANGENT_NO_HIT)
                    return which + ": tangent out of range (" + std::to_string(tangent) + ")";
                d.tangent = TangentRule(tangent);
                // Read back exactly as the worker wrote them (a hex float, "nan", "inf"); text
                // that is not all one number reads as NaN, refused below naming the field.
                auto real = [&](const char* field) {
                    std::string text = s.at(field).get<std::string>();
                    char* end = nullptr;
                    double x = std::strtod(text.c_str(), &end);
                    return !text.empty() && end == text.c_str() + text.size() ? x : NAN;
                };
                d.tolerance = {real("tolerance_absolute"), real("tolerance_relative")};
                d.negative_zero = real("negative_zero");
                if (!s.at("solve").get<bool>()) return which + " has no solve function";
                unsigned shapes = s.at("shapes").get<unsigned>();
                unsigned every = (1u << shape_count) - 1;
                if (!(shapes & every)) return which + " takes no shape";
                d.shapes = shapes & every;
                int carries = s.at("carries").get<int>();
                d.points = carries & LQ_POINTS, d.kinds = carries & LQ_KINDS;
                d.parts = carries & LQ_PARTS;
                d.mapping = s.at("mapping").get<std::string>();
                d.batch = s.at("batch").get<bool>();
                d.sense = s.at("sense").get<bool>();
                if (std::string p = declaration_problem(declared_as_external(d)); !p.empty())
                    return p;
                for (const DeclaredSolver& other : solvers)
                    if (other.name == d.name) return which + " is declared twice";
                solvers.push_back(d);
            }
            written.assign(solvers.size(), load_output);
            restarts.assign(solvers.size(), 0);
            batch_fallbacks.assign(solvers.size(), 0);
        } catch (const jsonl::Json::exception& e) {
            return std::string("the worker's hello is malformed: ") + e.what();
        }
        return "";
    }

    bool ensure_worker() {
        if (pid > 0) return true;
        if (!broken.empty()) return false;
        if (std::string why = spawn_worker(); !why.empty()) {
            broken = why;
            stop_worker();
            return false;
        }
        return true;
    }

    // How a request ended.
    struct Waited {
        enum Kind { replied, ended, timed_out, stopped } kind;
        Reply reply{};
        std::string why; // for ended: how
    };

    // Waits for request `seq`'s reply, handing each case the worker has answered to `answered`
    // (with the count done so far) while it answers the rest: the parent reads and converts the
    // first answers while the worker computes the later ones.
    template <class Answered>
    Waited wait_reply(std::uint32_t seq, Answered&& answered) {
        Header* h = shared.header();
        auto finished = [&] { return std::int32_t(h->finished.load() - seq) >= 0; };
        auto reply = [&] { return Waited{Waited::replied, h->replies[seq % ring], ""}; };
        auto last_progress = Clock::now();
        std::uint32_t last_done = h->done.load(std::memory_order_acquire);
        // Looking at `done` draws its line from the worker's core: not more than every few
        // hundred nanoseconds while nothing changes, and for 200 microseconds before sleeping.
        for (;;) {
            if (finished()) return reply();
            std::uint32_t done = h->done.load(std::memory_order_acquire);
            if (done != last_done) {
                last_done = done, last_progress = Clock::now();
                answered(done);
                continue;
            }
            for (int i = 0; i < 64; ++i)
                __builtin_ia32_pause();
            if (Clock::now() - last_progress > std::chrono::microseconds(200)) break;
        }
        for (;;) {
            h->parent_sleeps.store(1);
            if (finished()) {
                h->parent_sleeps.store(0);
                return reply();
            }
            pollfd fds[2] = {{channel, POLLIN, 0}, {output, POLLIN, 0}};
            ::poll(fds, 2, 20);
            h->parent_sleeps.store(0);
            drain_output();
            if (fds[0].revents & (POLLIN | POLLHUP | POLLERR)) {
                char bells[256];
                ssize_t n = ::read(channel, bells, sizeof bells);
                if (n == 0 || (n < 0 && errno != EAGAIN && errno != EINTR)) {
                    if (finished()) return reply();
                    int status = reap();
                    return {Waited::ended, {}, process::describe_status(status)};
                }
            }
            if (stop_requested()) {
                stop_worker();
                return {Waited::stopped, {}, ""};
            }
            // A crash is told from a hang by the worker's own end, not by its socket closing: a
            // helper the plugin forked may hold the socket open after the worker died.
            if (has_ended()) {
                int status = stop_worker();
                if (finished()) return reply();
                return {Waited::ended, {}, process::describe_status(status)};
            }
            std::uint32_t done = h->done.load(std::memory_order_acquire);
            auto now = Clock::now();
            if (done != last_done) last_done = done, last_progress = now, answered(done);
            if (std::chrono::duration<double>(now - last_progress).count() > timeout) {
                stop_worker();
                return {Waited::timed_out, {}, ""};
            }
        }
    }

    void collect(std::uint32_t i, ExternalAnswer& a, bool sides) const {
        Note note = shared.notes()[i];
        a.environment = "";
        a.side = 0;
        switch (note.outcome) {
        case answered:
            if (!sides) {
                read_plugin_answer(shared.answers()[i], a);
            } else if (int side = shared.answers()[i].count; side == -1 || side == 1) {
                a.result = Result{}, a.side = side;
            } else {
                a.result = Result::failure(
                    ErrorCode::foreign,
                    own_words("its sense wrote side " + std::to_string(side) + ", not -1 or 1"));
            }
            break;
        case returned_nonzero:
            a.result = Result::failure(ErrorCode::foreign, sides ? "its sense returned nonzero"
                                                                 : "its solve returned nonzero");
            break;
        case threw:
            a.result =
                Result::failure(ErrorCode::foreign,
                                own_words("threw: " + plugin_text(shared.thrown()[i].text, 120)));
            break;
        case threw_other:
            a.result = Result::failure(ErrorCode::foreign, "threw: not a std::exception");
            break;
        default:
            a.result = Result::failure(ErrorCode::foreign, "the worker noted no outcome");
        }
        if (note.changed)
            a.environment = interned(numeric::fp_change(loaded, {note.simd, note.x87}));
    }

    // One solver's cases on their way through the worker: [0, cursor) read back, [0, filled)
    // written to the shared memory.
    struct Run {
        int s;
        const std::vector<Case>& posed;
        std::size_t base;
        std::uint32_t count;
        std::vector<ExternalAnswer>& out;
        bool batch;
        bool sides = false; // the sense entry's calls, not solve's
        std::uint32_t cursor = 0, filled = 0;
        std::uint32_t one_at_a_time_until = 0; // cases before it asked one per request
        struct Sent {
            std::uint32_t seq, from, to;
        };
        std::vector<Sent> sent{}; // every request of this run, for a worker that lost its socket
        double ns = 0;
        std::uint64_t timed = 0;
    };

    void fill(Run& r, std::uint32_t to) {
        for (; r.filled < to; ++r.filled) {
            const Case& c = r.posed[r.base + r.filled];
            shared.shapes()[r.filled] = to_plugin_shape(c.shape);
            shared.lines()[r.filled] = lq_line{{c.line.L0.x, c.line.L0.y, c.line.L0.z},
                                               {c.line.v.x, c.line.v.y, c.line.v.z},
                                               c.line.range.t0,
                                               c.line.range.t1};
        }
    }
    // The answers [cursor, done) read (a plugin cannot make this read past `count`).
    void take(Run& r, std::uint32_t done) {
        for (done = std::min(done, r.count); r.cursor < done; ++r.cursor)
            collect(r.cursor, r.out[r.base + r.cursor], r.sides);
    }

    // Requests of a few hundred cases kept two in flight, so that the worker answers one while
    // this process writes the next and reads the last (a packet solver's batch entry gets them
    // all in one call), until every case is answered and every request replied to, or the worker
    // ends or a stop is asked. Every reply is waited for even when the answers were all read
    // from the cases done: the last request's reply comes after the worker's socket check, and a
    // run that ended on its answers alone left a worker that found its socket taken to end in the
    // next run, which charged that run's first case and let the call to blame go (seen under
    // load: two one-case requests in flight, both answered before the first reply was read).
    Waited drive(Run& r) {
        // A few requests per batch: enough to overlap, few enough that a request's own cost
        // stays small beside its calls'.
        const std::uint32_t per_request = std::max<std::uint32_t>(64, (r.count + 3) / 4);
        Header* h = shared.header();
        using Sent = Run::Sent;
        Sent flight[2];
        int in_flight = 0;
        std::uint32_t next = r.cursor;
        r.sent.clear();                                     // a worker numbers its requests from 1
        h->done.store(r.cursor, std::memory_order_release); // the worker waits: nothing in flight
        while (r.cursor < r.count || in_flight > 0) {
            while (in_flight < 2 && next < r.count && !(r.batch && in_flight)) {
                std::uint32_t to =
                    r.batch ? r.count
                            : std::min(r.count,
                                       next + (next < r.one_at_a_time_until ? 1 : per_request));
                fill(r, to);
                // The socket is checked after the last request of a run (so that a call that
                // took it is looked for in this run's requests only) and after each one asked
                // alone to find that call.
                bool check = to == r.count || next < r.one_at_a_time_until;
                Request q{request_magic,     ++seq,           std::uint32_t(r.s), next, to,
                          r.batch ? 1u : 0u, check ? 1u : 0u, r.sides ? 1u : 0u};
                r.sent.push_back({q.seq, next, to});
                h->requests[q.seq % ring] = q;
                h->posted.store(q.seq);
                char bell = 1;
                if (h->worker_sleeps.load() && !write_exactly(channel, &bell, 1)) break;
                flight[in_flight++] = {q.seq, next, to};
                next = to;
            }
            if (in_flight == 0) return {Waited::ended, {}, process::describe_status(reap())};
            Sent oldest = flight[0];
            // A packet's answers are read only once its call has returned (and answered).
            bool packet = r.batch;
            Waited w = wait_reply(oldest.seq, [&](std::uint32_t done) {
                if (!packet) take(r, done);
            });
            if (w.kind != Waited::replied) return w;
            if (w.reply.magic != reply_magic || w.reply.seq != oldest.seq ||
                w.reply.status > batch_declined ||
                h->done.load(std::memory_order_acquire) < oldest.to) {
                stop_worker();
                return {Waited::ended, {}, "broke the worker's protocol"};
            }
            flight[0] = flight[1], --in_flight;
            if (w.reply.status == batch_declined) { // asked again one case at a time
                ++batch_fallbacks[std::size_t(r.s)];
                r.batch = false;
                next = r.cursor;
                h->done.store(r.cursor, std::memory_order_release); // the worker waits again
                continue;
            }
            take(r, oldest.to);
            r.ns += double(std::min<std::uint64_t>(w.reply.ns, std::uint64_t(1) << 50));
            r.timed += oldest.to - oldest.from;
        }
        return {Waited::replied, {}, ""};
    }

    // After the worker ended: whether it ended because a call took its socket (closed it, or
    // opened another file on its number). Then the answers before the requests it names stand,
    // and their cases are asked again one per request, checked after each, so that the call to
    // blame is charged, not the next case.
    bool took_socket(Run& r) {
        Header* h = shared.header();
        std::uint32_t after = h->lost_after.load(), through = h->lost_through.load();
        if (through == 0 || through == lost_while_loading) return false;
        h->lost_through.store(0);
        std::uint32_t from = r.count, to = 0;
        for (const Run::Sent& q : r.sent)
            if (std::int32_t(q.seq - after) > 0 && std::int32_t(q.seq - through) <= 0)
                from = std::min(from, q.from), to = std::max(to, q.to);
        if (from >= to || to > r.count) return false; // not this run's requests
        ++restarts[std::size_t(r.s)];
        take(r, std::min(from, h->done.load(std::memory_order_acquire)));
        r.cursor = std::min(r.cursor, from);
        if (r.cursor < from) return true; // asked again from the first answer not read
        r.batch = false;
        if (to - from > 1) {
            r.one_at_a_time_until = std::max(r.one_at_a_time_until, to);
            return true;
        }
        r.out[r.base + r.cursor].result = Result::failure(
            ErrorCode::foreign, "crashed the worker: closed or replaced its descriptors");
        ++r.cursor;
        return true;
    }

    // Solver s on posed[base, base + count), through cases [0, count) of the shared memory, into
    // out[base + i]; false when stopped. When the worker ends, the cases it answered stand; a
    // packet's call is asked again one case at a time (which case failed is not known); else the
    // first case it did not answer is charged with how it ended, and the worker is started again
    // for the rest.
    bool run(Run& r) {
        while (r.cursor < r.count) {
            if (!ensure_worker()) {
                const char* why = own_words("the worker could not be started again: " + broken);
                for (std::uint32_t i = r.cursor; i < r.count; ++i)
                    r.out[r.base + i].result = Result::failure(ErrorCode::foreign, why);
                return true;
            }
            writing = r.s;
            Waited w = drive(r);
            if (w.kind == Waited::stopped) return false;
            if (w.kind != Waited::replied) {
                stop_worker();
                // Before the answers are taken as complete: a worker that found its socket
                // taken after its last request has answered every case, one of them by a call
                // to blame.
                if (took_socket(r)) continue;
            }
            if (r.cursor >= r.count) break;
            stop_worker();
            if (r.batch) {
                ++batch_fallbacks[std::size_t(r.s)];
                r.batch = false;
                continue;
            }
            take(r, std::clamp(shared.header()->done.load(std::memory_order_acquire), r.cursor,
                               r.count));
            if (r.cursor >= r.count) break;
            ++restarts[std::size_t(r.s)];
            std::string name = w.kind == Waited::timed_out ? "timed out" : w.why;
            r.out[r.base + r.cursor].result = Result::failure(ErrorCode::foreign, own_words(name));
            ++r.cursor;
        }
        return true;
    }

    // Solver s's solve (or, `sides`, its sense entry) on every case, a shared memory's worth at
    // a time.
    bool answer(int s, const std::vector<Case>& posed, std::vector<ExternalAnswer>& out, double* ns,
                bool sides);
};

PluginWorker::PluginWorker(const std::string& plugin, const PluginOptions& o)
    : impl_(std::make_unique<Impl>()) {
    Impl& m = *impl_;
    m.plugin = plugin;
    m.program = worker_program(o);
    m.timeout = o.timeout_seconds > 0 ? o.timeout_seconds : 5;
    m.create_memory();
    if (std::string why = m.spawn_worker(); !why.empty()) {
        m.stop_worker();
        throw std::runtime_error(plugin + ": " + why);
    }
}

PluginWorker::~PluginWorker() = default;

const std::string& PluginWorker::plugin() const {
    return impl_->plugin;
}
const std::vector<DeclaredSolver>& PluginWorker::solvers() const {
    return impl_->solvers;
}
const std::string& PluginWorker::load_environment() const {
    return impl_->load_environment;
}

bool PluginWorker::answer(int s, const std::vector<Case>& posed, std::vector<ExternalAnswer>& out,
                          double* ns) {
    return impl_->answer(s, posed, out, ns, false);
}
bool PluginWorker::sides(int s, const std::vector<Case>& at, std::vector<ExternalAnswer>& out) {
    return impl_->answer(s, at, out, nullptr, true);
}

bool PluginWorker::Impl::answer(int s, const std::vector<Case>& posed,
                                std::vector<ExternalAnswer>& out, double* ns, bool sides) {
    Impl& m = *this;
    std::lock_guard<std::mutex> lock(m.one_request);
    out.resize(posed.size());
    double total = 0;
    std::uint64_t timed = 0;
    for (std::size_t base = 0; base < posed.size(); base += capacity) {
        auto count = std::uint32_t(std::min<std::size_t>(capacity, posed.size() - base));
        Impl::Run r{s, posed, base, count, out, !sides && m.solvers[std::size_t(s)].batch, sides};
        if (!m.run(r)) return false;
        total += r.ns, timed += r.timed;
    }
    m.drain_output(); // what it wrote while answering, for the report
    // The calls' own time per case, scaled to every case (those of crashed calls have none).
    if (ns) *ns = timed ? total / double(timed) * double(posed.size()) : 0;
    return true;
}

std::string PluginWorker::output(int s) const {
    return impl_->written.at(std::size_t(s)).head;
}
std::uint64_t PluginWorker::output_bytes(int s) const {
    return impl_->written.at(std::size_t(s)).bytes;
}
int PluginWorker::restarts(int s) const {
    return impl_->restarts.at(std::size_t(s));
}
int PluginWorker::batch_fallbacks(int s) const {
    return impl_->batch_fallbacks.at(std::size_t(s));
}

} // namespace linequad::audit
