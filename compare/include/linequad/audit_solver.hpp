// Someone else's solver in the audit: a callable per shape, with what it answers and how it takes
// a line declared, graded and timed in process beside linequad's own solvers, into one report.
//
//     linequad::audit::ExternalSolver mine;
//     mine.name = "mine";
//     mine.answers = linequad::audit::Answers::nearest;
//     mine.on<linequad::Cylinder>() = [](const linequad::Cylinder& c, const linequad::Line& l)
//     {..}; linequad::audit::Options o; o.solvers = {"correct", "mine"}; linequad::audit::run(o,
//     {mine});
//
// The case a library is graded on is the case it saw: the audit poses each case the way the
// solver declares (its surfaces closed or infinite, its line as a unit direction or a from-to
// segment, exactly representable), hands the posed case over, and solves the exact reference for
// that posed case. The report shows the posed case in its worst cases.
#pragma once

#include "linequad/audit.hpp"

#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>
#include <tuple>
#include <vector>

namespace linequad::audit {

// What the solver answers about a line and a shape.
enum class Answers : std::uint8_t {
    all,         // every hit in the range, in order of t (linequad's own solvers)
    nearest,     // the hit with the smallest t in the range, or none (a ray caster's closest hit)
    first_entry, // the first hit where the line is outside the closed solid just before it (a
                 // physics ray test: a solid the line starts in is ignored until it is left)
    first_exit,  // the first crossing where the line leaves the closed solid (Geant4's and
                 // VecGeom's DistanceToOut); asked only of lines that start inside the solid
};

// What a nearest or first-entry solver answers when its range starts inside the closed solid.
enum class StartInside : std::uint8_t {
    as_answers, // nothing special: the nearest hit, or the first entry, as Answers says
    no_hit,     // no hit when the start is strictly inside the solid
    at_t0,      // one hit at the range's start t0 (Geometric Tools' Ray3 queries)
    at_zero,    // one hit at t = 0 (Jolt's fraction 0, PhysX's initial overlap)
    undefined,  // not defined (VecGeom's DistanceToIn from inside): such cases are not asked
};

// What a start on the surface is answered as: as a start inside (the inside convention applies,
// unless it is no_hit), or by where the line goes (moving in: an entry at t0; moving out: no
// entry; VecGeom's and Geant4's rule).
enum class StartOnSurface : std::uint8_t { as_inside, by_direction };

// Whether a tangent touch counts as a hit (linequad's, Embree's) or not (VecGeom's Tube,
// EllipticalTube, Ellipsoid: a line that only touches does not enter).
enum class TangentRule : std::uint8_t { hit, no_hit };

// How far a library's surface may lie from the exact one by its own contract (VecGeom's
// kTolerance): absolute, in scene units, plus relative to the scene's magnitude (the largest of
// the shape's coordinates and sizes and of |L0|). A case whose answer is right for some solid S'
// with S shrunk by delta inside S' inside S grown by delta is counted within tolerance, not as a
// mismatch (docs/semantics.md says how that is proved).
struct Tolerance {
    double absolute = 0, relative = 0;
    bool none() const { return absolute == 0 && relative == 0; }
    double at(double magnitude) const { return absolute + relative * magnitude; }
};

// How the solver is handed the line, and what its t means.
enum class Parametrisation : std::uint8_t {
    line,           // L0, v and [t0, t1] as given; t along v
    unit_direction, // L0 and u = v/|v| rounded to the case's format, the range's ends times |v|
                    // (rounded); t is the distance along u as the library holds it
    segment,        // from L(t0) to L(t1) (a finite range only), rounded and adjusted so that
                    // to - from is exact; t is the fraction of the way, in [0, 1]
};

// Which surface of a case's shape the solver represents.
enum class Surface : std::uint8_t {
    as_posed, // the case's shape as it is
    closed,   // a finite solid closed by its discs (a collision shape): caps put on every case;
              // a shape that is not finite cannot be posed
    infinite, // the whole quadric (a CAD kernel's analytic surface); a cone with both nappes
};

const char* answers_name(Answers a);
const char* parametrisation_name(Parametrisation p);
const char* surface_name(Surface s);
const char* start_inside_name(StartInside s);

template <class S>
using ShapeCallable = std::function<std::optional<Result>(const S&, const Line&)>;
// A callable for every alternative of a shape variant.
template <class Variant>
struct ShapeCallablesOf;
template <class... S>
struct ShapeCallablesOf<std::variant<S...>> {
    using type = std::tuple<ShapeCallable<S>...>;
};
template <class Variant>
using ShapeCallables = typename ShapeCallablesOf<Variant>::type;

// One answer of a solver from outside, with what the audit notes beside it. The texts are
// stable strings (interned), so that an answer copies as plain data: the audit handles millions.
struct ExternalAnswer {
    std::optional<Result> result;   // nullopt: the library cannot represent the case (not graded)
    const char* unrepresented = ""; // why not, in the library's words, if it says
    const char* environment = "";   // how the call left the floating-point environment, if changed
    int side = 0; // a sense call's answer: -1 (f < 0) or +1; 0 where it failed (`result` says why)
};

class PluginWorker; // a plugin's solvers in a worker process (plugin_worker.hpp)

// What a library in linequad's process writes of its own (its warnings and internal errors, taken
// from its message hooks), kept for the report as a plugin worker's standard output and error are,
// and off the terminal: its first lines and how much it wrote in all. Shared by the threads that
// call the library.
class OwnOutput {
  public:
    static constexpr std::size_t kept = 4096; // bytes of its first messages, each kept whole
    void write(std::string_view text);
    std::string head() const;
    std::uint64_t bytes() const;
    void clear(); // a new run starts counting afresh

