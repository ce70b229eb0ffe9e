// The history database, through SQLite's C API (Debian libsqlite3-dev). Each report is one
// transaction, so a crash or a second writer never leaves half a run; a busy database is waited
// for (shards of one campaign may finish together).
#include "report/history.hpp"

#include "io/escape.hpp"
#include "io/jsonl.hpp"
#include "report/svg_plot.hpp"

#include <sqlite3.h>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace linequad::audit {

namespace {

constexpr const char* format = "linequad-history-1";

constexpr const char* schema = R"(
CREATE TABLE IF NOT EXISTS meta(key TEXT PRIMARY KEY, value TEXT NOT NULL);
CREATE TABLE IF NOT EXISTS runs(
  id INTEGER PRIMARY KEY,
  commit_id TEXT NOT NULL,
  campaign TEXT NOT NULL,
  date TEXT NOT NULL,
  version TEXT NOT NULL,
  machine TEXT NOT NULL,
  command TEXT NOT NULL,
  complete INTEGER NOT NULL,
  UNIQUE(commit_id, campaign));
CREATE TABLE IF NOT EXISTS results(
  run INTEGER NOT NULL REFERENCES runs(id) ON DELETE CASCADE,
  solver TEXT NOT NULL,
  family TEXT NOT NULL,
  shape TEXT NOT NULL,
  cases INTEGER NOT NULL,
  mismatched INTEGER NOT NULL,
  unrepresented INTEGER NOT NULL,
  bound_violations INTEGER NOT NULL,
  t_max_ulps REAL,
  t_p99_ulps REAL NOT NULL,
  t_p50_ulps REAL NOT NULL,
  ns_median REAL,
  PRIMARY KEY(run, solver, family, shape));
)";

std::string joined(const std::vector<std::string>& v) {
    std::string out;
    for (const std::string& s : v)
        out += (out.empty() ? "" : ",") + s;
    return out;
}

std::string real(double x) {
    if (std::isinf(x)) return "inf";
    char b[32];
    std::snprintf(b, sizeof b, "%.4g", x);
    return b;
}

} // namespace

struct History::Db {
    sqlite3* handle = nullptr;
    std::string path;

    void exec(const char* sql) {
        char* message = nullptr;
        if (sqlite3_exec(handle, sql, nullptr, nullptr, &message) != SQLITE_OK) {
            std::string why = message ? message : sqlite3_errmsg(handle);
            sqlite3_free(message);
            throw std::runtime_error(path + ": " + why);
        }
    }
};

namespace {

// A prepared statement, finalised on every path; its errors name the database.
class Statement {
  public:
    Statement(sqlite3* db, const std::string& path, const char* sql) : db_(db), path_(path) {
        if (sqlite3_prepare_v2(db, sql, -1, &s_, nullptr) != SQLITE_OK)
            fail("cannot prepare a statement (is this linequad's history?)");
    }
    ~Statement() { sqlite3_finalize(s_); }
    Statement(const Statement&) = delete;
    Statement& operator=(const Statement&) = delete;

    Statement& text(int i, const std::string& v) {
        check(sqlite3_bind_text(s_, i, v.c_str(), int(v.size()), SQLITE_TRANSIENT));
        return *this;
    }
    Statement& integer(int i, std::uint64_t v) {
        if (v > std::uint64_t(std::numeric_limits<sqlite3_int64>::max()))
            throw std::runtime_error(path_ + ": a count beyond SQLite's integers");
        check(sqlite3_bind_int64(s_, i, sqlite3_int64(v)));
        return *this;
    }
    // NaN and infinities are stored as NULL: SQLite's REAL has no such values.
    Statement& number(int i, double v) {
        check(std::isfinite(v) ? sqlite3_bind_double(s_, i, v) : sqlite3_bind_null(s_, i));
        return *this;
    }
    bool step() {
        int rc = sqlite3_step(s_);
        if (rc == SQLITE_ROW) return true;
        if (rc == SQLITE_DONE) return false;
        fail("cannot step");
    }
    void run() {
        while (step()) {
        }
        sqlite3_reset(s_);
    }
    std::string column_text(int i) const {
        const unsigned char* t = sqlite3_column_text(s_, i);
        return t ? reinterpret_cast<const char*>(t) : "";
    }
    std::uint64_t column_count(int i) const {
        return std::uint64_t(std::max<sqlite3_int64>(0, sqlite3_column_int64(s_, i)));
    }
    bool null(int i) const { return sqlite3_column_type(s_, i) == SQLITE_NULL; }
    double column_real(int i) const { return sqlite3_column_double(s_, i); }

