// The verdict a person reads first: per solver, the share of its cases classified right, where it
// breaks, its errors in bits; and the gates a CI job puts on a solver (--expect).
#include "linequad/audit.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace linequad::audit {

namespace {

// The share that marks a family as broken at a difficulty k: 1 % of that k's cases misclassified.
constexpr double breaking_share = 0.01;

double bits(double ulps) {
    return std::log2(1 + ulps);
}

std::string number(double x, const char* format) {
    char text[48];
    std::snprintf(text, sizeof text, format, x);
    return text;
}

} // namespace

Row family_total(const Report& r, const std::string& family, const std::string& solver) {
    Row t;
    for (const auto& [key, row] : r.rows)
        if (key.family == family && key.solver == solver) t.merge(row);
    return t;
}

int breaks_at(const Report& r, const std::string& family, const std::string& solver) {
    auto it = r.curves.find({family, solver});
    if (it == r.curves.end()) return -1;
    for (const auto& [k, p] : it->second)
        if (p.cases && double(p.mismatched) >= breaking_share * double(p.cases)) return k;
    return -1;
}

double Verdict::t_max_bits() const {
    return bits(t_max_ulps);
}
double Verdict::t_p99_bits() const {
    return bits(t_p99_ulps);
}

std::vector<Verdict> verdicts(const Report& r) {
    std::vector<Verdict> out;
    for (const std::string& s : r.solvers) {
        Row t = r.total(s);
        Verdict v;
        v.solver = s;
        v.cases = t.cases, v.misclassified = t.cases_mismatched;
        v.within_tolerance = t.within_tolerance, v.not_asked = not_asked_count(t);
        v.unrepresented = t.unrepresented, v.sign_wrong = t.t_sign_wrong;
        v.errors = t.graded_roots > 0;
        v.t_max_ulps = double(t.t_max), v.t_p99_ulps = t.t_quantile(0.99);
        for (const std::string& f : r.families) {
            Row in = family_total(r, f, s);
            if (in.cases && in.cases_mismatched)
                v.worst_families.push_back({f, in.cases_mismatched, in.cases, breaks_at(r, f, s)});
        }
        std::stable_sort(v.worst_families.begin(), v.worst_families.end(),
                         [](const FamilyShare& a, const FamilyShare& b) {
                             // a/b > c/d without rounding: a d > c b (counts below 2^32 each in
                             // practice; long double holds the products exactly to 2^64).
                             return (long double)a.misclassified * (long double)b.cases >
                                    (long double)b.misclassified * (long double)a.cases;
                         });
        if (v.worst_families.size() > 3) v.worst_families.resize(3);
        out.push_back(std::move(v));
    }
    return out;
}

std::string bits_text(double ulps) {
    return ulps == 0 ? "0" : number(bits(ulps), "%.1f");
}

std::string grouped(std::uint64_t n) {
    std::string digits = std::to_string(n), out;
    for (std::size_t i = 0; i < digits.size(); ++i) {
        if (i && (digits.size() - i) % 3 == 0) out += ',';
        out += digits[i];
    }
    return out;
}

std::string percent_of(std::uint64_t part, std::uint64_t whole) {
    if (whole == 0) return "-";
    if (part == 0) return "0 %";
    if (part == whole) return "100 %";
    double p = 100.0 * double(part) / double(whole);
    if (p < 0.01) return "< 0.01 %";
    if (p > 99.99) return "> 99.99 %";
    return number(p, p < 10 ? "%.2f %%" : "%.1f %%");
}

std::string verdict_line(const Verdict& v) {
    std::string line = v.solver + ": ";
    if (v.cases == 0) return line + "graded no case";
    line += percent_of(v.cases - v.misclassified - v.within_tolerance, v.cases) + " right of " +
            std::to_string(v.cases);
    if (v.within_tolerance)
        line += ", " + percent_of(v.within_tolerance, v.cases) + " within its tolerance";
    if (v.misclassified) {
        const FamilyShare& w = v.worst_families.front();
        line += "; misclassifies most in " + w.family + " (" +
                percent_of(w.misclassified, w.cases) +
                (w.breaks_at >= 0 ? ", from k = " + std::to_string(w.breaks_at) : "") + ")";
    }
    if (v.errors)
        line += "; t error " + bits_text(v.t_max_ulps) + " bits at worst, " +
                bits_text(v.t_p99_ulps) + " at p99";
    if (v.sign_wrong) line += "; " + std::to_string(v.sign_wrong) + " roots of the wrong sign";
    return line;
}

bool parse_expectation(std::string_view text, Expectation* e, std::string* why) {
    std::size_t colon = text.find(':'), le = text.find("<=");
    if (colon == std::string_view::npos || le == std::string_view::npos || le < colon) {
        *why = "expected SOLVER:METRIC<=VALUE, not '" + std::string(text) + "'";
        return false;
    }
    e->solver = std::string(text.substr(0, colon));
    e->metric = std::string(text.substr(colon + 1, le - colon - 1));
    std::string value(text.substr(le + 2));
    if (e->solver.empty()) {
        *why = "no solver before ':' in '" + std::string(text) + "'";
        return false;
    }
    if (e->metric != "misclassified" && e->metric != "t_bits_max" && e->metric != "t_bits_p99") {
        *why = "no metric '" + e->metric + "' (misclassified, t_bits_max or t_bits_p99)";
        return false;
    }
    char* end = nullptr;
    e->at_most = std::strtod(value.c_str(), &end);
    if (value.empty() || end != value.c_str() + value.size() || !std::isfinite(e->at_most) ||
        e->at_most < 0) {
        *why = "'" + value + "' is not a finite value of at least 0";
        return false;
    }
    return true;
}

std::vector<std::string> unmet(const Report& r, const std::vector<Expectation>& expectations) {
    std::vector<std::string> out;
    for (const Expectation& e : expectations) {
        std::string gate = e.solver + ":" + e.metric + "<=" + number(e.at_most, "%g");
        if (std::find(r.solvers.begin(), r.solvers.end(), e.solver) == r.solvers.end()) {
            out.push_back(gate + ": no solver '" + e.solver + "' in this audit");
            continue;
        }
        if (r.total(e.solver).cases == 0) {
            out.push_back(gate + ": " + e.solver + " graded no case");
            continue;
        }
        for (const std::string& f : r.families) {
            Row t = family_total(r, f, e.solver);
            if (t.cases == 0) continue;
            double value = 0;
            std::string said;
            if (e.metric == "misclassified") {
                value = 100.0 * double(t.cases_mismatched) / double(t.cases);
                said = percent_of(t.cases_mismatched, t.cases);
            } else {
                if (!t.graded_roots) continue;
                double ulps = e.metric == "t_bits_max" ? double(t.t_max) : t.t_quantile(0.99);
                value = bits(ulps);
                said = number(value, "%.2f") + " bits";
            }
            if (value > e.at_most) out.push_back(gate + ": " + f + " has " + said);
        }
    }
    return out;
}

} // namespace linequad::audit
