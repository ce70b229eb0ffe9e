// report.json: written exactly, read strictly. Every value read back is checked for its type and
// its range, and the statistics for their consistency (a histogram holds as many errors as the
// row graded), so a damaged or hand-edited report is refused with the path of the bad field
// instead of being merged into a wrong total.
#include "linequad/audit.hpp"

#include "io/jsonl.hpp"
#include "io/shape_types.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <new>
#include <stdexcept>

namespace linequad::audit {

namespace {

using jsonl::Json;
using jsonl::OrderedJson;

constexpr const char* format_name = "linequad-audit-3";
constexpr int max_shards = 1000000;

// ---- writing

template <class Array>
OrderedJson pairs(const Array& a) {
    // Histograms are mostly zeros: written as [index, count] pairs.
    OrderedJson out = OrderedJson::array();
    for (std::size_t i = 0; i < a.size(); ++i)
        if (a[i]) out.push_back({i, a[i]});
    return out;
}

double mean(double sum, std::uint64_t n) {
    return n ? sum / double(n) : 0;
}

OrderedJson row_json(const RowKey& key, const Row& r) {
    OrderedJson mismatches = OrderedJson::object();
    for (int m = 0; m < mismatch_kinds; ++m)
        mismatches[mismatch_name(m)] = r.mismatches[m];
    OrderedJson worst = OrderedJson::array();
    for (const Worst& w : r.worst)
        worst.push_back({{"mismatch", w.mismatch},
                         {"t_ulps", w.ulps},
                         {"case", w.case_line()},
                         {"solver", w.solver_line()},
                         {"oracle", w.oracle_line()}});
    // mean, p50, p99, ... are for people reading the file; only the exact fields are read back.
    return {
        {"family", key.family},
        {"shape", key.shape},
        {"solver", key.solver},
        {"cases", r.cases},
        {"binary32_cases", r.binary32_cases},
        {"graded_roots", r.graded_roots},
        {"graded_points", r.graded_coords},
        {"cases_mismatched", r.cases_mismatched},
        {"mismatches", mismatches},
        {"t_ulps",
         {{"max", r.t_max},
          {"mean", mean(r.t_sum, r.graded_roots)},
          {"p50", r.t_quantile(0.5)},
          {"p99", r.t_quantile(0.99)},
          {"p999", r.t_quantile(0.999)},
          {"mean_bits", mean(r.t_bits_sum, r.graded_roots)},
          {"sum", r.t_sum},
          {"bits_sum", r.t_bits_sum},
          {"histogram", pairs(r.t_error.count)}}},
        {"point_ulps",
         {{"max", r.p_max}, {"p99", r.p_quantile(0.99)}, {"histogram", pairs(r.p_error.count)}}},
        {"scene_ulps",
         {{"max", r.s_max}, {"p99", r.s_quantile(0.99)}, {"histogram", pairs(r.s_error.count)}}},
        {"within_tolerance", r.within_tolerance},
        {"t_sign_wrong", r.t_sign_wrong},
        {"not_asked", r.not_asked},
        {"unrepresented", r.unrepresented},
        {"unrepresented_why", r.unrepresented_why},
        {"foreign_refusals", r.foreign},
        {"environment_changes", r.environment},
        {"ns_per_solve", {{"median", r.ns.median()}, {"histogram", pairs(r.ns.count)}}},
        {"certified",
         {{"uncertain", r.uncertain},
          {"certain_wrong", r.certain_wrong},
          {"bounded_roots", r.bounded_roots},
          {"bound_violations", r.bound_violations},
          {"tightness_p50", r.tightness.quantile(0.5)},
          {"bound_below_half_ulp", r.bound_below_half_ulp},
          {"tightness", pairs(r.tightness.count)}}},
        {"rungs",
         {{"newton", r.rungs[std::size_t(Rung::newton)]},
          {"double_double", r.rungs[std::size_t(Rung::double_double)]},
          {"exact", r.rungs[std::size_t(Rung::exact)]}}},
        {"worst", worst}};
}

OrderedJson curve_json(const CurveKey& key, const std::map<int, CurvePoint>& points) {
    OrderedJson list = OrderedJson::array();
    for (const auto& [k, p] : points)
        list.push_back({{"k", k},
                        {"cases", p.cases},
                        {"mismatched", p.mismatched},
                        {"t_max", p.t_max},
                        {"histogram", pairs(p.t_error.count)}});
    return {{"family", key.family}, {"solver", key.solver}, {"points", list}};
}

// ---- reading

struct Invalid : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// A value with the path that names it in errors ("rows[3].t_ulps.max"), spelled only for an
// error: a node knows its parent (alive in an enclosing scope) and its key or index. A report
// holds hundreds of thousands of values, and each save reads one back.
struct Node {
    const Json& v;
    const Node* parent = nullptr;
    const char* key = nullptr; // else the index in the parent array
    std::size_t index = 0;

