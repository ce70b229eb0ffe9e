// Someone else's solver in the audit: a callable per shape, with what it answers and how it takes
// a line declared, graded and timed in process beside linequad's own solvers, into one report.
//
//     linequad::audit::ExternalSolver mine;
//     mine.name = "mine";
//     mine.answers = linequad::audit::Answers::nearest;
//     mine.cylinder = [](const linequad::Cylinder& c, const linequad::Line& l) { ... };
//     linequad::audit::Options o;
//     o.solvers = {"correct", "mine"};
//     linequad::audit::run(o, {mine});
//
// The case a library is graded on is the case it saw: the audit poses each case the way the
// solver declares (its surfaces closed or infinite, its line as a unit direction or a from-to
// segment, exactly representable), hands the posed case over, and solves the exact reference for
// that posed case. The report shows the posed case in its worst cases.
#pragma once

#include "linequad/audit.hpp"

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace linequad::audit {

// What the solver answers about a line and a shape.
enum class Answers : std::uint8_t {
    all,         // every hit in the range, in order of t (linequad's own solvers)
    nearest,     // the hit with the smallest t in the range, or none (a ray caster's closest hit)
    first_entry, // the first hit where the line is outside the closed solid just before it (a
                 // physics ray test: a solid the line starts in is ignored until it is left)
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

template <class S>
using ShapeCallable = std::function<std::optional<Result>(const S&, const Line&)>;

// A solver from outside linequad. Each callable gets the posed case and returns the solver's
// answer as a linequad::Result (hits in order of t), or nullopt where the library cannot represent
// the case (counted as unrepresented, never graded); an empty callable: the library has no such
// shape. Refusals are Result::failure with the ErrorCode that fits (a library's own error that
// fits none is graded as a refusal the oracle does not make: ErrorCode::out_of_range).
struct ExternalSolver {
    std::string name;
    Precision precision = Precision::binary64; // binary32: posed float cases, graded in floats
    Answers answers = Answers::all;
    Parametrisation parametrisation = Parametrisation::line;
    Surface surface = Surface::as_posed;
    // What its answers carry: hit points, tangent-or-cross kinds, the part (lateral or a disc)
    // of each hit. What it does not carry is not graded.
    bool points = true, kinds = true, parts = true;
    std::string mapping; // for the report: how a case is handed over, what cannot be represented
    std::string plugin;  // the shared library it came from, if any (for replay commands)
    ShapeCallable<Cylinder> cylinder;
    ShapeCallable<EllipticCylinder> elliptic_cylinder;
    ShapeCallable<EllipticCone> elliptic_cone;
    ShapeCallable<Frustum> frustum;

    // Whether it has a callable for this shape.
    bool takes(const Shape& s) const;
    // Calls the shape's callable; nullopt when there is none or the case cannot be represented.
    // A crash or abort inside the callable (a signal) is caught: the answer is then a failure
    // named "crashed", counted apart.
    std::optional<Result> operator()(const Shape& s, const Line& l) const;
};

// While one lives, a crash or abort inside an external solver's call is caught (signal
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
// posed (a segment solver given an unbounded range, a closed solid asked of an infinite shape).
std::optional<Case> posed_for(const ExternalSolver& s, const Case& c);

// The exact reference for what the solver answers on a posed case: every hit, the nearest, or
// the first entry into the solid.
Result reference_for(Answers a, const Case& posed);

// Runs a campaign (or grades a cases file) with these solvers beside linequad's own: each one
// named in o.solvers (an empty o.solvers: linequad's own and all of these).
Report run(const Options& o, const std::vector<ExternalSolver>& external);

// Loads the solvers of a plugin (a shared library with the C ABI of linequad/audit_plugin.h);
// throws std::runtime_error naming the file and what is wrong.
std::vector<ExternalSolver> load_plugin(const std::string& path);

} // namespace linequad::audit