  private:
    mutable std::mutex lock_;
    std::string head_;
    std::uint64_t bytes_ = 0;
    bool full_ = false; // a message did not fit: the head is closed
};

// A solver from outside linequad. Each callable gets the posed case and returns the solver's
// answer as a linequad::Result (hits in order of t), or nullopt where the library cannot represent
// the case (counted as unrepresented, never graded); an empty callable: the library has no such
// shape. Refusals are Result::failure with the ErrorCode that fits (a library's own error that
// fits none is graded as a refusal the oracle does not make: ErrorCode::foreign).
//
// Its callables run in linequad's process, for speed; the floating-point environment is checked
// after every call and put back (a solver that changes it is reported as such). A plugin's
// solvers (load_plugin) run in a worker process instead.
struct ExternalSolver {
    std::string name;
    Precision precision = Precision::binary64; // binary32: posed float cases, graded in floats
    Answers answers = Answers::all;
    Parametrisation parametrisation = Parametrisation::line;
    Surface surface = Surface::as_posed;
    // Conventions the library keeps (graded as it means them, not as inaccuracy): what it answers
    // when the range starts inside the solid, and whether a line lying on the surface is answered
    // by one hit at the contact interval's first point in the range.
    StartInside inside = StartInside::as_answers;
    bool contact_as_point = false;
    // What a start on the surface is, whether a tangent touch is a hit, how thick its surfaces
    // are, and below how small a negative distance reads as 0 (in scene units: a t in
    // [-negative_zero / |v|, 0) is graded as 0).
    StartOnSurface on_surface = StartOnSurface::as_inside;
    TangentRule tangent = TangentRule::hit;
    Tolerance tolerance;
    double negative_zero = 0;
    // What its answers carry: hit points, tangent-or-cross kinds, the part (lateral or a disc)
    // of each hit. What it does not carry is not graded.
    bool points = true, kinds = true, parts = true;
    std::string mapping; // for the report: how a case is handed over, what cannot be represented
    std::string plugin;  // the shared library it came from (an absolute path), if any
    // Why `linequad replay` cannot run it, if it cannot (a Python callable, a C++ callable of the
    // caller's own): the report's replay commands then show the exact answer, and say this. Empty:
    // it can (linequad's peers; a plugin, given with --plugin).
    std::string not_replayable;
    // Where an in-process library's own messages go, if it has hooks for them (the peers'
    // adapters set it): counted in the report like a plugin's output. None: it writes nothing.
    std::shared_ptr<OwnOutput> own_output;
    // Its callable for shape S; an empty one: the library has no such shape.
    //     mine.on<Cylinder>() = [](const Cylinder& c, const Line& l) -> std::optional<Result> {..};
    template <class S>
    ShapeCallable<S>& on() {
        return std::get<ShapeCallable<S>>(callables);
    }
    template <class S>
    const ShapeCallable<S>& on() const {
        return std::get<ShapeCallable<S>>(callables);
    }
    ShapeCallables<Shape> callables;
    // A plugin's solver: its worker process and its index there; the callables are then empty.
    std::shared_ptr<PluginWorker> worker;
    int worker_index = -1;
    unsigned worker_shapes = 0; // bit k: takes the shape of index k in linequad::Shape (a
                                // plugin's, or a chunk callable's)
    // Or a callable answering a chunk of posed cases at once (a Python solver, through
    // linequad.audit: one call a chunk, not a case), one answer a case into `out` (sized for
    // them); it takes the shapes in worker_shapes, and answers what it cannot as failures of
    // those cases (it throws nothing). The floating-point environment is checked and put back
    // around each call, as for the callables.
    using ChunkCallable =
        std::function<void(const std::vector<Case>& posed, std::vector<ExternalAnswer>& out)>;
    ChunkCallable chunk;
    // Its side of a point, as its tracker's find-cell decides it (the plugin ABI's sense entry, or
    // a callable of the caller's own): -1 (f < 0) or +1 for a model's surface at p (a plane, a
    // quadric, a sphere or an axis-aligned cylinder), the particle moving along u; anything else
    // where it cannot say. None: the tracking audit finds that tracker's cells by the textbook's
    // sides (OpenMC's Surface::sense).
    using SenseCallable = std::function<int(const Shape&, Vec3 p, Vec3 u)>;
    SenseCallable sense;
    bool worker_sense = false; // a plugin's solver with the sense entry

