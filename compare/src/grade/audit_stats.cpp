// Mergeable statistics and the grading of one result against the oracle's.
#include "linequad/audit.hpp"

#include "shapes/all.hpp"

#include "linequad/case_io.hpp"

#include "numeric/format.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

namespace linequad::audit {

std::uint64_t ulps_between(double a, double b, Precision p) {
    if (std::isnan(a) || std::isnan(b)) return std::numeric_limits<std::uint64_t>::max();
    if (p == Precision::binary64) return detail::Binary64::ulps_between(a, b);
    // A float answer that is not a float is at least an ulp off, however near a float it is.
    std::uint64_t u = detail::Binary32::ulps_between(a, b);
    bool floats = detail::Binary32::holds(a) && detail::Binary32::holds(b);
    return floats || u > 0 ? u : 1;
}

double half_ulp_of(double x, Precision p) {
    if (!std::isfinite(x)) return 0;
    if (p == Precision::binary32) return detail::Binary32::half_ulp(double(float(x)));
    return 0.5 * (std::nextafter(std::fabs(x), INFINITY) - std::fabs(x));
}

int Histogram::bucket(std::uint64_t u) {
    if (u < std::uint64_t(exact)) return int(u);
    int b = exact + int(std::floor(4 * std::log2(double(u) / 16.0)));
    return std::min(std::max(b, exact), bins - 1);
}

double Histogram::upper_edge(int b) {
    if (b < exact) return b;
    return 16.0 * std::exp2((b - exact + 1) / 4.0);
}

std::uint64_t Histogram::total() const {
    std::uint64_t n = 0;
    for (auto c : count)
        n += c;
    return n;
}

double Histogram::quantile(double q) const {
    std::uint64_t n = total();
    if (n == 0) return 0;
    std::uint64_t need = std::uint64_t(std::ceil(q * double(n))), seen = 0;
    for (int b = 0; b < bins; ++b) {
        seen += count[b];
        if (seen >= need && seen > 0) return upper_edge(b);
    }
    return upper_edge(bins - 1);
}

void Histogram::merge(const Histogram& o) {
    for (int b = 0; b < bins; ++b)
        count[b] += o.count[b];
}

void TimeHistogram::add(double ns) {
    int b = ns <= 0.25 ? 0 : int(std::floor(16 * std::log2(ns / 0.25)));
    ++count[std::min(std::max(b, 0), bins - 1)];
}

double TimeHistogram::median() const {
    std::uint64_t n = 0;
    for (auto c : count)
        n += c;
    if (n == 0) return 0;
    std::uint64_t seen = 0;
    for (int b = 0; b < bins; ++b) {
        seen += count[b];
        if (2 * seen >= n) return 0.25 * std::exp2((b + 0.5) / 16.0); // bucket centre: within 2.2%
    }
    return 0;
}

void TimeHistogram::merge(const TimeHistogram& o) {
    for (int b = 0; b < bins; ++b)
        count[b] += o.count[b];
}

const char* mismatch_name(int m) {
    static const char* const names[mismatch_kinds] = {"invented",          "missed",
                                                      "tangent_missed",    "tangent_invented",
                                                      "on_surface_missed", "on_surface_invented",
                                                      "nonfinite",         "refused",
                                                      "crashed",           "part_wrong"};
    return names[m];
}

struct Worst::Graded {
    Case c;
    std::string solver, reference;
    Result got, oracle;
    Carries carries;
};

Worst::Worst(std::string case_line, std::string solver_line, std::string oracle_line)
    : case_line_(std::move(case_line)), solver_line_(std::move(solver_line)),
      oracle_line_(std::move(oracle_line)) {}

Worst::Worst(const Case& c, const std::string& solver, const Result& got, const Result& oracle,
             Carries carries, std::string_view reference)
    : graded_(std::make_shared<const Graded>(
          Graded{c, solver, std::string(reference), got, oracle, carries})) {}

void Worst::write_lines() const {
    if (!graded_) return;
    const Graded& g = *graded_;
    case_line_ = format_case(g.c);
    // Both as graded: the solver's answer with what it carries, the reference with what of it was
    // graded (a convention's hit has no kind or part of its own).
    solver_line_ = format_result(g.c.id, g.solver, g.got, g.carries);
    oracle_line_ = format_result(g.c.id, g.reference, g.oracle,
                                 g.reference == "exact" ? Carries{} : g.carries);
    graded_.reset();
}
const std::string& Worst::case_line() const {
    write_lines();
    return case_line_;
}
const std::string& Worst::solver_line() const {
    write_lines();
    return solver_line_;
}
const std::string& Worst::oracle_line() const {
    write_lines();
    return oracle_line_;
}

namespace {
bool worse(const Worst& a, const Worst& b) {
    if (a.mismatch != b.mismatch) return a.mismatch;
    return a.ulps > b.ulps;
}
void keep(std::vector<Worst>& list, Worst w) {
    list.push_back(std::move(w));
    std::stable_sort(list.begin(), list.end(), worse);
    if (list.size() > Row::keep_worst) list.resize(Row::keep_worst);
}
bool qualifies(const std::vector<Worst>& list, bool mismatch, std::uint64_t ulps) {
    if (list.size() < Row::keep_worst) return mismatch || ulps > 0;
    Worst w;
    w.mismatch = mismatch, w.ulps = ulps;
    return worse(w, list.back());
}
bool finite_result(const Result& r) {
    for (int i = 0; i < r.count; ++i)
        if (!std::isfinite(r.hits[i].t) || !is_finite(r.hits[i].p)) return false;
    return !r.on_surface || (!std::isnan(r.s0) && !std::isnan(r.s1));
}
// A point's error in ulps (of the case's format) of its natural scale, the largest of |p|, |L0|
// and |t v| (it is computed as L0 + t v): a coordinate that cancels to nearly zero would
// otherwise report an enormous relative error that says nothing about the hit.
std::uint64_t point_ulps(Vec3 got, Vec3 want, const Line& l, double t, Precision p) {
    if (got == want) return 0; // equal infinities included
    double scale = std::max({max_abs(want), max_abs(l.L0), std::fabs(t) * max_abs(l.v)});
    double err = max_abs(got - want);
    if (err == 0) return 0;
    if (!std::isfinite(err)) return std::numeric_limits<std::uint64_t>::max();
    if (!std::isfinite(scale)) return std::numeric_limits<std::uint64_t>::max();
    double ulp = 2 * half_ulp_of(scale, p);
    if (ulp == 0) ulp = p == Precision::binary32 ? 0x1p-149 : 0x1p-1074;
    double u = std::ceil(err / ulp);
    return u >= 1.8e19 ? std::numeric_limits<std::uint64_t>::max() : std::uint64_t(u);
}

// The scene's magnitude for the scene-relative error: the largest coordinate of the shape's
// defining points and sizes (its traits' magnitude), of L0, and of t v.
double scene_size(const Case& c, double t) {
    double m = std::max(max_abs(c.line.L0), std::fabs(t) * max_abs(c.line.v));
    return std::max(m,
                    std::visit([](const auto& x) { return detail::shape_magnitude(x); }, c.shape));
}

// |t - t_oracle| |v| in ulps (of the case's format) of the scene's magnitude, rounded up.
std::uint64_t scene_ulps(const Case& c, double got, double want) {
    if (got == want) return 0;
    double err = std::fabs(got - want) * max_abs(c.line.v);
    double ulp = 2 * half_ulp_of(scene_size(c, want), c.precision);
    if (!std::isfinite(err) || !(ulp > 0)) return std::numeric_limits<std::uint64_t>::max();
    double u = std::ceil(err / ulp);
    return u >= 1.8e19 ? std::numeric_limits<std::uint64_t>::max() : std::uint64_t(u);
}

double capped(const Histogram& h, double q, std::uint64_t max) {
    return std::min(h.quantile(q), double(max));
}
} // namespace

double Row::t_quantile(double q) const {
    return capped(t_error, q, t_max);
}
double Row::p_quantile(double q) const {
    return capped(p_error, q, p_max);
}
double Row::s_quantile(double q) const {
    return capped(s_error, q, s_max);
}

void Row::merge(const Row& o) {
    cases += o.cases, graded_roots += o.graded_roots, graded_coords += o.graded_coords;
    s_error.merge(o.s_error), s_max = std::max(s_max, o.s_max);
    unrepresented += o.unrepresented;
    within_tolerance += o.within_tolerance;
    t_sign_wrong += o.t_sign_wrong;
    for (const auto& [why, n] : o.not_asked)
        not_asked[why] += n;
    for (const auto& [name, n] : o.unrepresented_why)
        unrepresented_why[name] += n;
    for (const auto& [name, n] : o.foreign)
        foreign[name] += n;
    for (const auto& [name, n] : o.environment)
        environment[name] += n;
    binary32_cases += o.binary32_cases;
    for (int m = 0; m < mismatch_kinds; ++m)
        mismatches[m] += o.mismatches[m];
    cases_mismatched += o.cases_mismatched;
    t_error.merge(o.t_error), p_error.merge(o.p_error);
    t_max = std::max(t_max, o.t_max), p_max = std::max(p_max, o.p_max);
    t_sum += o.t_sum, t_bits_sum += o.t_bits_sum;
    ns.merge(o.ns);
    uncertain += o.uncertain, certain_wrong += o.certain_wrong;
    bounded_roots += o.bounded_roots, bound_violations += o.bound_violations;
    tightness.merge(o.tightness);
    bound_below_half_ulp += o.bound_below_half_ulp;
    for (std::size_t i = 0; i < rungs.size(); ++i)
        rungs[i] += o.rungs[i];
    for (const Worst& w : o.worst)
        keep(worst, w);
}

namespace {

int tangents(const Result& r) {
    int n = 0;
    for (int i = 0; i < r.count; ++i)
        n += r.hits[i].kind == HitKind::tangent;
    return n;
}

// A library's call that never returned an answer (a crash, an exit, a hang), as the in-process
// guard and the plugin worker name it.
bool did_not_return(const Result& r) {
    if (r.error_code != ErrorCode::foreign) return false;
    std::string_view why = r.error_field;
    for (std::string_view prefix : {"crashed", "exited", "timed out", "killed"})
        if (why.substr(0, prefix.size()) == prefix) return true;
    return false;
}

// How an answer is classified against its reference: each kind of mismatch it makes.
using Flags = std::array<bool, mismatch_kinds>;
Flags classify(const Result& got, const Result& want, const Grading& what) {
    Flags f{};
    if (did_not_return(got)) {
        f[crashed] = true;
    } else if (!want.ok() || !got.ok()) {
        f[refused] = want.ok() != got.ok() || want.error_code != got.error_code;
    } else if (!finite_result(got) && finite_result(want)) {
        f[nonfinite] = true;
    } else if (want.on_surface != got.on_surface) {
        f[want.on_surface ? on_surface_missed : on_surface_invented] = true;
    } else {
        // A solver that does not tell tangents from crossings is graded on its count of hits.
        int tw = tangents(want), tg = what.kinds ? tangents(got) : tw;
        f[tangent_missed] = tw > tg, f[tangent_invented] = tg > tw;
        f[invented] = got.count > want.count, f[missed] = got.count < want.count;
        if (want.count == got.count && !f[tangent_missed] && !f[tangent_invented]) {
            bool parts = !want.on_surface || want.surface_part == got.surface_part;
            for (int i = 0; i < want.count; ++i)
                parts = parts && want.hits[i].part == got.hits[i].part;
            f[part_wrong] = what.parts && !parts;
        }
    }
    return f;
}

// The errors of an answer classified like its reference (hits on other parts are other roots:
// nothing is measured between them): t and the scene error, certified bounds, points. Returns
// the case's largest t error in ulps.
std::uint64_t grade_roots(const Answered& a, Row& row, CurvePoint* curve) {
    const Case& c = a.c;
    std::uint64_t case_max = 0;
    // A certified bound must cover the exact root; the oracle's t is within half an ulp of it,
    // so a bound holds when |t - t_oracle| <= bound + ulp(t_oracle) / 2.
    auto check_bound = [&](const Hit& h, double o) {
        if (std::isnan(h.bound)) return;
        ++row.bounded_roots;
        double half_ulp = half_ulp_of(o, c.precision);
        double err = std::fabs(h.t - o);
        if (!(err <= h.bound + half_ulp)) ++row.bound_violations;
        if (h.bound < half_ulp) ++row.bound_below_half_ulp;
        double ratio = h.bound / std::fmax(err, half_ulp);
        row.tightness.add(std::isfinite(ratio) && ratio < 1.8e19 ? std::uint64_t(std::ceil(ratio))
                                                                 : UINT64_MAX);
    };
    auto add_t = [&](double g, double o) {
        // A root of the wrong sign, or 0 against a nonzero one: counted as what it is (its ulp
        // distance, through every float between them, would read near 2^63). Its scene error
        // still says how far the hit is; the case ranks first among its row's worst.
        bool sign_wrong = (g == 0) != (o == 0) || (g != 0 && std::signbit(g) != std::signbit(o));
        if (sign_wrong && std::isfinite(g) && std::isfinite(o)) {
            ++row.t_sign_wrong;
            case_max = UINT64_MAX;
            std::uint64_t su = scene_ulps(c, g, o);
            row.s_error.add(su);
            row.s_max = std::max(row.s_max, su);
            return;
        }
        std::uint64_t u = ulps_between(g, o, c.precision);
        row.t_error.add(u);
        if (curve) curve->t_error.add(u);
        row.t_max = std::max(row.t_max, u);
        row.t_sum += double(u);
        if (u > 0) row.t_bits_sum += std::log2(1.0 + double(u)); // log2(1) adds 0
        ++row.graded_roots;
        case_max = std::max(case_max, u);
        std::uint64_t su = std::isinf(o) && g == o ? 0 : scene_ulps(c, g, o);
        row.s_error.add(su);
        row.s_max = std::max(row.s_max, su);
    };
    const Result &got = a.got, &want = a.reference;
    if (want.on_surface) {
        add_t(got.s0, want.s0);
        add_t(got.s1, want.s1);
    }
    for (int i = 0; i < want.count; ++i) {
        add_t(got.hits[i].t, want.hits[i].t);
        check_bound(got.hits[i], want.hits[i].t);
        if (!a.what.points) continue;
        std::uint64_t u =
            point_ulps(got.hits[i].p, want.hits[i].p, c.line, want.hits[i].t, c.precision);
        row.p_error.add(u);
        row.p_max = std::max(row.p_max, u);
        ++row.graded_coords;
    }
    return case_max;
}

} // namespace

void grade(const Answered& a, Row& row, CurvePoint* curve) {
    const Result& got = a.got;
    ++row.cases;
    if (got.error_code == ErrorCode::foreign) ++row.foreign[got.error_field];
    row.binary32_cases += a.c.precision == Precision::binary32;
    if (got.ok() && got.rung != Rung::none) ++row.rungs[std::size_t(got.rung)];
    Flags flags = classify(got, a.reference, a.what);
    bool mismatch = std::find(flags.begin(), flags.end(), true) != flags.end();
    // Wrong by the exact surface, right by one within the solver's declared tolerance: its own
    // count, nothing measured (the roots it would compare are another surface's).
    if (mismatch && !flags[crashed] && a.tolerated && (*a.tolerated)(got)) {
        ++row.within_tolerance;
        if (curve) ++curve->cases;
        return;
    }
    std::uint64_t case_max = mismatch ? 0 : grade_roots(a, row, curve);
    // A certified solver that says it is unsure is not wrong; one that is sure must be right.
    if (got.ok() && got.certainty == Certainty::uncertain) {
        ++row.uncertain;
        mismatch = false;
    } else {
        for (int m = 0; m < mismatch_kinds; ++m)
            row.mismatches[m] += flags[m];
        if (mismatch && got.certainty == Certainty::certain) ++row.certain_wrong;
    }
    row.cases_mismatched += mismatch;
    if (curve) {
        ++curve->cases;
        curve->mismatched += mismatch;
        if (case_max != UINT64_MAX) curve->t_max = std::max(curve->t_max, case_max);
    }
    if (qualifies(row.worst, mismatch, case_max)) {
        Worst w(a.c, a.solver, got, a.reference, a.what, a.reference_name);
        w.mismatch = mismatch, w.ulps = case_max;
        keep(row.worst, std::move(w));
    }
}

const char* status_name(Status s) {
    switch (s) {
    case Status::running:
        return "running";
    case Status::stopped:
        return "stopped";
    case Status::complete:
        return "complete";
    }
    return "?";
}

namespace {
std::string joined(const std::vector<std::string>& v) {
    std::string s;
    for (const std::string& x : v)
        s += (s.empty() ? "" : ",") + x;
    return "[" + s + "]";
}
} // namespace

std::string unmergeable(const Report& a, const Report& b) {
    if (a.from_cases_file() || b.from_cases_file())
        return "it grades a cases file; merge combines the shards of one campaign";
    auto differ = [](const char* what, const std::string& x, const std::string& y) {
        return std::string(what) + " differ: " + y + " here, " + x + " in the first report";
    };
    if (a.seed != b.seed) return differ("seeds", std::to_string(a.seed), std::to_string(b.seed));
    if (a.cases_per_group != b.cases_per_group)
        return differ("case counts (per family, shape and range)",
                      std::to_string(a.cases_per_group), std::to_string(b.cases_per_group));
    if (a.families != b.families) return differ("families", joined(a.families), joined(b.families));
    if (a.shapes != b.shapes) return differ("shapes", joined(a.shapes), joined(b.shapes));
    if (a.frames != b.frames) return differ("frames", a.frames, b.frames);
    if (a.ranges != b.ranges) return differ("ranges", joined(a.ranges), joined(b.ranges));
    if (a.solvers != b.solvers) return differ("solvers", joined(a.solvers), joined(b.solvers));
    if (a.shards != b.shards)
        return differ("shard counts", std::to_string(a.shards), std::to_string(b.shards));
    if (a.version != b.version) return differ("linequad versions", a.version, b.version);
    if (a.compiler != b.compiler) return differ("compilers", a.compiler, b.compiler);
    if (a.flags != b.flags) return differ("fast/ compiler flags", a.flags, b.flags);
    for (int k : b.shards_included)
        if (std::find(a.shards_included.begin(), a.shards_included.end(), k) !=
            a.shards_included.end())
            return "shard " + std::to_string(k) + " is already merged";
    return "";
}

void Report::merge(const Report& o) {
    merge_statistics(o);
    // The least finished status stands for the whole.
    status = std::min(status, o.status);
    seconds += o.seconds;
    shards_included.insert(shards_included.end(), o.shards_included.begin(),
                           o.shards_included.end());
    shard_marks.insert(o.shard_marks.begin(), o.shard_marks.end());
    std::sort(shards_included.begin(), shards_included.end());
}

void Report::merge_statistics(const Report& o) {
    for (const auto& [key, row] : o.rows)
        rows[key].merge(row);
    for (const auto& [key, points] : o.curves)
        for (const auto& [k, p] : points) {
            CurvePoint& q = curves[key][k];
            q.cases += p.cases, q.mismatched += p.mismatched;
            q.t_max = std::max(q.t_max, p.t_max);
            q.t_error.merge(p.t_error);
        }
    for (int i = 0; i < 8; ++i)
        oracle_steps[i] += o.oracle_steps[i];
    oracle_by_intervals += o.oracle_by_intervals;
    oracle_by_filter += o.oracle_by_filter;
}

std::uint64_t not_asked_count(const Row& r) {
    std::uint64_t n = 0;
    for (const auto& [why, count] : r.not_asked)
        n += count;
    return n;
}

Row Report::total(const std::string& solver) const {
    Row t;
    for (const auto& [key, row] : rows)
        if (key.solver == solver) t.merge(row);
    return t;
}

} // namespace linequad::audit
