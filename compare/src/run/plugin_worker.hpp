// A plugin's solvers in a worker process of their own. The process that holds the exact
// reference, the grading and the report never runs a plugin's code (not even its load-time
// constructors), so nothing a plugin does can change linequad's own answers: its rounding mode
// and flush-to-zero are the worker's, and its crash, exit, hang or output ends or fills only the
// worker. A call that crashes, exits, throws or exceeds the timeout is answered as a refusal of
// the solver's own ("crashed (SIGSEGV)", "exited (0)", "threw: ...", "timed out"), the worker is
// started again, and the cases after it go on.
//
// The parent and the worker share one block of memory (the posed cases in, the answers out, the
// index of the case being answered) and two pipes (a request, its reply). Everything the worker
// writes is checked by the parent as data from outside: a plugin runs in the worker and may have
// written any of it.
#pragma once

#include "linequad/audit_plugin.h"
#include "linequad/audit_solver.hpp"

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace linequad::audit {

// What a plugin declares of one of its solvers, as its worker reported it and the parent checked.
struct DeclaredSolver {
    std::string name, mapping;
    Precision precision = Precision::binary64;
    Answers answers = Answers::all;
    Parametrisation parametrisation = Parametrisation::line;
    Surface surface = Surface::as_posed;
    StartInside inside = StartInside::as_answers;
    bool contact_as_point = false;
    StartOnSurface on_surface = StartOnSurface::as_inside;
    TangentRule tangent = TangentRule::hit;
    Tolerance tolerance;
    double negative_zero = 0;
    bool points = false, kinds = false, parts = false;
    unsigned shapes = 0; // bit k: the shape kind k of the ABI (the index in linequad::Shape)
    bool batch = false;  // it has the ABI's batch entry
    bool sense = false;  // it has the ABI's sense entry (ABI 4)
};

// The ExternalSolver a declaration makes (without its worker).
ExternalSolver declared_as_external(const DeclaredSolver& d);

class PluginWorker {
  public:
    // Starts the worker and reads what the plugin declares; throws std::runtime_error naming the
    // plugin and what is wrong (it cannot be loaded, has no entry, a solver is declared badly, the
    // worker does not start or answer in time).
    PluginWorker(const std::string& plugin, const PluginOptions& o);
    ~PluginWorker();
    PluginWorker(const PluginWorker&) = delete;
    PluginWorker& operator=(const PluginWorker&) = delete;

    const std::string& plugin() const;
    const std::vector<DeclaredSolver>& solvers() const;
    // How loading the plugin changed the floating-point environment ("flush-to-zero set, ..."),
    // or "": the environment every call starts from is the one loading left.
    const std::string& load_environment() const;

    // Answers posed cases with solver s, in order; false when a stop request ended it (the
    // answers are then incomplete). *ns: the calls' own time in the worker, in ns. One request at
    // a time (callers from several threads take turns).
    bool answer(int s, const std::vector<Case>& posed, std::vector<ExternalAnswer>& out,
                double* ns);
    // Solver s's sense entry on each case's shape at its line's point L0 and direction v: the
    // side in each answer's `side` (a call that failed: its result a failure, as answer's are).
    // False when a stop request ended it.
    bool sides(int s, const std::vector<Case>& at, std::vector<ExternalAnswer>& out);

    // What the plugin wrote on standard output and error while solver s ran: its first lines,
    // and how many bytes in all.
    std::string output(int s) const;
    std::uint64_t output_bytes(int s) const;
    // How many times solver s's calls crashed, exited or timed out, ending the worker (which was
    // started again for the next call).
    int restarts(int s) const;
    // How many of solver s's packets (its batch entry's calls) failed (declined, crashed, exited
    // or timed out) and were asked again one case at a time: no case of them is charged for it.
    int batch_fallbacks(int s) const;

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

// A case's shape as the plugin ABI hands it over, and a plugin's answer as the audit grades it
// (one that breaks the ABI's rules is the solver's own error, named for what is wrong with it).
lq_shape to_plugin_shape(const Shape& s);
ExternalAnswer from_plugin_answer(const lq_answer& a);
void read_plugin_answer(const lq_answer& a, ExternalAnswer& out); // the same, in place

// The name a solver's name must have (letters, digits and _ . + -, at most 64, not starting with
// a punctuation mark): it names rows, files and replay commands. Empty when it does; else why not.
std::string solver_name_problem(const std::string& name);

} // namespace linequad::audit
