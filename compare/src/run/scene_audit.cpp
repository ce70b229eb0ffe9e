// The scene audit (linequad/scene_audit.hpp): grading, the scene files, the report.
#include "linequad/scene_audit.hpp"

#include "linequad/audit.hpp"
#include "linequad/exact.hpp"

#include "io/escape.hpp"
#include "io/jsonl.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <optional>
#include <stdexcept>
#include <unordered_set>

namespace linequad::audit {

namespace {

bool same_bits(double a, double b) {
    return std::memcmp(&a, &b, sizeof a) == 0;
}

bool same_hit(const SceneHit& a, const SceneHit& b) {
    return a.shape == b.shape && a.tied == b.tied && a.hit.kind == b.hit.kind &&
           a.hit.part == b.hit.part && same_bits(a.hit.t, b.hit.t) &&
           same_bits(a.hit.p.x, b.hit.p.x) && same_bits(a.hit.p.y, b.hit.p.y) &&
           same_bits(a.hit.p.z, b.hit.p.z);
}

bool same_answer(const SceneAnswer& a, const SceneAnswer& b) {
    if (a.error.code != b.error.code || a.error_shape != b.error_shape) return false;
    if (a.hits.size() != b.hits.size()) return false;
    for (std::size_t k = 0; k < a.hits.size(); ++k)
        if (!same_hit(a.hits[k], b.hits[k])) return false;
    return true;
}

bool any_tie(const SceneAnswer& a) {
    return std::any_of(a.hits.begin(), a.hits.end(), [](const SceneHit& h) { return h.tied; });
}

// The shapes in the order the hits come, each run of tied hits at one t sorted (the order
// inside an exact tie is shape order by definition; a stable scene's ties are its doubles').
std::vector<std::uint32_t> shape_order(const SceneAnswer& a) {
    std::vector<std::uint32_t> out;
    for (std::size_t i = 0; i < a.hits.size();) {
        std::size_t j = i + 1;
        while (j < a.hits.size() && a.hits[j].tied && a.hits[i].tied &&
               a.hits[j].hit.t == a.hits[i].hit.t)
            ++j;
        std::size_t from = out.size();
        for (std::size_t k = i; k < j; ++k)
            out.push_back(a.hits[k].shape);
        std::sort(out.begin() + std::ptrdiff_t(from), out.end());
        i = j;
    }
    return out;
}

// How far a hit at t lies from the exact hit along the line, |t - t_exact| |v|, in ulps of the
// larger of |L0| and the exact point (max norms): the error in units of the point's own
// rounding. (Ulps of t itself say nothing near t = 0, where a spawned ray's hits are.)
std::uint64_t position_ulps(const Line& l, double t, const SceneHit& exact) {
    if (t == exact.hit.t) return 0;
    double err = std::fabs(t - exact.hit.t) * max_abs(l.v);
    double scale = std::max(max_abs(l.L0), max_abs(exact.hit.p));
    double ulp = std::nextafter(scale, INFINITY) - scale;
    if (!std::isfinite(err) || !(ulp > 0)) return std::numeric_limits<std::uint64_t>::max();
    double u = std::ceil(err / ulp);
    return u >= 1.8e19 ? std::numeric_limits<std::uint64_t>::max() : std::uint64_t(u);
}

void grade_line(const std::vector<Shape>& shapes, const Scene& stable, const Scene& correct,
                const Scene* embree, const Line& l, SceneTally& t) {
    SceneAnswer want_all, want_nearest, got;
    exact::intersect(shapes, l, {Need::all, true}, want_all);
    exact::intersect(shapes, l, {Need::nearest, true}, want_nearest);
    ++t.lines;
    t.hits += want_all.hits.size();
    t.tie_lines += any_tie(want_all);

    correct.intersect(l, {Need::all, true}, got);
    if (want_all.ok() && got.error.code == ErrorCode::out_of_range)
        ++t.correct_refused;
    else if (!same_answer(got, want_all))
        ++t.correct_differs_all;
    t.refined_all += got.exact_comparisons > 0;
    t.comparisons_all += got.exact_comparisons;
    correct.intersect(l, {Need::nearest, true}, got);
    if (!(want_all.ok() && got.error.code == ErrorCode::out_of_range) &&
        !same_answer(got, want_nearest))
        ++t.correct_differs_nearest;
    t.refined_nearest += got.exact_comparisons > 0;
    t.solved += got.shapes_solved;
    if (embree) { // the same correct scene through Embree's BVH: the same answers
        bool differs = false;
        for (Need need : {Need::all, Need::nearest}) {
            SceneAnswer e;
            embree->intersect(l, {need, true}, e);
            if (!(want_all.ok() && e.error.code == ErrorCode::out_of_range))
                differs = differs || !same_answer(e, need == Need::all ? want_all : want_nearest);
        }
        t.embree_lines += 1;
        t.embree_differs += differs;
    }

    if (!want_all.ok()) return; // bad input: the correct scene's verdict is graded above
    stable.intersect(l, {Need::all, true}, got);
    if (!got.ok()) return void(++t.stable_refused); // refused for need all: the line is refused
    SceneAnswer all = std::move(got);
    stable.intersect(l, {Need::nearest, true}, got);
    if (!got.ok()) return void(++t.stable_refused);
    if (got.hits.empty() != want_nearest.hits.empty()) {
        ++(got.hits.empty() ? t.stable_missed : t.stable_phantom);
    } else if (!got.hits.empty()) {
        // The exact hit stable's first hit stands for: its shape's nearest in t. Right when that
        // is one of the exactly nearest.
        const SceneHit& first = got.hits[0];
        const SceneHit* meant = nullptr;
        for (const SceneHit& h : want_all.hits)
            if (h.shape == first.shape && (!meant || std::fabs(h.hit.t - first.hit.t) <
                                                         std::fabs(meant->hit.t - first.hit.t)))
                meant = &h;
        bool right =
            meant &&
            std::any_of(want_nearest.hits.begin(), want_nearest.hits.end(), [&](const SceneHit& h) {
                return h.shape == meant->shape && same_bits(h.hit.t, meant->hit.t);
            });
        if (!right)
            ++t.stable_wrong;
        else {
            std::uint64_t u = position_ulps(l, first.hit.t, *meant);
            t.stable_error.add(u);
            t.stable_max_ulps = std::max(t.stable_max_ulps, u);
        }
    }
    if (all.hits.size() != want_all.hits.size())
        ++t.stable_count_differs;
    else if (shape_order(all) != shape_order(want_all))
        ++t.stable_misordered;
}

void grade_scene(const SceneCase& sc, SceneTally& t) {
    std::vector<Shape> shapes = sc.shape_list();
    Scene stable(shapes, SceneSolver::stable, SceneTraversal::hierarchy),
        correct(shapes, SceneSolver::correct, SceneTraversal::hierarchy);
    std::optional<Scene> embree;
    if (scene_traversal_available(SceneTraversal::embree))
        embree.emplace(shapes, SceneSolver::correct, SceneTraversal::embree);
    ++t.scenes;
    t.shapes += shapes.size();
    for (const SceneLine& l : sc.lines)
        grade_line(shapes, stable, correct, embree ? &*embree : nullptr, l.line, t);
}

void append_scene(std::string& out, const SceneCase& sc) {
    out += format_scene(sc.header) + "\n";
    for (const SceneShape& s : sc.shapes)
        out += format_scene_shape(s) + "\n";
    for (const SceneLine& l : sc.lines)
        out += format_scene_line(l) + "\n";
}

std::string percent(std::uint64_t n, std::uint64_t of) {
    if (of == 0) return "–";
    char buf[32];
    double p = 100.0 * double(n) / double(of);
    std::snprintf(buf, sizeof buf, p > 0 && p < 0.01 ? "%.3f%%" : "%.2f%%", p);
    return buf;
}

// A histogram's quantile (its bucket's upper edge, at most the largest seen), as a whole number.
std::string quantile(const Histogram& h, double q, std::uint64_t max) {
    if (h.total() == 0) return "–";
    return grouped(std::uint64_t(std::min(h.quantile(q), double(max))));
}

} // namespace

namespace {

// Scenes from records a line each (next_line: false at the end; `where` names a line).
template <class NextLine, class Where>
std::vector<SceneCase> scenes_from(NextLine&& next_line, Where&& where) {
    std::vector<SceneCase> scenes;
    std::unordered_set<std::string> ids; // the open scene's shape ids
    std::string line, why;
    Record rec;
    while (next_line(&line)) {
        std::string at = where() + ": ";
        if (jsonl::blank(line)) continue;
        if (!parse_record(line, &rec, &why)) throw std::runtime_error(at + why);
        switch (rec.kind) {
        case RecordKind::scene:
            scenes.push_back({rec.scene, {}, {}});
            ids.clear();
            break;
        case RecordKind::scene_shape: {
            if (scenes.empty())
                throw std::runtime_error(at + "field \"shape_id\": no scene is open (a "
                                              "{\"scene\": id} line first)");
            SceneCase& sc = scenes.back();
            if (!sc.lines.empty())
                throw std::runtime_error(at + "shape " + rec.shape.id +
                                         " comes after the scene's lines");
            if (!ids.insert(rec.shape.id).second)
                throw std::runtime_error(at + "field \"shape_id\": " + rec.shape.id +
                                         " is already in the scene");
            sc.shapes.push_back(rec.shape);
            break;
        }
        case RecordKind::scene_line:
            if (scenes.empty())
                throw std::runtime_error(at + "field \"shape\": missing (a line needs a shape, "
                                              "or a scene before it)");
            scenes.back().lines.push_back(rec.line);
            break;
        default:
            throw std::runtime_error(at + "a single case, where scenes are read (linequad audit "
                                          "reads single cases)");
        }
    }
    return scenes;
}

} // namespace

std::vector<SceneCase> read_scenes(const std::string& path, std::size_t max_line_bytes) {
    jsonl::LineReader in(path, max_line_bytes);
    auto next = [&](std::string* line) {
        auto status = in.next(line);
        if (status == jsonl::LineReader::Status::error) throw std::runtime_error(in.error());
        if (status == jsonl::LineReader::Status::too_long)
            throw std::runtime_error(jsonl::too_long_message(in.number(), max_line_bytes));
        return status == jsonl::LineReader::Status::line;
    };
    return scenes_from(next, [&] { return in.name() + ": line " + std::to_string(in.number()); });
}

std::vector<SceneCase> scenes_from_text(std::string_view text) {
    std::size_t at = 0;
    long number = 0;
    auto next = [&](std::string* line) {
        if (at >= text.size()) return false;
        std::size_t end = text.find('\n', at);
        if (end == std::string_view::npos) end = text.size();
        *line = std::string(text.substr(at, end - at));
        at = end + 1, ++number;
        return true;
    };
    return scenes_from(next, [&] { return "line " + std::to_string(number); });
}

std::string format_scenes(const std::vector<SceneCase>& scenes) {
    std::string out;
    for (const SceneCase& sc : scenes)
        append_scene(out, sc);
    return out;
}

std::vector<SceneRow> run_scene_audit(const SceneAuditOptions& o) {
    std::vector<SceneCase> scenes;
    if (!o.cases_file.empty()) {
        scenes = read_scenes(o.cases_file, o.max_line_bytes);
    } else {
        std::vector<SceneFamily> families = o.families;
        if (families.empty())
            for (int f = 0; f < scene_family_count; ++f)
                families.push_back(SceneFamily(f));
        for (SceneFamily f : families)
            for (std::uint64_t i = 0; i < o.scenes; ++i)
                scenes.push_back(make_scene(f, o.seed, i, o.lines));
    }
    // Written before they are graded: a grading that fails leaves the scenes to reproduce it.
    if (!o.write_cases.empty()) {
        std::string text;
        for (const SceneCase& sc : scenes)
            append_scene(text, sc);
        jsonl::write_file(o.write_cases, text);
    }
    std::vector<SceneRow> rows;
    for (const SceneCase& sc : scenes) {
        std::string family = sc.header.family.empty() ? "file" : sc.header.family;
        auto it = std::find_if(rows.begin(), rows.end(),
                               [&](const SceneRow& r) { return r.family == family; });
        if (it == rows.end()) it = rows.insert(rows.end(), {family, {}});
        grade_scene(sc, it->tally);
    }
    return rows;
}

std::string scene_report_markdown(const std::vector<SceneRow>& rows, const SceneAuditOptions& o,
                                  const std::string& command) {
    std::string md = "# Scenes: nearest hits and their order, against the exact oracle\n\n";
    md += escape::markdown_code(command) + "\n\n";
    if (o.cases_file.empty())
        md += std::to_string(o.scenes) + " scenes per family, " + std::to_string(o.lines) +
              " lines each, seed " + std::to_string(o.seed) + ".\n\n";
    else
        md += "Scenes from " + escape::markdown_code(o.cases_file) + ".\n\n";
    md += "The oracle solves every shape of a scene exactly and orders the hits by comparing "
          "their exact roots; ties are hits on two shapes at exactly one t. A correct scene must "
          "give the oracle's answer bit for bit (every hit, its shape, its tie) for need all and "
          "nearest. *Refined*: lines on which the correct scene compared two roots exactly "
          "(hits that rounded to one double). A stable scene is graded as a renderer uses it: "
          "its nearest hit wrong (the exact hit it stands for, its shape's nearest in t, is "
          "not among the exactly nearest: another shape's, or another hit of its shape), "
          "missed or invented; for need all, another number of hits or another order of shapes (an "
          "exact tie's order aside); the error of a right nearest hit's position along the line, "
          "|t - t_exact| |v|, in ulps of its coordinates (of the larger of |L0| and the exact "
          "point).\n\n";
    md += "| family | scenes | lines | shapes per scene | oracle hits | lines with exact ties | "
          "correct ≠ oracle (all / nearest) | correct refined (all / nearest) | shapes solved per "
          "line | stable nearest: wrong / missed / invented | stable all: count / order | "
          "stable error p50 / p99 / max (ulps of the point) |\n";
    md += "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
    char buf[64];
    for (const SceneRow& r : rows) {
        const SceneTally& t = r.tally;
        std::snprintf(buf, sizeof buf, "%.1f", t.scenes ? double(t.shapes) / double(t.scenes) : 0);
        std::string per_scene = buf;
        std::snprintf(buf, sizeof buf, "%.2f", t.lines ? double(t.solved) / double(t.lines) : 0);
        md += "| " + escape::markdown_text(r.family) + " | " + grouped(t.scenes) + " | " +
              grouped(t.lines) + " | " + per_scene + " | " + grouped(t.hits) + " | " +
              percent(t.tie_lines, t.lines) + " | " + grouped(t.correct_differs_all) + " / " +
              grouped(t.correct_differs_nearest) + " | " + percent(t.refined_all, t.lines) + " / " +
              percent(t.refined_nearest, t.lines) + " | " + buf + " | " +
              percent(t.stable_wrong, t.lines) + " / " + percent(t.stable_missed, t.lines) + " / " +
              percent(t.stable_phantom, t.lines) + " | " +
              percent(t.stable_count_differs, t.lines) + " / " +
              percent(t.stable_misordered, t.lines) + " | " +
              quantile(t.stable_error, 0.5, t.stable_max_ulps) + " / " +
              quantile(t.stable_error, 0.99, t.stable_max_ulps) + " / " +
              grouped(t.stable_max_ulps) + " |\n";
    }
    std::uint64_t refused = 0, stable_refused = 0, embree_lines = 0, embree_differs = 0;
    for (const SceneRow& r : rows) {
        refused += r.tally.correct_refused, stable_refused += r.tally.stable_refused;
        embree_lines += r.tally.embree_lines, embree_differs += r.tally.embree_differs;
    }
    md += "\nRefused (out_of_range where the oracle answers): correct " + grouped(refused) +
          " lines, stable " + grouped(stable_refused) + ".\n";
    if (embree_lines)
        md += "\nThe correct scene traversing Embree's BVH instead of its own: " +
              grouped(embree_differs) + " of " + grouped(embree_lines) +
              " lines answered otherwise than the oracle (need all and nearest).\n";
    else
        md += "\nBuilt without Embree: its traversal was not graded.\n";
    return md;
}

} // namespace linequad::audit