  private:
    [[noreturn]] void fail(const std::string& what) const {
        throw std::runtime_error(path_ + ": " + what + ": " + sqlite3_errmsg(db_));
    }
    void check(int rc) {
        if (rc != SQLITE_OK) fail("cannot bind a value");
    }
    sqlite3* db_;
    const std::string& path_;
    sqlite3_stmt* s_ = nullptr;
};

} // namespace

std::string campaign_of(const Report& r) {
    std::ostringstream c;
    if (r.from_cases_file()) {
        c << "cases " << r.cases_file << " (" << r.cases_count << ")";
        if (r.grades_results()) c << ", results " << r.results_file;
        return c.str();
    }
    c << "seed " << r.seed << ", " << r.cases_per_group << " cases per group, families "
      << joined(r.families) << ", shapes " << joined(r.shapes) << ", ranges " << joined(r.ranges)
      << ", frames " << r.frames;
    if (r.shards > 1) {
        std::vector<std::string> included;
        for (int k : r.shards_included)
            included.push_back(std::to_string(k));
        c << ", shards " << joined(included) << " of " << r.shards;
    }
    return c.str();
}

History::History(const std::string& path, Access access)
    : db_(std::make_unique<Db>()), path_(path) {
    db_->path = path;
    bool writes = access == Access::read_write;
    int flags = writes ? SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE : SQLITE_OPEN_READONLY;
    if (!writes && ::access(path.c_str(), F_OK) != 0)
        throw std::runtime_error(path + ": no such history (audit --history and history --add "
                                        "create one)");
    if (sqlite3_open_v2(path.c_str(), &db_->handle, flags, nullptr) != SQLITE_OK) {
        std::string why = db_->handle ? sqlite3_errmsg(db_->handle) : "cannot open";
        sqlite3_close(db_->handle);
        throw std::runtime_error(path + ": " + why);
    }
    // SQLite opens a file it cannot write read-only, without a word: refused here, before an
    // audit's work, not when its report is added.
    if (writes && sqlite3_db_readonly(db_->handle, "main") == 1) {
        sqlite3_close(db_->handle);
        throw std::runtime_error(path + ": cannot write it (read-only)");
    }
    try {
        sqlite3_busy_timeout(db_->handle, 30000);
        db_->exec("PRAGMA foreign_keys = ON");
        if (writes) {
            db_->exec("BEGIN IMMEDIATE");
            db_->exec(schema);
        }
        bool has_meta = false;
        {
            Statement meta(db_->handle, path_,
                           "SELECT 1 FROM sqlite_master WHERE type = 'table' AND name = 'meta'");
            has_meta = meta.step();
        }
        if (!has_meta) throw std::runtime_error(path + ": not a linequad history (no meta table)");
        Statement get(db_->handle, path_, "SELECT value FROM meta WHERE key = 'format'");
        if (get.step()) {
            std::string found = get.column_text(0);
            if (found != format)
                throw std::runtime_error(path + ": a history in format '" + found + "', not '" +
                                         format + "'");
        } else if (writes) {
            Statement put(db_->handle, path_, "INSERT INTO meta(key, value) VALUES('format', ?)");
            put.text(1, format).run();
        } else {
            throw std::runtime_error(path + ": not a linequad history (no format recorded)");
        }
        if (writes) db_->exec("COMMIT");
    } catch (...) {
        sqlite3_close(db_->handle); // rolls the transaction back
        throw;
    }
}

History::~History() {
    sqlite3_close(db_->handle);
}

