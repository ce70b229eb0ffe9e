// linequad cells: a model of cells (linequad/cells.hpp) read from its JSON file; particles'
// exact tracks through it, or the tracking audit of the tracker transport codes write.
#include "cli/cli.hpp"
#include "cli/openmc_geometry.hpp"
#include "linequad/audit.hpp"
#include "linequad/case_io.hpp"
#include "linequad/exact.hpp"
#include "linequad/tracking_audit.hpp"

#include "io/escape.hpp"
#include "io/jsonl.hpp"
#include "report/report_html.hpp"
#include "run/stop.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <sstream>
#include <stdexcept>

namespace linequad::cli {

namespace {

struct CellsArgs {
    std::string model, queries = "-", rays = "1000", seed = "1", max_steps = "1000",
                       max_model_bytes = "268435456", markdown, box, out, points = "20000", solvers,
                       timeout = "10";
    std::vector<std::string> plugins;
    bool audit = false;
};

// --box x0,y0,z0,x1,y1,z1: where the audit draws its sources.
std::array<Vec3, 2> parse_box(const std::string& text) {
    std::vector<std::string> parts = split_list(text);
    double c[6];
    bool ok = parts.size() == 6;
    for (std::size_t i = 0; ok && i < 6; ++i) {
        char* end = nullptr;
        c[i] = std::strtod(parts[i].c_str(), &end);
        ok = !parts[i].empty() && *end == 0 && std::isfinite(c[i]);
    }
    if (!ok || !(c[0] < c[3] && c[1] < c[4] && c[2] < c[5]))
        throw std::runtime_error("--box " + text +
                                 ": expected x0,y0,z0,x1,y1,z1, finite, each corner below the "
                                 "other");
    return {Vec3{c[0], c[1], c[2]}, Vec3{c[3], c[4], c[5]}};
}

struct Loaded {
    Model model;
    std::optional<std::array<Vec3, 2>> box;
};
Loaded load(const CellsArgs& a) {
    // A model of 10^5 surfaces is some 10 MB.
    std::string text =
        jsonl::read_file(a.model, std::size_t(to_whole(a.max_model_bytes)), "--max-model-bytes");
    ModelFile file;
    std::string why;
    std::size_t first = text.find_first_not_of(" \t\r\n");
    bool xml = first != std::string::npos && text[first] == '<'; // OpenMC's geometry.xml
    if (!(xml ? parse_openmc_geometry(text, &file, &why) : parse_model(text, &file, &why)))
        throw std::runtime_error(a.model + ": " + why);
    if (!a.box.empty()) file.box = parse_box(a.box);
    std::optional<Model> m = Model::build(std::move(file.surfaces), file.cells, why);
    if (!m) throw std::runtime_error(a.model + ": " + why);
    return {std::move(*m), file.box};
}

std::string ids(const Model& m, const std::vector<int>& cells, bool surfaces = false) {
    std::string out = "[";
    for (std::size_t i = 0; i < cells.size(); ++i) {
        std::int64_t id =
            surfaces ? m.surfaces()[std::size_t(cells[i])].id : m.cells()[std::size_t(cells[i])].id;
        out += (i ? "," : "") + std::to_string(id);
    }
    return out + "]";
}

// One query: {"id", "p", "u"} for the exact track from p, or with "cell" (an id) the next
// crossing out of that cell.
std::string answer(const Model& m, const std::string& line, int max_steps, bool* malformed,
                   long number) {
    jsonl::Json obj;
    std::string why, id = "null";
    auto refuse = [&](const std::string& what) {
        *malformed = true;
        return format_failure(id, "cells", "malformed",
                              "line " + std::to_string(number) + ": " + what);
    };
    if (!jsonl::parse(line, &obj, &why)) return refuse("not valid JSON: " + why);
    jsonl::ReleaseOnUnwind release(obj);
    if (!obj.is_object()) return refuse("not a JSON object");
    if (obj.contains("id")) id = jsonl::member_text(line, "id");
    // p and u as a sense query reads them (the same numbers, the same field errors).
    SenseQuery q;
    std::string as_query = "{\"shape\":\"plane\",\"n\":[1,0,0],\"d\":0";
    for (const char* field : {"p", "u"})
        if (obj.contains(field))
            as_query += std::string(",\"") + field + "\":" + jsonl::dump(obj[field]);
    if (!obj.contains("u")) return refuse("field \"u\": missing");
    if (!parse_sense_query(as_query + "}", &q, &why)) return refuse(why);
    for (const auto& item : obj.items())
        if (item.key() != "id" && item.key() != "p" && item.key() != "u" && item.key() != "cell")
            return refuse("field \"" + item.key() + "\": not a field of a cells query");
    std::string out = "{\"id\":" + id;
    if (obj.contains("cell")) {
        const jsonl::Json& c = obj["cell"];
        int cell = c.is_number_integer() ? m.cell_index(c.get<std::int64_t>()) : -1;
        if (cell < 0) return refuse("field \"cell\": no cell of the model has this id");
        Model::Crossing x = m.next_crossing(cell, q.p, *q.u);
        if (x.exit == Model::Exit::error)
            return format_failure(id, "cells", code_name(x.error.code), message(x.error));
        out += ",\"exit\":\"" + std::string(exit_name(x.exit)) + "\"";
        if (x.exit == Model::Exit::leaves)
            out += ",\"t\":\"" + hex(x.t) + "\",\"surfaces\":" + ids(m, x.surfaces, true) +
                   ",\"entered\":" + ids(m, x.entered) +
                   ",\"undecided\":" + ids(m, x.undecided_entered);
        return out + "}";
    }
    Model::Track t = m.track(q.p, *q.u, max_steps);
    if (!t.error.ok())
        return format_failure(id, "cells", code_name(t.error.code), message(t.error));
    out += ",\"start\":" + ids(m, t.start) + ",\"start_undecided\":" + ids(m, t.start_undecided) +
           ",\"steps\":[";
    for (std::size_t k = 0; k < t.steps.size(); ++k) {
        const Model::Step& s = t.steps[k];
        out += std::string(k ? "," : "") + "{\"t\":\"" + hex(s.t) +
               "\",\"surfaces\":" + ids(m, s.surfaces, true) + ",\"cells\":" + ids(m, s.cells) +
               ",\"undecided\":" + ids(m, s.undecided) + "}";
    }
    return out + "],\"truncated\":" + (t.truncated ? "true" : "false") + "}";
}

int run_queries(const CellsArgs& a) {
    Loaded l = load(a);
    int max_steps = int(to_whole(a.max_steps));
    jsonl::LineReader in(a.queries, jsonl::default_max_line_bytes);
    jsonl::Output out;
    std::string why;
    bool malformed = false;
    jsonl::each_line(
        in, jsonl::default_max_line_bytes, &why,
        [&](const std::string& line, auto&& parse) {
            std::string answered;
            if (parse([&] {
                    answered = answer(l.model, line, max_steps, &malformed, in.number());
                    return true;
                })) {
                out.line(answered);
                return;
            }
            malformed = true;
            out.line(format_failure("null", "cells", "malformed",
                                    "line " + std::to_string(in.number()) + ": " + why));
        },
        [&](const std::string& too_long) {
            malformed = true;
            out.line(format_failure("null", "cells", "malformed", too_long));
        });
    out.finish();
    return malformed ? 1 : 0;
}

// The tracking audit's tallies: each tracker's on each family, and their totals.
struct TrackingRun {
    struct Row {
        int tracker; // its index in trackers
        TrackFamily family;
        TrackingTally tally;
    };
    std::vector<std::string> trackers; // linequad's four (tracker_name), then a user's: markdown
    std::vector<Row> rows;
    std::vector<TrackingTally> totals; // a tracker's
    std::uint64_t exact_steps = 0, exact_rays = 0;
    std::string stopped; // where a stop request (SIGINT, SIGTERM) ended it, if one did
};

void tally_ray(TrackingTally& t, const GradedTrack& g, TrackFamily f, std::uint64_t i,
               const TrackRay& ray) {
    ++t.rays;
    t.steps += std::uint64_t(g.steps);
    t.zero_length_steps += std::uint64_t(g.zero_length_steps);
    ++t.outcomes[std::size_t(g.outcome)];
    t.max_t_ulps = std::max(t.max_t_ulps, g.max_t_ulps);
    bool fault = g.outcome != TrackOutcome::right && g.outcome != TrackOutcome::overlap &&
                 g.outcome != TrackOutcome::undecided;
    if (fault && t.worst.empty()) {
        t.worst =
            query_line(std::string(track_family_name(f)) + "/" + std::to_string(i), ray.p, ray.u);
        t.worst_what = std::string(track_outcome_name(g.outcome)) + " at step " +
                       std::to_string(g.failed_step);
    }
}

// Each family's rays, the reference the oracle's exact track (robust/), each tracker graded
// against it: the transport codes' loop with its three kinds of distances, linequad's cells, and
// the loop with each user's distances (`external`).
TrackingRun track_families(const Model& m, Vec3 lo, Vec3 hi, std::uint64_t rays, std::uint64_t seed,
                           int max_steps,
                           const std::vector<const audit::ExternalSolver*>& external) {
    TrackingRun out;
    for (int k = 0; k < tracker_count; ++k)
        out.trackers.push_back(tracker_name(k));
    for (const audit::ExternalSolver* e : external)
        out.trackers.push_back("textbook, " + escape::markdown_text(e->name) +
                               (e->has_sense() ? " distances and sides" : " distances"));
    const std::size_t count = out.trackers.size();
    out.totals.resize(count);
    for (int f = 0; f < track_family_count; ++f) {
        std::vector<TrackingTally> tally(count);
        for (std::uint64_t i = 0; i < rays && out.stopped.empty(); ++i) {
            if (audit::stop_requested()) {
                out.stopped = "at ray " + std::to_string(i) + " of family " +
                              track_family_name(TrackFamily(f));
                break;
            }
            std::optional<TrackRay> ray = track_ray(m, lo, hi, TrackFamily(f), seed, i);
            if (!ray) continue; // the family does not apply, or no such ray came of this draw
            Model::Track oracle = exact::track(m, ray->p, ray->u, max_steps);
            if (!oracle.error.ok()) continue; // a ray a surface refuses (none in a valid model)
            std::vector<GradedTrack> graded;
            for (int d = 0; d < tracker_distances_count; ++d)
                graded.push_back(grade_track(
                    oracle, textbook_track(m, ray->p, ray->u, max_steps, TrackerDistances(d))));
            graded.push_back(grade_linequad_track(oracle, m.track(ray->p, ray->u, max_steps)));
            for (const audit::ExternalSolver* e : external)
                graded.push_back(
                    grade_track(oracle, textbook_track(m, ray->p, ray->u, max_steps, *e)));
            // A stop while a plugin answered: its answers for this ray are not all there.
            if (!external.empty() && audit::stop_requested()) continue;
            out.exact_steps += oracle.steps.size(), ++out.exact_rays;
            for (std::size_t d = 0; d < count; ++d)
                tally_ray(tally[d], graded[d], TrackFamily(f), i, *ray);
        }
        for (std::size_t d = 0; d < count; ++d) {
            const TrackingTally& t = tally[d];
            TrackingTally& total = out.totals[d];
            total.rays += t.rays, total.steps += t.steps;
            total.zero_length_steps += t.zero_length_steps;
            for (int o = 0; o < track_outcome_count; ++o)
                total.outcomes[std::size_t(o)] += t.outcomes[std::size_t(o)];
            total.max_t_ulps = std::max(total.max_t_ulps, t.max_t_ulps);
            if (total.worst.empty()) total.worst = t.worst, total.worst_what = t.worst_what;
            out.rows.push_back({int(d), TrackFamily(f), t});
        }
    }
    return out;
}

std::uint64_t count(const TrackingTally& t, TrackOutcome o) {
    return t.outcomes[std::size_t(o)];
}
// Rays the tracker took wrong (overlap and undecided rays are the model's, not graded).
std::uint64_t failed(const TrackingTally& t) {
    return t.rays - count(t, TrackOutcome::right) - count(t, TrackOutcome::overlap) -
           count(t, TrackOutcome::undecided);
}

// The command that shows a query's exact answer, as a code span (report.html gives it a copy
// button): the query's line on the standard input of `linequad cells MODEL`.
std::string replay(const std::string& model, const std::string& query) {
    return escape::markdown_code("echo " + escape::shell_word(query) + " | linequad cells " +
                                 escape::shell_word(model));
}

std::string cells_list(const Model& m, const std::vector<int>& cells) {
    std::string out;
    for (std::size_t i = 0; i < cells.size(); ++i) {
        const Model::Cell& c = m.cells()[std::size_t(cells[i])];
        out += std::string(i == 0                  ? ""
                           : i + 1 == cells.size() ? " and "
                                                   : ", ") +
               "cell " + std::to_string(c.id) + (c.name.empty() ? "" : " (" + c.name + ")");
    }
    return out;
}

// The report, verdict first: how each tracker did, the points in two cells or none, then each
// failing tracker and family's first failing ray with its replay, the table by family.
std::string tracking_markdown(const CellsArgs& a, const Model& m, const TrackingRun& run,
                              const PointSample& points) {
    using audit::grouped;
    using escape::markdown_text;
    const TrackingTally& textbook = run.totals[0];
    std::ostringstream md;
    md << "# Tracking audit: " << markdown_text(a.model) << "\n\n## Verdict\n\n";
    if (!run.stopped.empty())
        md << "**Stopped** (SIGINT or SIGTERM) " << markdown_text(run.stopped)
           << ": what follows is what was tracked before.\n\n";
    const TrackingTally& own = run.totals[tracker_distances_count];
    md << "**The textbook tracker went wrong on " << grouped(failed(textbook)) << " of "
       << grouped(textbook.rays) << " rays** (lost " << grouped(count(textbook, TrackOutcome::lost))
       << ", wrong cell " << grouped(count(textbook, TrackOutcome::wrong_cell))
       << ", missed crossing " << grouped(count(textbook, TrackOutcome::missed))
       << ", extra crossing " << grouped(count(textbook, TrackOutcome::extra)) << ", stuck "
       << grouped(count(textbook, TrackOutcome::stuck))
       << "); with linequad's stable distances in the same loop on "
       << grouped(failed(run.totals[1])) << ", with its correct distances on "
       << grouped(failed(run.totals[2])) << ". **linequad's cells went wrong on "
       << grouped(failed(own)) << "**: its tracks are the oracle's bit for bit on "
       << grouped(count(own, TrackOutcome::right) + count(own, TrackOutcome::overlap) +
                  count(own, TrackOutcome::undecided))
       << " of " << grouped(own.rays) << ". The reference is the oracle's exact track (robust/, "
       << grouped(run.exact_steps) << " cell changes on " << grouped(run.exact_rays)
       << " rays): each crossing ordered by its exact root, its distance correctly rounded.\n\n";
    if (points.points == 0) {
        md << "**Overlaps and gaps:** not sampled (`--points 0`, or the run was stopped).\n\n";
    } else {
        std::uint64_t overlapping = 0;
        for (const auto& [cells, n] : points.overlaps)
            overlapping += n;
        md << "**Overlaps and gaps:** of " << grouped(points.points) << " points drawn in the box, "
           << grouped(overlapping) << " lie in two cells or more";
        for (std::size_t k = 0; k < points.overlaps.size() && k < 3; ++k)
            md << (k ? "; " : " (") << markdown_text(cells_list(m, points.overlaps[k].first))
               << ": " << points.overlaps[k].second;
        md << (points.overlaps.empty() ? "" : ")") << ", " << grouped(points.in_none)
           << " in no cell (a gap, or the box reaching beyond the model)";
        if (points.undecided) md << ", " << points.undecided << " on a surface, undecided";
        md << ".\n\n";
        if (!points.first_overlap.empty())
            md << "The first point in two cells (its cells): "
               << replay(a.model, points.first_overlap) << "\n\n";
        if (!points.first_gap.empty())
            md << "The first point in none: " << replay(a.model, points.first_gap) << "\n\n";
    }
    // Each tracker's share of rays gone wrong, family by family: where each one breaks (report.html
    // colours a verdict's "Misclassified" table as a heat map, as the audit's).
    md << "### Misclassified rays, by tracker and family (% of the rays graded)\n\n| tracker |";
    for (int f = 0; f < track_family_count; ++f)
        md << " " << markdown_text(track_family_name(TrackFamily(f))) << " |";
    md << "\n|---|";
    for (int f = 0; f < track_family_count; ++f)
        md << "---:|";
    md << "\n";
    for (int k = 0; k < int(run.trackers.size()); ++k) {
        md << "| " << run.trackers[std::size_t(k)] << " |";
        for (const TrackingRun::Row& row : run.rows) {
            if (row.tracker != k) continue;
            std::uint64_t graded = row.tally.rays - count(row.tally, TrackOutcome::overlap) -
                                   count(row.tally, TrackOutcome::undecided);
            md << " "
               << (!row.tally.rays ? "-"
                   : graded        ? audit::percent_of(failed(row.tally), graded)
                                   : "not graded")
               << " |";
        }
        md << "\n";
    }
    md << "\nOf the rays each tracker is graded on, up to " << grouped(to_whole(a.rays))
       << " a family: lost, wrong cell, missed, extra, stuck or inexact, each counted in the "
          "table by family below. \"-\": the family does not apply to this model; \"not "
          "graded\": every exact track runs along a surface or through an overlap, which the "
          "transport codes' loop is not graded on (linequad's cells are: their tracks must be "
          "the oracle's there too).\n\n";
    md << "## Failing rays\n\n";
    bool any = false;
    for (const TrackingRun::Row& row : run.rows) {
        if (row.tally.worst.empty()) continue;
        any = true;
        md << "**" << run.trackers[std::size_t(row.tracker)] << ", "
           << track_family_name(row.family) << "**: " << grouped(failed(row.tally)) << " of "
           << grouped(row.tally.rays) << " rays; the first, " << row.tally.worst_what
           << " (its exact track): " << replay(a.model, row.tally.worst) << "\n\n";
    }
    if (!any) md << "None: every tracker entered every cell the exact tracks enter.\n\n";
    md << "## By family\n\n";
    md << "| tracker | family | rays | right | lost | wrong cell | missed | extra | stuck | "
          "inexact | overlap | undecided | steps | steps < 1e-12 | max t error (ulps) |\n";
    md << "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
    for (const TrackingRun::Row& row : run.rows) {
        const TrackingTally& t = row.tally;
        md << "| " << run.trackers[std::size_t(row.tracker)] << " | "
           << markdown_text(track_family_name(row.family)) << " | " << t.rays;
        for (TrackOutcome o :
             {TrackOutcome::right, TrackOutcome::lost, TrackOutcome::wrong_cell,
              TrackOutcome::missed, TrackOutcome::extra, TrackOutcome::stuck, TrackOutcome::inexact,
              TrackOutcome::overlap, TrackOutcome::undecided})
            md << " | " << count(t, o);
        char ulps[32];
        std::snprintf(ulps, sizeof ulps, "%.3g", t.max_t_ulps);
        md << " | " << t.steps << " | " << t.zero_length_steps << " | " << ulps << " |\n";
    }
    md << "\nRight: every step into the cell the exact track enters; overlap and undecided rays "
          "(the exact track in two cells, or moving along a surface) are not graded, but for "
          "linequad's cells, right only where its track is the oracle's bit for bit. The t error "
          "is the tracker's summed distance against the exact crossing's, over right steps. A "
          "family with no rays does not apply to the model (no axis-aligned planes, no curved "
          "surface).\n";
    // The command that measures it again: every option that changes what is measured.
    std::string command = "linequad cells " + escape::shell_word(a.model) + " --audit --rays " +
                          a.rays + " --points " + a.points + " --seed " + a.seed;
    if (!a.box.empty()) command += " --box " + escape::shell_word(a.box);
    if (a.max_steps != "1000") command += " --max-steps " + escape::shell_word(a.max_steps);
    for (const std::string& plugin : a.plugins)
        command += " --plugin " + escape::shell_word(plugin);
    if (!a.solvers.empty()) command += " --solvers " + escape::shell_word(a.solvers);
    md << "\nCommand: " << escape::markdown_code(command) << "\n";
    return md.str();
}

// The tracking audit: each family's rays through the model, the tracker transport codes write
// (with its own distances, then linequad's stable and correct ones) graded against the exact
// track; and points sampled in the box for overlaps and gaps.
int run_audit(const CellsArgs& a) {
    Loaded l = load(a);
    if (!l.box)
        throw std::runtime_error(a.model + ": the tracking audit needs the model's \"box\"");
    Vec3 lo = (*l.box)[0], hi = (*l.box)[1];
    std::uint64_t seed = to_whole(a.seed);
    // A user's distances: the solvers named, a plugin's (in its worker) or a peer's.
    std::vector<audit::ExternalSolver> ext;
    std::vector<const audit::ExternalSolver*> users;
    if (!a.solvers.empty()) {
        std::vector<std::string> names = split_list(a.solvers);
        ext = external_solvers(a.plugins, a.timeout, names);
        for (const std::string& name : names) {
            const audit::ExternalSolver* e = find_external(ext, name);
            if (!e) {
                std::string why = solver_error(name, false, ext);
                throw std::runtime_error(
                    "--solvers: " + (why.empty() ? "'" + name +
                                                       "' is linequad's own: the loop with its "
                                                       "stable and correct distances is graded "
                                                       "already"
                                                 : why));
            }
            if (std::string why = external_distances_problem(l.model, *e); !why.empty())
                throw std::runtime_error("--solvers: " + why);
            users.push_back(e);
        }
    }
    TrackingRun run;
    PointSample points;
    {
        audit::StopOnSignal stop; // a stop ends the tracking early, its report written
        run = track_families(l.model, lo, hi, to_whole(a.rays), seed, int(to_whole(a.max_steps)),
                             users);
        if (run.stopped.empty()) points = sample_points(l.model, lo, hi, seed, to_whole(a.points));
    }
    report_plugin_output(ext);
    std::string md = tracking_markdown(a, l.model, run, points);
    if (!a.out.empty()) {
        std::filesystem::create_directories(a.out);
        jsonl::write_file(a.out + "/report.md", md);
        audit::write_report_html(a.out);
        std::fprintf(stderr, "cells: %s/report.md and report.html\n", a.out.c_str());
    }
    if (!a.markdown.empty()) jsonl::write_file(a.markdown, md);
    if (a.out.empty() && a.markdown.empty()) {
        jsonl::Output out;
        out.text(md);
        out.finish();
    }
    if (!run.stopped.empty()) {
        std::fprintf(stderr,
                     "linequad cells: stopped (SIGINT or SIGTERM) %s; the report holds what was "
                     "tracked\n",
                     run.stopped.c_str());
        return 130;
    }
    return 0;
}

} // namespace

Command cells_command(CLI::App& app) {
    auto a = std::make_shared<CellsArgs>();
    CLI::App* s = app.add_subcommand(
        "cells",
        "Particles through a model of cells over planes, quadrics, spheres and cylinders (a JSON "
        "file: "
        "{\"surfaces\": [...], \"cells\": [{\"id\", \"region\"}], \"box\"}, or OpenMC's "
        "geometry.xml): each query line "
        "{\"id\", \"p\", \"u\"} gets the exact track (the cells at p, then each point where "
        "they change), {\"id\", \"p\", \"u\", \"cell\"} the next crossing out of that cell. "
        "With --audit, the tracker transport codes write, graded against the exact tracks.");
    s->add_option("model", a->model, "the model (JSON)")->required()->type_name("MODEL");
    s->add_option("queries", a->queries, "the queries (- or nothing: standard input)")
        ->type_name("FILE");
    s->add_flag("--audit", a->audit,
                "grade the textbook tracker on each ray family instead of answering queries");
    s->add_option("--rays", a->rays, "rays per family (--audit)")
        ->check(WholeNumber(1, 100000000))
        ->type_name("N");
    s->add_option("--seed", a->seed, "the rays' seed (--audit)")
        ->check(WholeNumber(0, UINT64_MAX))
        ->type_name("S");
    s->add_option("--max-steps", a->max_steps, "steps a track may take")
        ->check(WholeNumber(1, 1000000))
        ->type_name("N");
    s->add_option("--max-model-bytes", a->max_model_bytes, "the largest model file read")
        ->check(WholeNumber(1024, std::uint64_t(1) << 34))
        ->type_name("N");
    s->add_option("--box", a->box,
                  "where the audit draws its sources, x0,y0,z0,x1,y1,z1 (a geometry.xml has "
                  "none; a JSON model's own \"box\" is replaced)")
        ->type_name("BOX");
    s->add_option("--points", a->points,
                  "points drawn in the box and located, for overlaps and gaps (--audit)")
        ->check(WholeNumber(0, 100000000))
        ->type_name("N");
    s->add_option("--solvers", a->solvers,
                  "(--audit) the transport loop again with each of these solvers' distances to the "
                  "model's surfaces, and its sides of them where it has a sense entry: a "
                  "plugin's (--plugin) or a peer library's")
        ->type_name("NAME,...");
    add_plugin_options(s, a->plugins, a->timeout);
    s->add_option("--markdown", a->markdown, "write the audit's report here (default: stdout)")
        ->type_name("FILE");
    s->add_option("--out", a->out, "write the audit's report.md and report.html into DIR")
        ->type_name("DIR");
    return {s,
            [a](const std::string&) {
                try {
                    return a->audit ? run_audit(*a) : run_queries(*a);
                } catch (const std::bad_alloc&) {
                    std::fprintf(stderr, "linequad cells: out of memory reading %s\n",
                                 a->model.c_str());
                    return 2;
                } catch (const std::exception& e) {
                    std::fprintf(stderr, "linequad cells: %s\n", e.what());
                    return 2;
                }
            },
            {}};
}

} // namespace linequad::cli