    std::string path() const {
        if (!parent) return "";
        std::string p = parent->path();
        if (key) return p.empty() ? std::string(key) : p + "." + key;
        return p + "[" + std::to_string(index) + "]";
    }
    [[noreturn]] void fail(const std::string& what) const { throw Invalid(path() + ": " + what); }

    const Json* find(const char* key) const {
        auto it = v.find(key);
        return it == v.end() ? nullptr : &*it;
    }
    Node at(const char* k) const {
        if (!v.is_object()) fail("expected an object");
        const Json* x = find(k);
        if (!x) Node{v, this, k}.fail("missing");
        return {*x, this, k};
    }
    Node item(std::size_t i) const { return {v[i], this, nullptr, i}; }
    std::size_t size(std::size_t at_most = SIZE_MAX) const {
        if (!v.is_array()) fail("expected an array");
        if (v.size() > at_most) fail("more than " + std::to_string(at_most) + " entries");
        return v.size();
    }
    std::uint64_t count(std::uint64_t at_most = UINT64_MAX) const {
        if (v.is_number_unsigned()) {
            std::uint64_t x = v.get<std::uint64_t>();
            if (x > at_most) fail(std::to_string(x) + " is above " + std::to_string(at_most));
            return x;
        }
        fail("expected a whole number >= 0, not " + jsonl::dump(v));
    }
    long integer(long lo, long hi) const {
        if (!v.is_number_integer()) fail("expected a whole number, not " + jsonl::dump(v));
        long x = v.is_number_unsigned()
                     ? long(std::min<std::uint64_t>(v.get<std::uint64_t>(), std::uint64_t(hi) + 1))
                     : long(v.get<std::int64_t>());
        if (x < lo || x > hi)
            fail(std::to_string(x) + " is outside " + std::to_string(lo) + ".." +
                 std::to_string(hi));
        return x;
    }
    double real() const { // finite and >= 0: sums of errors, seconds
        if (!v.is_number()) fail("expected a number, not " + jsonl::dump(v));
        double x = v.get<double>();
        if (!std::isfinite(x) || x < 0)
            fail("expected a finite number >= 0, not " + jsonl::dump(v));
        return x;
    }
    std::string text() const {
        if (!v.is_string()) fail("expected a string, not " + jsonl::dump(v));
        return v.get<std::string>();
    }
    bool flag() const {
        if (!v.is_boolean()) fail("expected true or false, not " + jsonl::dump(v));
        return v.get<bool>();
    }
    // A list of distinct strings, each accepted by known (which says what it expects).
    template <class Known>
    std::vector<std::string> names(Known known) const {
        std::vector<std::string> out;
        for (std::size_t i = 0, n = size(); i < n; ++i) {
            std::string s = item(i).text();
            if (std::string expected = known(s); !expected.empty())
                item(i).fail("'" + s + "' is not " + expected);
            if (std::find(out.begin(), out.end(), s) != out.end())
                item(i).fail("'" + s + "' is listed twice");
            out.push_back(s);
        }
        return out;
    }
};

template <class Array>
std::uint64_t read_pairs(const Node& n, Array& a) {
    std::uint64_t total = 0;
    long last = -1;
    for (std::size_t i = 0, size = n.size(); i < size; ++i) {
        Node pair = n.item(i);
        if (pair.size() != 2) pair.fail("expected [index, count]");
        long index = pair.item(0).integer(0, long(a.size()) - 1);
        if (index <= last) pair.fail("indices must increase");
        last = index;
        std::uint64_t c = pair.item(1).count();
        if (c == 0) pair.fail("a zero count is not written");
        if (c > UINT64_MAX - total) pair.fail("the counts overflow");
        a[std::size_t(index)] = c;
        total += c;
    }
    return total;
}

// The largest error of a histogram must lie in its top bucket (maxima and histograms are kept
// together, so a report whose two disagree was edited or damaged).
void check_max(const Node& n, std::uint64_t max, const Histogram& h, std::uint64_t graded) {
    int top = -1;
    for (int b = 0; b < Histogram::bins; ++b)
        if (h.count[b]) top = b;
    bool fits = graded == 0 ? max == 0 : Histogram::bucket(max) == top;
    if (!fits) n.fail(std::to_string(max) + " does not lie in the histogram's top bucket");
}

void check_total(const Node& n, std::uint64_t total, std::uint64_t want, const char* what) {
    if (total != want)
        n.fail("holds " + std::to_string(total) + " values, but " + what + " is " +
               std::to_string(want));
}

// A row's errors: t, points, scene, each histogram consistent with its counts.
void read_errors(const Node& n, Row& r) {
    Node t = n.at("t_ulps");
    r.t_max = t.at("max").count();
    r.t_sum = t.at("sum").real();
    r.t_bits_sum = t.at("bits_sum").real();
    check_total(t.at("histogram"), read_pairs(t.at("histogram"), r.t_error.count), r.graded_roots,
                "graded_roots");
    check_max(t.at("max"), r.t_max, r.t_error, r.graded_roots);
    Node p = n.at("point_ulps");
    r.p_max = p.at("max").count();
    check_total(p.at("histogram"), read_pairs(p.at("histogram"), r.p_error.count), r.graded_coords,
                "graded_points");
    check_max(p.at("max"), r.p_max, r.p_error, r.graded_coords);
    // Reports from before scene-relative errors and external solvers have neither.
    // A row merged from such a report and a newer one holds scene errors for only some of its
    // roots, so the scene histogram holds at most graded_roots values, not exactly that many;
    // roots of the wrong sign have a scene error (and no ulps of t) too.
    if (n.find("scene_ulps")) {
        Node sc = n.at("scene_ulps");
        r.s_max = sc.at("max").count();
        std::uint64_t scene = read_pairs(sc.at("histogram"), r.s_error.count);
        if (scene > r.graded_roots + r.t_sign_wrong)
            sc.at("histogram")
                .fail("holds " + std::to_string(scene) +
                      " values, more than graded_roots and t_sign_wrong (" +
                      std::to_string(r.graded_roots + r.t_sign_wrong) + ")");
        check_max(sc.at("max"), r.s_max, r.s_error, scene);
    }
}

// A row's certified bounds and the correct solvers' rungs.
void read_certified_and_rungs(const Node& n, Row& r) {
    Node c = n.at("certified");
    r.uncertain = c.at("uncertain").count(r.cases);
    r.certain_wrong = c.at("certain_wrong").count(r.cases);
    r.bounded_roots = c.at("bounded_roots").count(r.graded_roots + r.t_sign_wrong);
    r.bound_violations = c.at("bound_violations").count(r.bounded_roots);
    r.bound_below_half_ulp = c.at("bound_below_half_ulp").count(r.bounded_roots);
    check_total(c.at("tightness"), read_pairs(c.at("tightness"), r.tightness.count),
                r.bounded_roots, "bounded_roots");
    Node g = n.at("rungs");
    r.rungs[std::size_t(Rung::newton)] = g.at("newton").count(r.cases);
    r.rungs[std::size_t(Rung::double_double)] = g.at("double_double").count(r.cases);
    r.rungs[std::size_t(Rung::exact)] = g.at("exact").count(r.cases);
}

Row read_row(const Node& n) {
    Row r;
    r.cases = n.at("cases").count();
    auto at_most_cases = [&](const char* key) { return n.at(key).count(r.cases); };
    // Reports from before binary32 cases have none.
    if (n.find("binary32_cases")) r.binary32_cases = at_most_cases("binary32_cases");
    r.graded_roots = n.at("graded_roots").count();
    r.graded_coords = n.at("graded_points").count();
    r.cases_mismatched = at_most_cases("cases_mismatched");
    Node m = n.at("mismatches");
    for (int k = 0; k < mismatch_kinds; ++k)
        r.mismatches[k] = m.at(mismatch_name(k)).count(r.cases);
    r.t_sign_wrong = n.at("t_sign_wrong").count();
    read_errors(n, r);
    r.within_tolerance = at_most_cases("within_tolerance");
    if (r.within_tolerance + r.cases_mismatched > r.cases)
        n.at("within_tolerance").fail("with the mismatched cases, more than the cases");
    r.unrepresented = n.at("unrepresented").count();
    // Counts by name: each name once, no zero count, at most `most` in all.
    auto counts = [&](const char* field, std::map<std::string, std::uint64_t>& out,
                      std::uint64_t most) {
        if (!n.find(field)) return;
        Node f = n.at(field);
        if (!f.v.is_object()) f.fail("expected an object of counts by name");
        std::uint64_t total = 0;
        for (auto it = f.v.begin(); it != f.v.end(); ++it) {
            Node x{*it, &f, it.key().c_str()};
            std::uint64_t k = x.count(most);
            if (k == 0) x.fail("a zero count is not written");
            out[it.key()] = k;
            total += k;
        }
        if (total > most) f.fail("counts more than " + std::to_string(most));
    };
    counts("unrepresented_why", r.unrepresented_why, r.unrepresented);
    counts("not_asked", r.not_asked, std::numeric_limits<std::uint64_t>::max());
    if (n.find("foreign_refusals")) {
        Node f = n.at("foreign_refusals");
        if (!f.v.is_object()) f.fail("expected an object of counts by name");
        std::uint64_t total = 0;
        for (auto it = f.v.begin(); it != f.v.end(); ++it) {
            Node x{*it, &f, it.key().c_str()};
            std::uint64_t k = x.count(r.cases);
            if (k == 0) x.fail("a zero count is not written");
            r.foreign[it.key()] = k;
            total += k;
        }
        if (total > r.mismatches[refused] + r.mismatches[crashed])
            f.fail("counts more than the refused and crashed mismatches");
    }
    counts("environment_changes", r.environment, r.cases + r.unrepresented);
    read_pairs(n.at("ns_per_solve").at("histogram"), r.ns.count);
    read_certified_and_rungs(n, r);
    Node w = n.at("worst");
    for (std::size_t i = 0, size = w.size(Row::keep_worst); i < size; ++i) {
        Node x = w.item(i);
        Worst k(x.at("case").text(), x.at("solver").text(), x.at("oracle").text());
        k.mismatch = x.at("mismatch").flag();
        k.ulps = x.at("t_ulps").count();
        r.worst.push_back(k);
    }
    return r;
}

std::string expect_in(const std::vector<std::string>& list, const std::string& s,
                      const char* what) {
    if (std::find(list.begin(), list.end(), s) != list.end()) return "";
    return "'" + s + "' is not one of the report's " + what;
}

// The solvers from outside linequad: how each was handed its cases, what it did besides.
void read_external(const Node& top, Report* r) {
    if (!top.find("external")) return;
    {
        Node ex = top.at("external");
        for (std::size_t i = 0, n = ex.size(); i < n; ++i) {
            Node x = ex.item(i);
            Report::External e;
            std::string name = x.at("solver").text();
            e.answers = x.at("answers").text();
            e.parametrisation = x.at("parametrisation").text();
            e.surface = x.at("surface").text();
            e.mapping = x.at("mapping").text();
            e.plugin = x.at("plugin").text();
            if (x.find("not_replayable")) e.not_replayable = x.at("not_replayable").text();
            if (x.find("inside")) e.inside = x.at("inside").text();
            if (x.find("contact")) e.contact = x.at("contact").text();
            if (x.find("conventions")) e.conventions = x.at("conventions").text();
            auto length = [&](const char* field) {
                double v = x.at(field).real();
                if (!(v >= 0) || !std::isfinite(v)) x.at(field).fail("expected a finite length");
                return v;
            };
            if (x.find("tolerance_absolute")) e.tolerance_absolute = length("tolerance_absolute");
            if (x.find("tolerance_relative")) e.tolerance_relative = length("tolerance_relative");
            if (x.find("batch")) e.batch = x.at("batch").flag();
            if (x.find("load_environment")) e.load_environment = x.at("load_environment").text();
            if (x.find("output")) {
                e.output = x.at("output").text();
                e.output_bytes = x.at("output_bytes").count();
            }
            if (x.find("restarts")) e.restarts = x.at("restarts").count();
            if (x.find("batch_fallbacks")) e.batch_fallbacks = x.at("batch_fallbacks").count();
            if (r->external.count(name)) x.at("solver").fail("'" + name + "' appears twice");
            r->external[name] = e;
        }
    }
}

// What the campaign ran: families, shapes, frames, ranges, solvers, shards, the oracle's steps.
void read_campaign(const Node& top, Report* r) {
    auto any = [](const std::string&) { return std::string(); };
    // A cases file's families are whatever its cases name.
    r->families = top.at("families").names([&](const std::string& f) {
        Family x;
        return r->from_cases_file() || parse_family(f, &x) ? "" : "a family";
    });
    r->shapes = top.at("shapes").names(
        [](const std::string& s) { return shape_index(s) < shape_count ? "" : "a shape"; });
    // Reports from before the frames option were built on any frames.
    if (top.find("frames")) {
        Frames x;
        r->frames = top.at("frames").text();
        if (!parse_frames(r->frames, &x))
            top.at("frames").fail("expected any, circular, axis or aligned");
    }
    r->ranges = top.at("ranges").names([](const std::string& s) {
        return s == "line" || s == "ray" || s == "segment" ? "" : "line, ray or segment";
    });
    r->solvers = top.at("solvers").names(any);
    r->shards = int(top.at("shards").integer(1, max_shards));
    Node included = top.at("shards_included");
    r->shards_included.clear();
    for (std::size_t i = 0, n = included.size(); i < n; ++i) {
        int k = int(included.item(i).integer(0, r->shards - 1));
        if (!r->shards_included.empty() && k <= r->shards_included.back())
            included.item(i).fail("shards must be listed once each, ascending");
        r->shards_included.push_back(k);
    }
    if (r->shards_included.empty()) included.fail("names no shard");
    if (top.find("shard_marks")) {
        Node marks = top.at("shard_marks");
        for (std::size_t i = 0, n = marks.size(); i < n; ++i) {
            Node pair = marks.item(i);
            if (!pair.v.is_array() || pair.v.size() != 2) pair.fail("expected [shard, mark]");
            int k = int(pair.item(0).count(std::uint64_t(r->shards - 1)));
            std::string text = pair.item(1).text();
            char* end = nullptr;
            std::uint64_t mark = std::strtoull(text.c_str(), &end, 16);
            if (text.size() != 16 || end != text.c_str() + 16)
                pair.item(1).fail("expected 16 hex digits");
            if (std::find(r->shards_included.begin(), r->shards_included.end(), k) ==
                r->shards_included.end())
                pair.item(0).fail("a mark of a shard the report does not include");
            r->shard_marks[k] = mark;
        }
    }
    Node steps = top.at("oracle_rounding_steps");
    if (steps.size() != r->oracle_steps.size()) steps.fail("expected 8 counts");
    for (std::size_t i = 0; i < r->oracle_steps.size(); ++i)
        r->oracle_steps[i] = steps.item(i).count();
    if (top.find("oracle_rounded_by_intervals"))
        r->oracle_by_intervals = top.at("oracle_rounded_by_intervals").count();
    if (top.find("oracle_rounded_by_filter"))
        r->oracle_by_filter = top.at("oracle_rounded_by_filter").count();
}

void read_rows(const Node& top, Report* r) {
    Node rows = top.at("rows");
    for (std::size_t i = 0, n = rows.size(); i < n; ++i) {
        Node x = rows.item(i);
        RowKey key{x.at("family").text(), x.at("shape").text(), x.at("solver").text()};
        if (auto e = expect_in(r->families, key.family, "families"); !e.empty())
            x.at("family").fail(e);
        if (auto e = expect_in(r->shapes, key.shape, "shapes"); !e.empty()) x.at("shape").fail(e);
        if (auto e = expect_in(r->solvers, key.solver, "solvers"); !e.empty())
            x.at("solver").fail(e);
        if (r->rows.count(key)) x.fail(key.name() + " appears twice");
        r->rows[key] = read_row(x);
    }
}

void read_curves(const Node& top, Report* r) {
    Node curves = top.at("curves");
    for (std::size_t i = 0, n = curves.size(); i < n; ++i) {
        Node x = curves.item(i);
        CurveKey key{x.at("family").text(), x.at("solver").text()};
        if (auto e = expect_in(r->families, key.family, "families"); !e.empty())
            x.at("family").fail(e);
        if (auto e = expect_in(r->solvers, key.solver, "solvers"); !e.empty())
            x.at("solver").fail(e);
        if (r->curves.count(key)) x.fail(key.family + "/" + key.solver + " appears twice");
        auto& points = r->curves[key];
        Node list = x.at("points");
        for (std::size_t j = 0, m = list.size(); j < m; ++j) {
            Node p = list.item(j);
            int k = int(p.at("k").integer(-1000000, 1000000));
            if (points.count(k)) p.at("k").fail("k = " + std::to_string(k) + " appears twice");
            CurvePoint& q = points[k];
            q.cases = p.at("cases").count();
            q.mismatched = p.at("mismatched").count(q.cases);
            q.t_max = p.at("t_max").count();
            read_pairs(p.at("histogram"), q.t_error.count);
        }
    }
}

void read_report(const Json& root, Report* r) {
    Node top{root};
    if (!root.is_object()) throw Invalid("not a JSON object");
    std::string format = top.at("format").text();
    if (format == "linequad-audit-1" || format == "linequad-audit-2")
        throw Invalid("format: " + format +
                      " is an older report format (before mismatched hit counts were split into "
                      "invented and missed); run the audit again with this linequad");
    if (format != format_name) top.at("format").fail("not a linequad audit report");
    *r = Report{};
    std::string status = top.at("status").text();
    bool known_status = false;
    for (Status s : {Status::running, Status::stopped, Status::complete})
        if (status == status_name(s)) r->status = s, known_status = true;
    if (!known_status) top.at("status").fail("expected running, stopped or complete");
    r->command = top.at("command").text(), r->machine = top.at("machine").text();
    r->compiler = top.at("compiler").text(), r->flags = top.at("flags").text();
    r->version = top.at("version").text(), r->commit = top.at("commit").text();
    r->date = top.at("date").text();
    if (top.find("run")) r->run = top.at("run").text();
    r->seconds = top.at("seconds").real();
    r->seed = top.at("seed").count();
    r->cases_per_group = top.at("cases_per_group").count();
    if (top.find("results_file")) r->results_file = top.at("results_file").text();
    if (top.find("cases_file")) r->cases_file = top.at("cases_file").text();
    if (top.find("cases_count")) r->cases_count = top.at("cases_count").count();
    read_external(top, r);
    read_campaign(top, r);
    read_rows(top, r);
    read_curves(top, r);
}

} // namespace

std::string to_json(const Report& r) {
    OrderedJson head = {{"format", format_name},
                        {"status", status_name(r.status)},
                        {"command", r.command},
                        {"machine", r.machine},
                        {"compiler", r.compiler},
                        {"flags", r.flags},
                        {"version", r.version},
                        {"commit", r.commit},
                        {"date", r.date},
                        {"seconds", r.seconds},
                        {"seed", r.seed},
                        {"cases_per_group", r.cases_per_group},
                        {"families", r.families},
                        {"shapes", r.shapes},
                        {"frames", r.frames},
                        {"ranges", r.ranges},
                        {"solvers", r.solvers},
                        {"shards", r.shards},
                        {"shards_included", r.shards_included}};
    if (!r.shard_marks.empty()) {
        OrderedJson marks = OrderedJson::array();
        for (const auto& [k, mark] : r.shard_marks) {
            char hex[24];
            std::snprintf(hex, sizeof hex, "%016llx", (unsigned long long)mark);
            marks.push_back({k, hex});
        }
        head["shard_marks"] = marks;
    }
    if (!r.run.empty()) head["run"] = r.run;
    if (r.from_cases_file()) {
        head["cases_file"] = r.cases_file;
        head["cases_count"] = r.cases_count;
    }
    if (r.grades_results()) head["results_file"] = r.results_file;
    if (!r.external.empty()) {
        OrderedJson ex = OrderedJson::array();
        for (const auto& [name, e] : r.external) {
            OrderedJson x = {{"solver", name},
                             {"answers", e.answers},
                             {"parametrisation", e.parametrisation},
                             {"surface", e.surface},
                             {"mapping", e.mapping},
                             {"plugin", e.plugin}};
            // What only some solvers have is written only where it is.
            if (!e.not_replayable.empty()) x["not_replayable"] = e.not_replayable;
            if (!e.inside.empty()) x["inside"] = e.inside;
            if (!e.contact.empty()) x["contact"] = e.contact;
            if (!e.conventions.empty()) x["conventions"] = e.conventions;
            if (e.tolerance_absolute > 0) x["tolerance_absolute"] = e.tolerance_absolute;
            if (e.tolerance_relative > 0) x["tolerance_relative"] = e.tolerance_relative;
            if (e.batch) x["batch"] = true;
            if (!e.load_environment.empty()) x["load_environment"] = e.load_environment;
            if (e.output_bytes) x["output"] = e.output, x["output_bytes"] = e.output_bytes;
            if (e.restarts) x["restarts"] = e.restarts;
            if (e.batch_fallbacks) x["batch_fallbacks"] = e.batch_fallbacks;
            ex.push_back(x);
        }
        head["external"] = ex;
    }
    head["oracle_rounding_steps"] = r.oracle_steps;
    head["oracle_rounded_by_intervals"] = r.oracle_by_intervals;
    head["oracle_rounded_by_filter"] = r.oracle_by_filter;
    // One row and one curve per line, so that two reports diff line by line.
    std::string s = jsonl::dump(head);
    s.pop_back(); // the closing brace
    s += ",\"rows\":[";
    bool first = true;
    for (const auto& [key, row] : r.rows) {
        s += (first ? "\n" : ",\n") + jsonl::dump(row_json(key, row));
        first = false;
    }
    s += "],\n\"curves\":[";
    first = true;
    for (const auto& [key, points] : r.curves) {
        s += (first ? "\n" : ",\n") + jsonl::dump(curve_json(key, points));
        first = false;
    }
    return s + "]}\n";
}

bool from_json(std::string_view text, Report* r, std::string* why) {
    Json root;
    jsonl::ReleaseOnUnwind release(root); // a report's million values, out of memory
    std::string err;
    if (!jsonl::parse(text, &root, &err)) return *why = "not valid JSON: " + err, false;
    try {
        read_report(root, r);
    } catch (const Invalid& e) {
        *why = e.what();
        return false;
    }
    return true;
}

bool read_json(const std::string& path, Report* r, std::string* why) {
    // Memory runs out on an endless or enormous input (a FIFO fed forever, /dev/zero): said with
    // the file it was reading, not as a bare "out of memory".
    try {
        std::string text = jsonl::read_file(path);
        if (!from_json(text, r, why)) return *why = path + ": " + *why, false;
    } catch (const std::bad_alloc&) {
        return *why = path + ": out of memory while reading it (is it a report.json?)", false;
    } catch (const std::runtime_error& e) {
        return *why = e.what(), false;
    }
    return true;
}

void write_json(const Report& r, const std::string& path) {
    jsonl::write_file(path, to_json(r));
}

} // namespace linequad::audit