std::size_t History::add(const Report& r, const std::string& commit) {
    std::string id = commit.empty() ? r.commit : commit;
    if (id.empty()) throw std::runtime_error(path_ + ": the report names no commit (--commit)");
    std::string campaign = campaign_of(r);

    // Each solver over all families and shapes, each family, each shape, each family and shape.
    std::map<std::tuple<std::string, std::string, std::string>, Row> rows;
    for (const auto& [key, row] : r.rows) {
        rows[{key.solver, "*", "*"}].merge(row);
        rows[{key.solver, key.family, "*"}].merge(row);
        rows[{key.solver, "*", key.shape}].merge(row);
        rows[{key.solver, key.family, key.shape}].merge(row);
    }

    db_->exec("BEGIN IMMEDIATE");
    try {
        Statement drop(db_->handle, path_, "DELETE FROM runs WHERE commit_id = ? AND campaign = ?");
        drop.text(1, id).text(2, campaign).run();
        Statement run(db_->handle, path_,
                      "INSERT INTO runs(commit_id, campaign, date, version, machine, "
                      "command, complete) VALUES(?, ?, ?, ?, ?, ?, ?)");
        run.text(1, id)
            .text(2, campaign)
            .text(3, r.date)
            .text(4, r.version)
            .text(5, r.machine)
            .text(6, r.command)
            .integer(7, r.complete() ? 1 : 0)
            .run();
        sqlite3_int64 run_id = sqlite3_last_insert_rowid(db_->handle);
        Statement put(db_->handle, path_,
                      "INSERT INTO results(run, solver, family, shape, cases, mismatched, "
                      "unrepresented, bound_violations, t_max_ulps, t_p99_ulps, "
                      "t_p50_ulps, ns_median) VALUES(?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?)");
        for (const auto& [key, row] : rows) {
            const auto& [solver, family, shape] = key;
            double t_max = row.t_max == UINT64_MAX ? std::numeric_limits<double>::infinity()
                                                   : double(row.t_max);
            put.integer(1, std::uint64_t(run_id))
                .text(2, solver)
                .text(3, family)
                .text(4, shape)
                .integer(5, row.cases)
                .integer(6, row.cases_mismatched)
                .integer(7, row.unrepresented)
                .integer(8, row.bound_violations)
                .number(9, t_max)
                .number(10, row.t_quantile(0.99))
                .number(11, row.t_quantile(0.5))
                .number(12, row.timed() ? row.ns.median() : std::nan(""))
                .run();
        }
        db_->exec("COMMIT");
    } catch (...) {
        sqlite3_exec(db_->handle, "ROLLBACK", nullptr, nullptr, nullptr);
        throw;
    }
    return rows.size();
}

std::vector<HistoryPoint> History::trend(const std::string& solver, const std::string& family,
                                         const std::string& shape) const {
    Statement q(db_->handle, path_,
                "SELECT runs.commit_id, runs.date, runs.campaign, runs.complete, cases, "
                "mismatched, unrepresented, bound_violations, t_max_ulps, t_p99_ulps, "
                "t_p50_ulps, ns_median FROM results JOIN runs ON results.run = runs.id "
                "WHERE solver = ? AND family = ? AND shape = ? ORDER BY runs.id");
    q.text(1, solver).text(2, family).text(3, shape);
    std::vector<HistoryPoint> out;
    while (q.step()) {
        HistoryPoint p;
        p.commit = q.column_text(0);
        p.date = q.column_text(1);
        p.campaign = q.column_text(2);
        p.complete = q.column_count(3) != 0;
        p.cases = q.column_count(4);
        p.mismatched = q.column_count(5);
        p.unrepresented = q.column_count(6);
        p.bound_violations = q.column_count(7);
        p.t_max = q.null(8) ? std::numeric_limits<double>::infinity() : q.column_real(8);
        p.t_p99 = q.column_real(9);
        p.t_p50 = q.column_real(10);
        p.ns_median = q.null(11) ? 0 : q.column_real(11);
        out.push_back(p);
    }
    return out;
}

