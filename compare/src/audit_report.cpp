// report.json (exact, mergeable), report.md (for people) and the gnuplot figures.
#include "linequad/audit.hpp"

#include "linequad/json.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

namespace linequad::audit {

namespace {

using json::Value;

std::string num(std::uint64_t x) {
    return std::to_string(x);
}
std::string real(double x) {
    char b[32];
    std::snprintf(b, sizeof b, "%.17g", x);
    return b;
}
template <class Array>
std::string array(const Array& a) {
    // Histograms are mostly zeros: written as [index, count] pairs.
    std::string s = "[";
    bool first = true;
    for (std::size_t i = 0; i < a.size(); ++i)
        if (a[i]) {
            s += (first ? "[" : ",[") + num(i) + "," + num(a[i]) + "]";
            first = false;
        }
    return s + "]";
}
std::string str(const std::string& x) {
    std::string s;
    json::write_string(s, x);
    return s;
}

std::string row_json(const Row& r) {
    std::string s = "{\"cases\":" + num(r.cases) + ",\"graded_roots\":" + num(r.graded_roots) +
                    ",\"graded_points\":" + num(r.graded_coords) +
                    ",\"cases_mismatched\":" + num(r.cases_mismatched) + ",\"mismatches\":{";
    for (int m = 0; m < mismatch_kinds; ++m)
        s += (m ? ",\"" : "\"") + std::string(mismatch_name(m)) + "\":" + num(r.mismatches[m]);
    s += "},\"t_ulps\":{\"max\":" + num(r.t_max) +
         ",\"mean\":" + real(r.graded_roots ? r.t_sum / double(r.graded_roots) : 0) +
         ",\"p50\":" + real(r.t_error.quantile(0.5)) +
         ",\"p99\":" + real(r.t_error.quantile(0.99)) +
         ",\"p999\":" + real(r.t_error.quantile(0.999)) +
         ",\"mean_bits\":" + real(r.graded_roots ? r.t_bits_sum / double(r.graded_roots) : 0) +
         ",\"sum\":" + real(r.t_sum) + ",\"bits_sum\":" + real(r.t_bits_sum) +
         ",\"histogram\":" + array(r.t_error.count) + "}";
    s += ",\"point_ulps\":{\"max\":" + num(r.p_max) + ",\"p99\":" + real(r.p_error.quantile(0.99)) +
         ",\"histogram\":" + array(r.p_error.count) + "}";
    s += ",\"ns_per_solve\":{\"median\":" + real(r.ns.median()) +
         ",\"histogram\":" + array(r.ns.count) + "}";
    s += ",\"certified\":{\"uncertain\":" + num(r.uncertain) +
         ",\"certain_wrong\":" + num(r.certain_wrong) +
         ",\"bounded_roots\":" + num(r.bounded_roots) +
         ",\"bound_violations\":" + num(r.bound_violations) +
         ",\"tightness_p50\":" + real(r.tightness.quantile(0.5)) +
         ",\"bound_below_half_ulp\":" + num(r.bound_below_half_ulp) +
         ",\"tightness\":" + array(r.tightness.count) + "}";
    s += ",\"rungs\":{\"newton\":" + num(r.rungs[std::size_t(Rung::newton)]) +
         ",\"double_double\":" + num(r.rungs[std::size_t(Rung::double_double)]) +
         ",\"exact\":" + num(r.rungs[std::size_t(Rung::exact)]) + "}";
    s += ",\"worst\":[";
    for (std::size_t i = 0; i < r.worst.size(); ++i) {
        const Worst& w = r.worst[i];
        s += (i ? ",{" : "{") + std::string("\"mismatch\":") + (w.mismatch ? "true" : "false") +
             ",\"t_ulps\":" + num(w.ulps) + ",\"case\":" + str(w.case_line) +
             ",\"solver\":" + str(w.solver_line) + ",\"oracle\":" + str(w.oracle_line) + "}";
    }
    return s + "]}";
}

template <class Array>
void read_array(const Value* v, Array& a) {
    if (!v) return;
    for (const Value& pair : v->items)
        if (pair.items.size() == 2) {
            std::size_t i = std::stoull(pair.items[0].text);
            if (i < a.size()) a[i] = std::stoull(pair.items[1].text);
        }
}
std::uint64_t u64(const Value* v) {
    return v && v->type == Value::Type::number ? std::stoull(v->text) : 0;
}
double dbl(const Value* v) {
    return v && v->type == Value::Type::number ? std::stod(v->text) : 0;
}
std::string text(const Value* v) {
    return v && v->type == Value::Type::string ? v->text : "";
}

Row row_from(const Value& v) {
    Row r;
    r.cases = u64(v.find("cases")), r.graded_roots = u64(v.find("graded_roots"));
    r.graded_coords = u64(v.find("graded_points")),
    r.cases_mismatched = u64(v.find("cases_mismatched"));
    if (const Value* m = v.find("mismatches"))
        for (int k = 0; k < mismatch_kinds; ++k)
            r.mismatches[k] = u64(m->find(mismatch_name(k)));
    if (const Value* t = v.find("t_ulps")) {
        r.t_max = u64(t->find("max")), r.t_sum = dbl(t->find("sum")),
        r.t_bits_sum = dbl(t->find("bits_sum"));
        read_array(t->find("histogram"), r.t_error.count);
    }
    if (const Value* p = v.find("point_ulps")) {
        r.p_max = u64(p->find("max"));
        read_array(p->find("histogram"), r.p_error.count);
    }
    if (const Value* n = v.find("ns_per_solve")) read_array(n->find("histogram"), r.ns.count);
    if (const Value* c = v.find("certified")) {
        r.uncertain = u64(c->find("uncertain")), r.certain_wrong = u64(c->find("certain_wrong"));
        r.bounded_roots = u64(c->find("bounded_roots")),
        r.bound_violations = u64(c->find("bound_violations"));
        read_array(c->find("tightness"), r.tightness.count);
        r.bound_below_half_ulp = u64(c->find("bound_below_half_ulp"));
    }
    if (const Value* g = v.find("rungs")) {
        r.rungs[std::size_t(Rung::newton)] = u64(g->find("newton")); // 0 in older reports
        r.rungs[std::size_t(Rung::double_double)] = u64(g->find("double_double"));
        r.rungs[std::size_t(Rung::exact)] = u64(g->find("exact"));
    }
    if (const Value* w = v.find("worst"))
        for (const Value& x : w->items) {
            Worst k;
            const Value* mm = x.find("mismatch");
            k.mismatch = mm && mm->boolean;
            k.ulps = u64(x.find("t_ulps"));
            k.case_line = text(x.find("case")), k.solver_line = text(x.find("solver")),
            k.oracle_line = text(x.find("oracle"));
            r.worst.push_back(k);
        }
    return r;
}

std::string fmt(double x) {
    char b[32];
    if (x == 0) return "0";
    if (x < 1e4 && x == std::floor(x))
        std::snprintf(b, sizeof b, "%.0f", x);
    else if (x < 1e4)
        std::snprintf(b, sizeof b, "%.3g", x);
    else
        std::snprintf(b, sizeof b, "%.2e", x);
    return b;
}
std::string fmt_ulps(std::uint64_t u) {
    return u == UINT64_MAX ? "inf" : fmt(double(u));
}

// The shell command that replays a case: the solver and the oracle side by side.
std::string replay(const Worst& w, const std::string& solver) {
    std::string quoted;
    for (char c : w.case_line)
        quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
    // `solve` takes one line at a time; batch's results are stable's, bit for bit.
    std::string scalar = solver == batch_name ? "stable" : solver;
    return "echo '" + quoted + "' | linequad solve --solver " + scalar + ",exact";
}

} // namespace

void write_json(const Report& r, const std::string& path) {
    std::string s =
        "{\"format\":\"linequad-audit-1\",\"command\":" + str(r.command) +
        ",\"machine\":" + str(r.machine) + ",\"compiler\":" + str(r.compiler) +
        ",\"flags\":" + str(r.flags) + ",\"commit\":" + str(r.commit) + ",\"date\":" + str(r.date) +
        ",\"seed\":" + num(r.seed) + ",\"cases_per_group\":" + num(r.cases_per_group) +
        ",\"shard\":" + std::to_string(r.shard) + ",\"shards\":" + std::to_string(r.shards) +
        ",\"complete\":" + (r.complete ? "true" : "false") + ",\"seconds\":" + real(r.seconds) +
        ",\"solvers\":[";
    for (std::size_t i = 0; i < r.solvers.size(); ++i)
        s += (i ? "," : "") + str(r.solvers[i]);
    s += "],\"oracle_rounding_steps\":[";
    for (int i = 0; i < 8; ++i)
        s += (i ? "," : "") + num(r.oracle_steps[i]);
    s += "],\"rows\":{";
    bool first = true;
    for (const auto& [key, row] : r.rows) {
        s += (first ? "" : ",\n") + str(key) + ":" + row_json(row);
        first = false;
    }
    s += "},\"curves\":{";
    first = true;
    for (const auto& [key, points] : r.curves) {
        s += (first ? "" : ",\n") + str(key) + ":[";
        bool f2 = true;
        for (const auto& [k, p] : points) {
            s += (f2 ? "" : ",") + std::string("{\"k\":") + std::to_string(k) +
                 ",\"cases\":" + num(p.cases) + ",\"mismatched\":" + num(p.mismatched) +
                 ",\"t_max\":" + num(p.t_max) + ",\"histogram\":" + array(p.t_error.count) + "}";
            f2 = false;
        }
        s += "]";
        first = false;
    }
    s += "}}\n";
    // Written to a temporary file and renamed: a reader never sees half a report.
    std::string tmp = path + ".tmp";
    {
        std::ofstream out(tmp, std::ios::binary);
        out << s;
        if (!out) throw std::runtime_error("cannot write " + tmp);
    }
    if (std::rename(tmp.c_str(), path.c_str()) != 0)
        throw std::runtime_error("cannot write " + path);
}

bool read_json(const std::string& path, Report* r, std::string* why) {
    std::ifstream in(path, std::ios::binary);
    if (!in) return *why = "cannot open " + path, false;
    std::stringstream ss;
    ss << in.rdbuf();
    Value v;
    std::string err;
    if (!json::parse(ss.str(), &v, &err)) return *why = path + ": " + err, false;
    if (text(v.find("format")) != "linequad-audit-1")
        return *why = path + ": not a linequad audit report", false;
    *r = Report{};
    r->command = text(v.find("command")), r->machine = text(v.find("machine"));
    r->compiler = text(v.find("compiler")), r->flags = text(v.find("flags"));
    r->commit = text(v.find("commit")), r->date = text(v.find("date"));
    r->seed = u64(v.find("seed")), r->cases_per_group = u64(v.find("cases_per_group"));
    r->shard = int(u64(v.find("shard"))), r->shards = int(u64(v.find("shards")));
    const Value* c = v.find("complete");
    r->complete = c && c->boolean;
    r->seconds = dbl(v.find("seconds"));
    if (const Value* s = v.find("solvers"))
        for (const Value& x : s->items)
            r->solvers.push_back(x.text);
    if (const Value* s = v.find("oracle_rounding_steps"))
        for (std::size_t i = 0; i < s->items.size() && i < 8; ++i)
            r->oracle_steps[i] = u64(&s->items[i]);
    if (const Value* rows = v.find("rows"))
        for (const auto& [key, row] : rows->members)
            r->rows[key] = row_from(row);
    if (const Value* curves = v.find("curves"))
        for (const auto& [key, points] : curves->members)
            for (const Value& p : points.items) {
                CurvePoint& q = r->curves[key][int(std::stol(p.find("k")->text))];
                q.cases = u64(p.find("cases")), q.mismatched = u64(p.find("mismatched")),
                q.t_max = u64(p.find("t_max"));
                read_array(p.find("histogram"), q.t_error.count);
            }
    return true;
}

// How often the correct solver needed each rung of its ladder, by family.
void write_rungs(std::ostream& md, const Report& r) {
    std::map<std::string, Row> by_family;
    for (const auto& [key, row] : r.rows)
        if (key.size() > 8 && key.compare(key.size() - 8, 8, "/correct") == 0)
            by_family[key.substr(0, key.find('/'))].merge(row);
    if (by_family.empty()) return;
    md << "\n## The correct solver's rungs\n\n"
          "Results settled by the Newton rung, the double-double rung (each only where its bounds "
          "proved every sign and every rounding) and the exact rung, by family; ns/solve is the "
          "median of the mix.\n\n";
    md << "| family | cases | Newton | double-double | exact | exact % | ns/solve |\n";
    md << "|---|---:|---:|---:|---:|---:|---:|\n";
    for (const auto& [family, row] : by_family) {
        std::uint64_t nw = row.rungs[std::size_t(Rung::newton)];
        std::uint64_t dd = row.rungs[std::size_t(Rung::double_double)];
        std::uint64_t ex = row.rungs[std::size_t(Rung::exact)], all = nw + dd + ex;
        md << "| " << family << " | " << row.cases << " | " << nw << " | " << dd << " | " << ex
           << " | " << fmt(all ? 100.0 * double(ex) / double(all) : 0) << " | "
           << fmt(row.ns.median()) << " |\n";
    }
    Row certified = r.total("certified");
    if (certified.bounded_roots)
        md << "\nA certified bound below half an ulp of t (the only kind that could prove a "
              "rounding on its own, without the Newton step): "
           << certified.bound_below_half_ulp << " of " << certified.bounded_roots
           << " certified roots.\n";
}

void write_markdown(const Report& r, const std::string& dir) {
    std::ostringstream md;
    md << "# linequad accuracy audit\n\n";
    md << "| | |\n|---|---|\n";
    md << "| command | `" << r.command << "` |\n| commit | " << r.commit << " |\n| date | "
       << r.date << " |\n";
    md << "| machine | " << r.machine << " |\n| compiler | " << r.compiler << " |\n";
    md << "| fast/ flags | `" << r.flags << "` |\n| seed | " << r.seed << " |\n";
    md << "| cases per family, shape and range | " << r.cases_per_group << " |\n";
    md << "| shards | " << r.shards << " |\n| complete | "
       << (r.complete ? "yes" : "**no: stopped early**") << " |\n";
    md << "| run time | " << fmt(r.seconds) << " s |\n\n";
    md << "Errors are distances to the exact oracle's correctly rounded value, in units in the "
          "last "
          "place (0: correctly rounded); bits = log2(1 + ulps) as Herbie counts them. Points: the "
          "largest coordinate error in ulps of the point's scale, max(|p|, |L0|, |t v|). A "
          "mismatch is a "
          "different classification (hit count, tangent, on-surface), a NaN/infinity, or a "
          "refusal; "
          "errors are only measured on cases classified like the oracle. A certified solver may "
          "call a "
          "case uncertain (counted apart, not as a mismatch); each of its roots carries a bound, "
          "violated when |t - t_oracle| exceeds it by more than half an ulp (the oracle's "
          "rounding); "
          "bound/err is how loose the bound is. ns/solve: median over "
          "chunks of 256 cases, this run, this machine. batch is stable's batch path (its "
          "results equal stable's bit for bit): graded on every case, one line per call; its "
          "ns is per line, each chunk's lines solved as one batch against four of the chunk's "
          "shapes.\n\n";

    md << "## Headline: every family\n\n";
    md << "| solver | cases | mismatched | uncertain | bound violations | t max ulps | t p99 | t "
          "p50 "
          "| mean bits | point max ulps | ns/solve (generic) |\n";
    md << "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
    for (const std::string& s : r.solvers) {
        Row t = r.total(s);
        Row generic;
        for (const auto& [key, row] : r.rows)
            if (key.rfind("generic/", 0) == 0 && key.size() > s.size() &&
                key.compare(key.size() - s.size() - 1, s.size() + 1, "/" + s) == 0)
                generic.merge(row);
        md << "| " << s << " | " << t.cases << " | " << t.cases_mismatched << " | "
           << (t.bounded_roots || t.uncertain ? num(t.uncertain) : "-") << " | "
           << (t.bounded_roots ? num(t.bound_violations) + " of " + num(t.bounded_roots) : "-")
           << " | " << fmt_ulps(t.t_max) << " | " << fmt(t.t_error.quantile(0.99)) << " | "
           << fmt(t.t_error.quantile(0.5)) << " | "
           << fmt(t.graded_roots ? t.t_bits_sum / double(t.graded_roots) : 0) << " | "
           << fmt_ulps(t.p_max) << " | " << fmt(generic.ns.median()) << " |\n";
    }
    md << "\n![run time against error](pareto.svg)\n\n";

    md << "## By family and shape\n\n";
    md << "| family | shape | solver | cases | mismatched | by kind | uncertain | bound viol. | "
          "bound/err p50 | t max | t p99 | t p99.9 | t mean | point max | ns/solve |\n";
    md << "|---|---|---|---:|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
    for (const auto& [key, row] : r.rows) {
        std::string family = key.substr(0, key.find('/'));
        std::string rest = key.substr(key.find('/') + 1);
        std::string shape = rest.substr(0, rest.find('/')),
                    solver = rest.substr(rest.find('/') + 1);
        std::string kinds;
        for (int m = 0; m < mismatch_kinds; ++m)
            if (row.mismatches[m])
                kinds += (kinds.empty() ? "" : ", ") + std::string(mismatch_name(m)) + " " +
                         num(row.mismatches[m]);
        md << "| " << family << " | " << shape << " | " << solver << " | " << row.cases << " | "
           << row.cases_mismatched << " | " << kinds << " | "
           << (row.bounded_roots || row.uncertain ? num(row.uncertain) : "-") << " | "
           << (row.bounded_roots ? num(row.bound_violations) : "-") << " | "
           << (row.bounded_roots ? fmt(row.tightness.quantile(0.5)) : "-") << " | "
           << fmt_ulps(row.t_max) << " | " << fmt(row.t_error.quantile(0.99)) << " | "
           << fmt(row.t_error.quantile(0.999)) << " | "
           << fmt(row.graded_roots ? row.t_sum / double(row.graded_roots) : 0) << " | "
           << fmt_ulps(row.p_max) << " | " << fmt(row.ns.median()) << " |\n";
    }

    write_rungs(md, r);

    md << "\n## Error against difficulty\n\n";
    for (const char* f : {"near_tangent", "axis_parallel", "apex", "generator", "degenerate_frame",
                          "scale", "extent_edge"})
        for (const auto& [key, points] : r.curves)
            if (key.rfind(std::string(f) + "/", 0) == 0) {
                md << "![" << f << "](difficulty_" << f << ".svg)\n\n";
                break;
            }

    md << "## Worst cases\n\nEach replays with the command under it.\n\n";
    for (const auto& [key, row] : r.rows) {
        if (row.worst.empty()) continue;
        std::string solver = key.substr(key.rfind('/') + 1);
        md << "### " << key << "\n\n";
        for (const Worst& w : row.worst) {
            md << (w.mismatch ? "- **mismatch**" : "- t error " + fmt_ulps(w.ulps) + " ulps")
               << "\n\n";
            md << "  ```\n  " << w.case_line << "\n  " << w.solver_line << "\n  " << w.oracle_line
               << "\n  ```\n\n";
            md << "  `" << replay(w, solver) << "`\n\n";
        }
    }
    md << "## Oracle rounding\n\nValues rounded at 64, 128, 256, ... bits: ";
    for (int i = 0; i < 8; ++i)
        md << (i ? ", " : "") << r.oracle_steps[i];
    md << ".\n";
    std::ofstream(dir + "/report.md") << md.str();
}

void write_plots(const Report& r, const std::string& dir) {
    if (std::system("command -v gnuplot >/dev/null 2>&1") != 0) {
        std::fprintf(stderr,
                     "linequad: gnuplot not found: no plots (apt-get install gnuplot-nox)\n");
        return;
    }
    std::ofstream gp(dir + "/plots.gp");
    auto both_terminals = [&](const std::string& name, const std::string& body) {
        gp << "set terminal svg size 800,500 dynamic noenhanced font 'sans,11'\nset output '" << dir
           << "/" << name << ".svg'\n"
           << body << "set terminal pngcairo size 800,500 noenhanced font 'sans,10'\nset output '"
           << dir << "/" << name << ".png'\nreplot\nunset output\n";
    };
    // Pareto: median ns per solve on generic cases against max and p99 t error over all families.
    {
        std::ofstream dat(dir + "/pareto.dat");
        dat << "# solver ns_generic max_ulps p99_ulps\n";
        for (const std::string& s : r.solvers) {
            Row t = r.total(s), generic;
            for (const auto& [key, row] : r.rows)
                if (key.rfind("generic/", 0) == 0 &&
                    key.compare(key.size() - s.size() - 1, s.size() + 1, "/" + s) == 0)
                    generic.merge(row);
            dat << s << " " << generic.ns.median() << " " << 1 + double(t.t_max) << " "
                << 1 + t.t_error.quantile(0.99) << "\n";
        }
        both_terminals("pareto", "set title 'run time against error (every family)'\nset xlabel "
                                 "'ns per solve, median, generic cases'\n"
                                 "set ylabel '1 + t error in ulps'\nset logscale y\nset grid\nset "
                                 "key outside bottom center horizontal\n"
                                 "set offsets graph 0.15, graph 0.15, graph 0.1, graph 0.1\n"
                                 "plot '" +
                                     dir +
                                     "/pareto.dat' using 2:3:1 with labels offset 0,1 notitle, "
                                     "'' using 2:3 with points pt 7 ps 1.5 title 'max', '' using "
                                     "2:4 with points pt 5 ps 1.5 title 'p99'\n");
    }
    // Error against difficulty, one figure per family, one curve per solver.
    std::map<std::string, std::vector<std::string>> families;
    for (const auto& [key, points] : r.curves) {
        std::string family = key.substr(0, key.find('/'));
        if (family == "generic") continue;
        std::string solver = key.substr(key.find('/') + 1);
        std::string file = dir + "/difficulty_" + family + "_" + solver + ".dat";
        std::ofstream dat(file);
        dat << "# k cases mismatched_fraction 1+max_ulps\n";
        for (const auto& [k, p] : points)
            dat << k << " " << p.cases << " "
                << (p.cases ? double(p.mismatched) / double(p.cases) : 0) << " "
                << 1 + double(p.t_max) << "\n";
        families[family].push_back(solver);
    }
    for (const auto& [family, solvers] : families) {
        std::string plot = "set title '" + family +
                           ": error and misclassification against k'\n"
                           "set xlabel 'k (difficulty 2^-k)'\nset ylabel '1 + max t error "
                           "(ulps)'\nset logscale y\n"
                           "set y2label 'fraction of cases misclassified'\nset y2range [0:1]\nset "
                           "y2tics\nset ytics nomirror\n"
                           "set grid\nset key outside right\nplot ";
        for (std::size_t i = 0; i < solvers.size(); ++i) {
            std::string f = "'" + dir + "/difficulty_" + family + "_" + solvers[i] + ".dat'";
            plot += (i ? ", " : "") + f + " using 1:4 with linespoints lw 2 title '" + solvers[i] +
                    " max error', " + f + " using 1:3 axes x1y2 with lines dt 2 title '" +
                    solvers[i] + " misclassified'";
        }
        both_terminals("difficulty_" + family, plot + "\n");
    }
    gp.close();
    std::string cmd = "gnuplot '" + dir + "/plots.gp' 2>&1";
    if (std::system(cmd.c_str()) != 0)
        std::fprintf(stderr, "linequad: gnuplot failed on %s/plots.gp\n", dir.c_str());
}

} // namespace linequad::audit
