// The audit's history across commits: each report's summary appended to a SQLite database (one
// run per commit and campaign, rows per solver, family and shape), and a solver's trend read
// back for `linequad history`.
#pragma once

#include "linequad/audit.hpp"

#include <memory>
#include <string>
#include <vector>

namespace linequad::audit {

// How a run is known in the history: the commit it measured and the campaign it ran (seed, case
// counts, families, shapes, ranges, frames, shards; or the cases and results files).
std::string campaign_of(const Report& r);

// One solver's figures in one run, for one family and shape ("*": all of them).
struct HistoryPoint {
    std::string commit, date, campaign;
    std::uint64_t cases = 0, mismatched = 0, unrepresented = 0, bound_violations = 0;
    double t_max = 0, t_p99 = 0, t_p50 = 0; // ulps; t_max is infinite for a NaN or infinite t
    double ns_median = 0;                   // 0: not timed
    bool complete = true;                   // every case of the campaign graded
};

class History {
  public:
    // To add reports (the database created if need be, and refused at once if it cannot be
    // written), or only to read trends (a database someone else keeps, on a read-only file or
    // file system: never created, never written).
    enum class Access { read_write, read_only };
    // Opens the database at path. Throws std::runtime_error naming the path and SQLite's reason
    // (not a database, not writable when it must be, a schema not linequad's).
    explicit History(const std::string& path, Access access = Access::read_write);
    ~History();
    History(const History&) = delete;
    History& operator=(const History&) = delete;

    // Appends r's summary under commit (r.commit when empty), in one transaction: a run of the
    // same commit and campaign recorded earlier is replaced. Returns the rows written.
    std::size_t add(const Report& r, const std::string& commit = "");

    // The solver's points in the order their runs were added; family and shape "*" for all.
    std::vector<HistoryPoint> trend(const std::string& solver, const std::string& family = "*",
                                    const std::string& shape = "*") const;
    std::vector<std::string> solvers() const;

  private:
    struct Db; // the SQLite handle (history.cpp)
    std::unique_ptr<Db> db_;
    std::string path_;
};

// A trend as a markdown table, oldest first, each change from the run before marked.
std::string trend_markdown(const std::vector<HistoryPoint>& points, const std::string& solver,
                           const std::string& family, const std::string& shape);

// The trend as an SVG figure (t max and p99 in ulps, misclassified fraction on the second axis,
// one point per run labelled by commit). Throws if it cannot write the file.
void plot_trend(const std::vector<HistoryPoint>& points, const std::string& title,
                const std::string& svg_path);

} // namespace linequad::audit