std::vector<std::string> History::solvers() const {
    Statement q(db_->handle, path_, "SELECT DISTINCT solver FROM results ORDER BY solver");
    std::vector<std::string> out;
    while (q.step())
        out.push_back(q.column_text(0));
    return out;
}

namespace {

// What moved from the run before, when both ran the same campaign.
std::string against(const HistoryPoint& before, const HistoryPoint& now) {
    if (before.campaign != now.campaign) return "another campaign";
    std::vector<std::string> worse, better;
    auto compare = [&](const char* what, double b, double n, const std::string& text) {
        if (n > b) worse.push_back(std::string(what) + " " + text);
        if (n < b) better.push_back(std::string(what) + " " + text);
    };
    auto rate = [](std::uint64_t a, std::uint64_t b) { return b ? double(a) / double(b) : 0.0; };
    compare("mismatched", rate(before.mismatched, before.cases), rate(now.mismatched, now.cases),
            std::to_string(before.mismatched) + " → " + std::to_string(now.mismatched));
    compare("t max", before.t_max, now.t_max, real(before.t_max) + " → " + real(now.t_max));
    compare("t p99", before.t_p99, now.t_p99, real(before.t_p99) + " → " + real(now.t_p99));
    std::string out;
    if (!worse.empty()) out += "**worse**: " + joined(worse);
    if (!better.empty()) out += std::string(out.empty() ? "" : "; ") + "better: " + joined(better);
    return out.empty() ? "same" : out;
}

} // namespace

std::string trend_markdown(const std::vector<HistoryPoint>& points, const std::string& solver,
                           const std::string& family, const std::string& shape) {
    std::ostringstream md;
    using escape::markdown_text;
    md << "## " << markdown_text(solver) << ": "
       << (family == "*" ? "every family" : markdown_text(family)) << ", "
       << (shape == "*" ? "every shape" : markdown_text(shape)) << "\n\n";
    if (points.empty()) {
        md << "No run recorded.\n";
        return md.str();
    }
    md << "| # | commit | date | cases | mismatched | t max | t p99 | t p50 | ns median | against "
          "the run before |\n|---:|---|---|---:|---:|---:|---:|---:|---:|---|\n";
    for (std::size_t i = 0; i < points.size(); ++i) {
        const HistoryPoint& p = points[i];
        // A commit's text is the user's (--commit): one table row whatever it holds.
        md << "| " << i + 1 << " | " << markdown_text(p.commit)
           << (p.complete ? "" : " (incomplete)") << " | " << markdown_text(p.date) << " | "
           << p.cases << " | " << p.mismatched << " | " << real(p.t_max) << " | " << real(p.t_p99)
           << " | " << real(p.t_p50) << " | " << (p.ns_median > 0 ? real(p.ns_median) : "-")
           << " | " << (i ? against(points[i - 1], p) : "") << " |\n";
    }
    return md.str();
}

void plot_trend(const std::vector<HistoryPoint>& points, const std::string& title,
                const std::string& svg_path) {
    plot::Chart c;
    c.title = title;
    c.x_label = "run (commit)";
    c.y_label = "1 + t error (ulps)";
    c.y2_label = "fraction misclassified";
    c.log_y = true;
    plot::Series max, p99, wrong;
    max.name = "t max", p99.name = "t p99", wrong.name = "misclassified";
    wrong.right = wrong.dashed = true;
    double most = 0;
    for (std::size_t i = 0; i < points.size(); ++i) {
        const HistoryPoint& p = points[i];
        double x = double(i + 1), rate = p.cases ? double(p.mismatched) / double(p.cases) : 0.0;
        max.points.emplace_back(x, 1 + p.t_max); // an infinite maximum is left out
        p99.points.emplace_back(x, 1 + p.t_p99);
        wrong.points.emplace_back(x, rate);
        most = std::max(most, rate);
        c.x_names.emplace_back(x, p.commit);
    }
    c.y2_max = most > 0 ? std::min(1.0, most * 1.1) : 1;
    c.series = {max, p99, wrong};
    jsonl::write_file(svg_path, plot::svg({c}));
}

} // namespace linequad::audit