    bool has_sense() const;
    // The sides of many points (each case: a shape, the point L0, the direction v) in out[i].side,
    // in order; a call that failed, crashed or answered something else than -1 or 1 has side 0
    // and a failure as its result. False when a stop request ended it.
    bool sides(const std::vector<Case>& at, std::vector<ExternalAnswer>& out) const;

    // Whether it takes this shape, or the shape of this index in linequad::Shape.
    bool takes(const Shape& s) const;
    bool takes_shape(std::size_t index) const;
    // One posed case: the answer and what was noted of the call. A crash or abort inside an
    // in-process callable (a signal) is caught: the answer is then a failure named "crashed".
    ExternalAnswer answer(const Shape& s, const Line& l) const;
    // Many posed cases, in order (a plugin's in one round trip to its worker, timed there).
    // Returns false when a stop request ended it: the answers are then incomplete. *ns: the time
    // of the calls alone, in ns.
    bool answer_all(const std::vector<Case>& posed, std::vector<ExternalAnswer>& out,
                    double* ns) const;
    // The answer alone (nullopt where the case cannot be represented).
    std::optional<Result> operator()(const Shape& s, const Line& l) const {
        return answer(s, l).result;
    }
};

// While one lives, a crash or abort inside an in-process external solver's call is caught (signal
// handlers for SIGSEGV, SIGBUS, SIGFPE, SIGILL and SIGABRT, the previous ones restored after).
// Every call holds one; a caller making many calls holds one across them, so that the handlers
// are installed once rather than per call (which would weigh on the timings).
class CrashGuard {
  public:
    CrashGuard();
    ~CrashGuard();
    CrashGuard(const CrashGuard&) = delete;
    CrashGuard& operator=(const CrashGuard&) = delete;
};

// The case as this solver sees it (see Surface and Parametrisation); nullopt when it cannot be
// posed (a segment solver given an unbounded range, a closed solid asked of an infinite shape),
// with *why saying so.
std::optional<Case> posed_for(const ExternalSolver& s, const Case& c, std::string* why = nullptr);

// The exact reference for what a solver answers on a posed case, under its declared answers and
// conventions: every hit, the nearest, the first entry into the solid or the first exit from it,
// a hit at the start of a range that starts inside, a contact interval as its first point.
struct Reference {
    Result result;
    std::string unrepresented; // the case cannot be posed for such a solver: why (not graded)
    // The case is outside the solver's contract (a first exit from a start outside, a start
    // inside where it is undefined): not asked, counted, never charged. Why, if so.
    std::string not_asked;
    // A hit the conventions make (a start inside, a contact's first point) has no kind, and no
    // part or (for a contact) no point to grade: what of the solver's answer is graded.
    bool kinds = true, parts = true, points = true;
};
Reference reference_for(const ExternalSolver& s, const Case& posed);
// How the reference names itself in a report's worst cases and a replay: "exact" where it is the
// oracle's answer to the posed case, else what it is ("exact, nearest hit, start inside: a hit
// at 0", ...).
std::string reference_label(const ExternalSolver& s);
// The reference without conventions (kept for callers of the first API).
Result reference_for(Answers a, const Case& posed);

// Whether the conventions leave the oracle's answer as the reference (all hits, every case).
bool answers_as_oracle(const ExternalSolver& s);

// The answer as the solver's conventions read it: a negative t within negative_zero of 0 is 0.
void read_conventions(const ExternalSolver& s, const Case& posed, Result& got);

// The conventions of ABI 3 in words, for the report and the solver list (the start inside and
// the contact have their own): "surfaces 5e-10 off at most; a tangent touch is no hit".
std::string conventions_text(const ExternalSolver& s);

// Refuses a solver whose declarations are out of range (a negative, NaN or infinite tolerance, a
// convention its answers cannot have): the message names the solver and the field. Empty: none.
std::string declaration_problem(const ExternalSolver& s);

// What a solver from outside cannot be handed: a value that is not a float, for a binary32
// solver (not_binary32, naming it); none otherwise.
Error input_problem(const ExternalSolver& s, const Case& posed);

// A graded case replayed: the two lines a report's worst case shows for it, the solver's answer
// as graded and the reference its grade used, for linequad's solver `own`, its batch path (name
// batch_name), or a solver from outside `theirs`, on the case as that solver saw it (not posed
// again).
std::vector<std::string> replay_lines(const std::string& name, const Solver* own,
                                      const ExternalSolver* theirs, const Case& c);

// Runs a campaign (or grades a cases file) with these solvers beside linequad's own: each one
// named in o.solvers (an empty o.solvers: linequad's own and all of these).
Report run(const Options& o, const std::vector<ExternalSolver>& external);

// Where a plugin's worker process comes from, and how long a call may take.
struct PluginOptions {
    // The linequad program, which runs the worker (`linequad plugin-worker LIB`). Empty: the
    // LINEQUAD_PROGRAM environment variable, else this program when it is linequad, else the
    // installed linequad.
    std::string program;
    double timeout_seconds = 5; // per call (a batch entry's call included)
};

// Loads the solvers of a plugin (a shared library with the C ABI of linequad/audit_plugin.h) in a
// worker process; throws std::runtime_error naming the file and what is wrong (it does not load,
// exports no entry, speaks no ABI linequad knows, declares a solver badly, ...).
std::vector<ExternalSolver> load_plugin(const std::string& path, const PluginOptions& o = {});

// The worker's side: loads the plugin and answers requests on descriptors 3 (requests), 4
// (replies) and 5 (shared memory) until its parent goes away. What `linequad plugin-worker LIB`
// runs; returns the process's exit status.
int plugin_worker_main(const std::string& path);

} // namespace linequad::audit
