// linequad cells: a model of cells (linequad/cells.hpp) read from its JSON file; particles'
// exact tracks through it, or the tracking audit of the tracker transport codes write.
#include "cli/cli.hpp"
#include "cli/openmc_geometry.hpp"
#include "linequad/case_io.hpp"
#include "linequad/tracking_audit.hpp"

#include "io/jsonl.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <sstream>
#include <stdexcept>

namespace linequad::cli {

namespace {

struct CellsArgs {
    std::string model, queries = "-", rays = "1000", seed = "1", max_steps = "1000",
                       max_model_bytes = "268435456", markdown, box;
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

// The tracking audit: each family's rays through the model, the tracker transport codes write
// (with its own distances, then linequad's stable and correct ones) graded against the exact
// track. The summary, verdict first, in markdown.
int run_audit(const CellsArgs& a) {
    Loaded l = load(a);
    if (!l.box)
        throw std::runtime_error(a.model + ": the tracking audit needs the model's \"box\"");
    std::uint64_t rays = to_whole(a.rays), seed = to_whole(a.seed);
    int max_steps = int(to_whole(a.max_steps));
    Vec3 lo = (*l.box)[0], hi = (*l.box)[1];
    struct Row {
        TrackerDistances tracker;
        TrackFamily family;
        TrackingTally tally;
    };
    std::vector<Row> rows;
    std::array<TrackingTally, tracker_distances_count> totals{};
    std::uint64_t exact_steps = 0, exact_rays = 0;
    for (int f = 0; f < track_family_count; ++f) {
        std::array<TrackingTally, tracker_distances_count> tally{};
        for (std::uint64_t i = 0; i < rays; ++i) {
            std::optional<TrackRay> ray = track_ray(l.model, lo, hi, TrackFamily(f), seed, i);
            if (!ray) break;
            Model::Track exact = l.model.track(ray->p, ray->u, max_steps);
            if (!exact.error.ok()) continue; // a ray a surface refuses (none in a valid model)
            exact_steps += exact.steps.size(), ++exact_rays;
            for (int d = 0; d < tracker_distances_count; ++d) {
                TrackerRun run =
                    textbook_track(l.model, ray->p, ray->u, max_steps, TrackerDistances(d));
                GradedTrack g = grade_track(exact, run);
                TrackingTally& t = tally[std::size_t(d)];
                ++t.rays;
                t.steps += std::uint64_t(g.steps);
                t.zero_length_steps += std::uint64_t(g.zero_length_steps);
                ++t.outcomes[std::size_t(g.outcome)];
                t.max_t_ulps = std::max(t.max_t_ulps, g.max_t_ulps);
                bool fault = g.outcome != TrackOutcome::right &&
                             g.outcome != TrackOutcome::overlap &&
                             g.outcome != TrackOutcome::undecided;
                if (fault && t.worst.empty())
                    t.worst = "{\"id\":\"" + std::string(track_family_name(TrackFamily(f))) + "/" +
                              std::to_string(i) + "\",\"p\":[\"" + hex(ray->p.x) + "\",\"" +
                              hex(ray->p.y) + "\",\"" + hex(ray->p.z) + "\"],\"u\":[\"" +
                              hex(ray->u.x) + "\",\"" + hex(ray->u.y) + "\",\"" + hex(ray->u.z) +
                              "\"]}  (" + track_outcome_name(g.outcome) + " at step " +
                              std::to_string(g.failed_step) + ")";
            }
        }
        for (int d = 0; d < tracker_distances_count; ++d) {
            const TrackingTally& t = tally[std::size_t(d)];
            TrackingTally& total = totals[std::size_t(d)];
            total.rays += t.rays, total.steps += t.steps;
            total.zero_length_steps += t.zero_length_steps;
            for (int o = 0; o < track_outcome_count; ++o)
                total.outcomes[std::size_t(o)] += t.outcomes[std::size_t(o)];
            total.max_t_ulps = std::max(total.max_t_ulps, t.max_t_ulps);
            if (total.worst.empty()) total.worst = t.worst;
            rows.push_back({TrackerDistances(d), TrackFamily(f), t});
        }
    }
    auto count = [](const TrackingTally& t, TrackOutcome o) { return t.outcomes[std::size_t(o)]; };
    auto failed = [&](const TrackingTally& t) {
        return t.rays - count(t, TrackOutcome::right) - count(t, TrackOutcome::overlap) -
               count(t, TrackOutcome::undecided);
    };
    const TrackingTally& textbook = totals[0];
    std::ostringstream md;
    md << "# Tracking audit: " << a.model << "\n\n";
    md << "**The textbook tracker went wrong on " << failed(textbook) << " of " << textbook.rays
       << " rays** (lost " << count(textbook, TrackOutcome::lost) << ", wrong cell "
       << count(textbook, TrackOutcome::wrong_cell) << ", missed crossing "
       << count(textbook, TrackOutcome::missed) << ", extra crossing "
       << count(textbook, TrackOutcome::extra) << ", stuck " << count(textbook, TrackOutcome::stuck)
       << "); with linequad's stable distances on " << failed(totals[1])
       << ", with its correct distances on " << failed(totals[2])
       << ". The reference is the model's exact track (" << exact_steps << " cell changes on "
       << exact_rays << " rays), which linequad's cells follow exactly: each crossing's order "
       << "exact, its distance correctly rounded.\n\n";
    for (int d = 0; d < tracker_distances_count; ++d)
        if (!totals[std::size_t(d)].worst.empty())
            md << "First failing ray of the tracker with "
               << tracker_distances_name(TrackerDistances(d))
               << " distances (replay its exact track: `linequad cells " << a.model
               << "` with this line on standard input):\n\n    " << totals[std::size_t(d)].worst
               << "\n\n";
    md << "| distances | family | rays | right | lost | wrong cell | missed | extra | stuck | "
          "overlap | undecided | steps | steps < 1e-12 | max t error (ulps) |\n";
    md << "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
    for (const Row& row : rows) {
        const TrackingTally& t = row.tally;
        md << "| " << tracker_distances_name(row.tracker) << " | " << track_family_name(row.family)
           << " | " << t.rays;
        for (TrackOutcome o : {TrackOutcome::right, TrackOutcome::lost, TrackOutcome::wrong_cell,
                               TrackOutcome::missed, TrackOutcome::extra, TrackOutcome::stuck,
                               TrackOutcome::overlap, TrackOutcome::undecided})
            md << " | " << count(t, o);
        char ulps[32];
        std::snprintf(ulps, sizeof ulps, "%.3g", t.max_t_ulps);
        md << " | " << t.steps << " | " << t.zero_length_steps << " | " << ulps << " |\n";
    }
    md << "\nRight: every step into the cell the exact track enters; overlap and undecided rays "
          "(the exact track in two cells, or moving along a surface) are not graded. The t error "
          "is the tracker's summed distance against the exact crossing's, over right steps.\n";
    md << "\nCommand: `linequad cells " << a.model << " --audit --rays " << a.rays << " --seed "
       << a.seed << "`\n";
    if (a.markdown.empty()) {
        jsonl::Output out;
        out.text(md.str());
        out.finish();
    } else {
        jsonl::write_file(a.markdown, md.str());
    }
    return 0;
}

} // namespace

Command cells_command(CLI::App& app) {
    auto a = std::make_shared<CellsArgs>();
    CLI::App* s = app.add_subcommand(
        "cells",
        "Particles through a model of cells over planes and quadrics (a JSON file: "
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
    s->add_option("--markdown", a->markdown, "write the audit's summary here (default: stdout)")
        ->type_name("FILE");
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
