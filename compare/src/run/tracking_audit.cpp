// The tracking audit's tracker as transport codes write it, the grading of its steps against a
// model's exact track, and the ray families.
#include "linequad/tracking_audit.hpp"

#include "linequad/case_io.hpp"
#include "linequad/solvers.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <random>

namespace linequad {

namespace {

constexpr double infinity = std::numeric_limits<double>::infinity();
// OpenMC's constants (include/openmc/constants.h).
constexpr double fp_coincident = 1e-12; // |f| below this: on the surface
constexpr double fp_precision = 1e-14;  // a later surface wins only if nearer by this, relatively
constexpr double tiny_bit = 1e-8;       // the nudge before a particle is declared lost

double dot3(Vec3 a, Vec3 b) {
    return a.x * b.x + a.y * b.y + a.z * b.z;
}

// ---- the surfaces as OpenMC evaluates them (src/surface.cpp) ----

double evaluate(const Plane& s, Vec3 p) {
    return s.n.x * p.x + s.n.y * p.y + s.n.z * p.z - s.d;
}
double evaluate(const Quadric& s, Vec3 r) {
    const auto& q = s.q;
    double x = r.x, y = r.y, z = r.z;
    return x * (q[0] * x + q[3] * y + q[6]) + y * (q[1] * y + q[4] * z + q[7]) +
           z * (q[2] * z + q[5] * x + q[8]) + q[9];
}
Vec3 normal(const Plane& s, Vec3) {
    return s.n;
}
Vec3 normal(const Quadric& s, Vec3 r) {
    const auto& q = s.q;
    return {2 * q[0] * r.x + q[3] * r.y + q[5] * r.z + q[6],
            2 * q[1] * r.y + q[3] * r.x + q[4] * r.z + q[7],
            2 * q[2] * r.z + q[4] * r.y + q[5] * r.x + q[8]};
}

// The sphere (SurfaceSphere) and the x-, y- and z-cylinders (axis_aligned_cylinder_distance), as
// OpenMC writes them for a unit direction, here with its squared length for the 1 it assumes
// (the tracking audit's directions are not unit vectors).
double evaluate(const Sphere& s, Vec3 r) {
    double x = r.x - s.C.x, y = r.y - s.C.y, z = r.z - s.C.z;
    return x * x + y * y + z * z - s.r * s.r;
}
Vec3 normal(const Sphere& s, Vec3 r) {
    return {2 * (r.x - s.C.x), 2 * (r.y - s.C.y), 2 * (r.z - s.C.z)};
}
// The cylinder's axis (0, 1 or 2: x, y or z; a model's cylinders lie along one).
int axis_of(const Cylinder& s) {
    Vec3 d = s.H - s.C;
    return d.x != 0 ? 0 : d.y != 0 ? 1 : 2;
}
double evaluate(const Cylinder& s, Vec3 r) {
    int i = axis_of(s), j = (i + 1) % 3, k = (i + 2) % 3;
    double x = r[j] - s.C[j], y = r[k] - s.C[k];
    return x * x + y * y - s.r * s.r;
}
Vec3 normal(const Cylinder& s, Vec3 r) {
    int i = axis_of(s);
    double n[3] = {2 * (r.x - s.C.x), 2 * (r.y - s.C.y), 2 * (r.z - s.C.z)};
    n[i] = 0;
    return {n[0], n[1], n[2]};
}
// OpenMC's near root of a k^2 - a c: the far one from a point on the surface or inside.
double centred_distance(double a, double k, double c, bool coincident) {
    if (a == 0.0) return infinity;
    double quad = k * k - a * c;
    if (quad < 0.0) return infinity;
    if (coincident || std::fabs(c) < fp_coincident)
        return k >= 0.0 ? infinity : (-k + std::sqrt(quad)) / a;
    if (c < 0.0) return (-k + std::sqrt(quad)) / a;
    double d = (-k - std::sqrt(quad)) / a;
    return d < 0.0 ? infinity : d;
}
double distance(const Sphere& s, Vec3 r, Vec3 u, bool coincident) {
    double x = r.x - s.C.x, y = r.y - s.C.y, z = r.z - s.C.z;
    return centred_distance(dot3(u, u), x * u.x + y * u.y + z * u.z, evaluate(s, r), coincident);
}
double distance(const Cylinder& s, Vec3 r, Vec3 u, bool coincident) {
    int i = axis_of(s), j = (i + 1) % 3, k = (i + 2) % 3;
    double x = r[j] - s.C[j], y = r[k] - s.C[k];
    return centred_distance(u[j] * u[j] + u[k] * u[k], x * u[j] + y * u[k], evaluate(s, r),
                            coincident);
}

double distance(const Plane& s, Vec3 r, Vec3 u, bool coincident) {
    double f = evaluate(s, r), projection = dot3(s.n, u);
    if (coincident || std::fabs(f) < fp_coincident || projection == 0.0) return infinity;
    double d = -f / projection;
    return d < 0.0 ? infinity : d;
}
double distance(const Quadric& s, Vec3 r, Vec3 dir, bool coincident) {
    const auto& q = s.q;
    double x = r.x, y = r.y, z = r.z, u = dir.x, v = dir.y, w = dir.z;
    double a =
        q[0] * u * u + q[1] * v * v + q[2] * w * w + q[3] * u * v + q[4] * v * w + q[5] * u * w;
    double k = q[0] * u * x + q[1] * v * y + q[2] * w * z +
               0.5 * (q[3] * (u * y + v * x) + q[4] * (v * z + w * y) + q[5] * (w * x + u * z) +
                      q[6] * u + q[7] * v + q[8] * w);
    double c = evaluate(s, r);
    double quad = k * k - a * c, d;
    if (quad < 0.0) {
        d = infinity;
    } else if (coincident || std::fabs(c) < fp_coincident) {
        d = k >= 0.0 ? infinity : (-k + std::sqrt(quad)) / a; // on it: the other root
    } else if (a == 0.0) {
        d = -0.5 * c / k;
    } else {
        quad = std::sqrt(quad);
        d = (-k - quad) / a;
        double b = (-k + quad) / a;
        if (d < 0.0) {
            if (b > 0.0) d = b;
        } else if (b > 0.0 && b < d) {
            d = b;
        }
    }
    return d <= 0.0 || std::isnan(d) ? infinity : d;
}

// OpenMC's Surface::sense: the sign of f, the direction's side of the normal where |f| is below
// the coincidence tolerance.
Sense textbook_sense(const SurfaceShape& s, Vec3 p, Vec3 u) {
    return std::visit(
        [&](const auto& x) {
            double f = evaluate(x, p);
            bool positive = std::fabs(f) < fp_coincident ? dot3(normal(x, p), u) > 0 : f > 0;
            return positive ? Sense::positive : Sense::negative;
        },
        s);
}

// The textbook's sides of a point: OpenMC's Surface::sense, surface by surface.
struct TextbookSides {
    const Model& m;
    void at(Vec3 p, Vec3 u, int known, std::vector<Sense>& senses) {
        for (std::size_t s = 0; s < m.surfaces().size(); ++s)
            if (int(s) != known) senses[s] = textbook_sense(m.surfaces()[s].shape, p, u);
    }
};

// A user's sides (its sense entry: a plugin's, in its worker), every surface of the model in one
// call. A failed call leaves that surface's side undecided, which no cell is found by.
struct ExternalSides {
    const Model& m;
    const audit::ExternalSolver& solver;
    std::vector<Case> posed{};
    std::vector<audit::ExternalAnswer> answers{};

    void at(Vec3 p, Vec3 u, int known, std::vector<Sense>& senses) {
        posed.resize(m.surfaces().size());
        for (std::size_t s = 0; s < posed.size(); ++s) {
            posed[s].shape =
                std::visit([](const auto& x) -> Shape { return x; }, m.surfaces()[s].shape);
            posed[s].line = Line{p, u, Range::ray};
        }
        if (!solver.sides(posed, answers)) answers.assign(posed.size(), {});
        for (std::size_t s = 0; s < posed.size(); ++s)
            if (int(s) != known) senses[s] = Sense(answers[s].side);
    }
};

// The first cell (in the model's order, as an exhaustive search finds it) holding p, the
// surface `known` (if any) on its side `known_sense`, the others on the sides `sides` puts p on.
template <class Sides>
int find_cell(const Model& m, Vec3 p, Vec3 u, int known, Sense known_sense, Sides& sides) {
    std::vector<Sense> senses(m.surfaces().size(), Sense::on);
    if (known >= 0) senses[std::size_t(known)] = known_sense;
    sides.at(p, u, known, senses);
    for (std::size_t c = 0; c < m.cells().size(); ++c)
        if (m.cells()[c].region.contains(senses) == std::optional<bool>(true)) return int(c);
    return -1;
}

// linequad's solver's distance: its first hit beyond the particle (t > 0) on the ray, the
// surface it sits on posed coincident (its root at t = 0 exactly).
template <class S>
double solver_distance(S s, Vec3 p, Vec3 u, bool coincident, TrackerDistances d) {
    auto solve = [&](const Line& l) {
        return d == TrackerDistances::stable ? stable::intersect(s, l, {Need::all, false})
                                             : correct::intersect(s, l, {Need::all, false});
    };
    if constexpr (!has_coincident<S>) {
        // A sphere or a cylinder has no `coincident`: of the whole line's crossings, the one
        // nearest 0 is the surface the particle sits on, and the other its distance, if ahead.
        if (coincident) {
            Result r = solve(Line{p, u, Range::line});
            if (r.count != 2 || r.hits[1].kind != HitKind::cross) return infinity;
            double other =
                std::fabs(r.hits[0].t) <= std::fabs(r.hits[1].t) ? r.hits[1].t : r.hits[0].t;
            return other > 0 ? other : infinity;
        }
    } else {
        s.coincident = coincident;
    }
    Result r = solve(Line{p, u, Range::ray});
    for (int k = 0; k < r.count; ++k)
        if (r.hits[k].t > 0 && r.hits[k].kind == HitKind::cross) return r.hits[k].t;
    return infinity;
}

// The model's planes perpendicular to a coordinate axis whose coordinate there is a double
// exactly: (axis, coordinate).
std::vector<std::pair<int, double>> axis_planes(const Model& m) {
    std::vector<std::pair<int, double>> planes;
    for (const Model::Surface& s : m.surfaces())
        if (const Plane* pl = std::get_if<Plane>(&s.shape)) {
            int nonzero = (pl->n.x != 0) + (pl->n.y != 0) + (pl->n.z != 0);
            if (nonzero != 1) continue;
            int axis = pl->n.x != 0 ? 0 : pl->n.y != 0 ? 1 : 2;
            double n = axis == 0 ? pl->n.x : axis == 1 ? pl->n.y : pl->n.z;
            double x = pl->d / n;
            if (std::fma(x, n, -pl->d) == 0) planes.push_back({axis, x});
        }
    return planes;
}

} // namespace

const char* tracker_distances_name(TrackerDistances d) {
    static const char* const names[] = {"textbook", "stable", "correct"};
    return names[int(d)];
}

namespace {

// The transport codes' loop (textbook_track's comment), its surface distances from `distances`:
// begin(tokens, p, u, last) once a step, then distance(surface, on_it) for each surface the
// current cell's region names; the sides of a point for its cell search from `sides`.
template <class Distances, class Sides>
TrackerRun transport_loop(const Model& m, Vec3 p, Vec3 u, int max_steps, Distances& distances,
                          Sides& sides) {
    TrackerRun run;
    int cell = run.start = find_cell(m, p, u, -1, Sense::on, sides);
    if (cell < 0) return run;
    int last = -1;
    double t = 0;
    while (int(run.steps.size()) < max_steps) {
        double d_min = infinity;
        int nearest = -1;
        const std::vector<Region::Token>& tokens = m.cells()[std::size_t(cell)].region.tokens();
        distances.begin(tokens, p, u, last);
        for (const Region::Token& tok : tokens) {
            if (tok.op != Region::Op::half_space) continue;
            double d = distances.distance(tok.surface, tok.surface == last, p, u);
            if (d < d_min && (d_min == infinity || std::fabs(d - d_min) / d_min >= fp_precision))
                d_min = d, nearest = tok.surface;
        }
        if (nearest < 0) {
            run.escaped = true;
            return run;
        }
        p = {p.x + d_min * u.x, p.y + d_min * u.y, p.z + d_min * u.z};
        t += d_min;
        last = nearest;
        Vec3 n = std::visit([&](const auto& x) { return normal(x, p); },
                            m.surfaces()[std::size_t(nearest)].shape);
        Sense side = dot3(n, u) > 0 ? Sense::positive : Sense::negative;
        cell = find_cell(m, p, u, nearest, side, sides);
        if (cell < 0) { // tangent, or a void: a tiny step on, then lost
            p = {p.x + tiny_bit * u.x, p.y + tiny_bit * u.y, p.z + tiny_bit * u.z};
            t += tiny_bit;
            cell = find_cell(m, p, u, nearest, side, sides);
        }
        run.steps.push_back({t, d_min, cell});
        if (cell < 0) return run;
    }
    return run;
}

// The textbook quadratic, or linequad's stable or correct solver, one surface at a time.
struct OwnDistances {
    const Model& m;
    TrackerDistances kind;
    void begin(const std::vector<Region::Token>&, Vec3, Vec3, int) {}
    double distance(int surface, bool on_it, Vec3 p, Vec3 u) const {
        return std::visit(
            [&](const auto& x) {
                return kind == TrackerDistances::textbook ? linequad::distance(x, p, u, on_it)
                                                          : solver_distance(x, p, u, on_it, kind);
            },
            m.surfaces()[std::size_t(surface)].shape);
    }
};

// A solver from outside (a plugin's, in its worker): each step's surfaces posed as one chunk of
// cases (the surface the particle sits on `coincident`, the ray from p), asked at once.
struct ExternalDistances {
    const Model& m;
    const audit::ExternalSolver& solver;
    std::vector<Case> posed;
    std::vector<int> surfaces;
    std::vector<double> found;
    std::vector<audit::ExternalAnswer> answers;

    void begin(const std::vector<Region::Token>& tokens, Vec3 p, Vec3 u, int last) {
        posed.clear(), surfaces.clear(), found.clear();
        for (const Region::Token& tok : tokens) {
            if (tok.op != Region::Op::half_space ||
                std::find(surfaces.begin(), surfaces.end(), tok.surface) != surfaces.end())
                continue;
            Case c;
            c.shape = std::visit(
                [&](auto x) -> Shape {
                    if constexpr (has_coincident<decltype(x)>) x.coincident = tok.surface == last;
                    return x;
                },
                m.surfaces()[std::size_t(tok.surface)].shape);
            c.line = Line{p, u, Range::ray};
            posed.push_back(std::move(c));
            surfaces.push_back(tok.surface);
        }
        if (!solver.answer_all(posed, answers, nullptr)) answers.assign(posed.size(), {});
        for (const audit::ExternalAnswer& a : answers)
            found.push_back(first_ahead(a));
    }
    // Its first hit beyond the particle; none (a refusal, a case it cannot hold): infinity,
    // no surface ahead. Tangent touches are skipped where it reports kinds.
    double first_ahead(const audit::ExternalAnswer& a) const {
        if (!a.result || !a.result->ok()) return infinity;
        double best = infinity;
        for (int k = 0; k < a.result->count; ++k) {
            const Hit& h = a.result->hits[k];
            if (h.t > 0 && (!solver.kinds || h.kind == HitKind::cross)) best = std::min(best, h.t);
        }
        return best;
    }
    double distance(int surface, bool, Vec3, Vec3) const {
        auto at = std::find(surfaces.begin(), surfaces.end(), surface);
        return found[std::size_t(at - surfaces.begin())];
    }
};

} // namespace

TrackerRun textbook_track(const Model& m, Vec3 p, Vec3 u, int max_steps,
                          TrackerDistances distances) {
    OwnDistances own{m, distances};
    TextbookSides sides{m};
    return transport_loop(m, p, u, max_steps, own, sides);
}

TrackerRun textbook_track(const Model& m, Vec3 p, Vec3 u, int max_steps,
                          const audit::ExternalSolver& distances) {
    ExternalDistances external{m, distances, {}, {}, {}, {}};
    if (distances.has_sense()) {
        ExternalSides sides{m, distances};
        return transport_loop(m, p, u, max_steps, external, sides);
    }
    TextbookSides sides{m};
    return transport_loop(m, p, u, max_steps, external, sides);
}

std::string external_distances_problem(const Model& m, const audit::ExternalSolver& s) {
    if (s.parametrisation != audit::Parametrisation::line || s.surface != audit::Surface::as_posed)
        return "solver '" + s.name +
               "' takes its lines as something else than L0, v and t along v, or its surfaces "
               "other than as posed: a tracker's distances are t along u from p";
    for (const Model::Surface& surface : m.surfaces())
        if (!s.takes(std::visit([](const auto& x) -> Shape { return x; }, surface.shape)))
            return "solver '" + s.name + "' does not take the model's " +
                   std::visit([](const auto& x) { return std::string(shape_name(x)); },
                              surface.shape) +
                   "s";
    return "";
}

const char* track_outcome_name(TrackOutcome o) {
    static const char* const names[] = {"right",   "lost",      "wrong_cell", "missed", "extra",
                                        "overlap", "undecided", "stuck",      "inexact"};
    return names[int(o)];
}

const char* tracker_name(int k) {
    static const char* const names[] = {"textbook", "textbook, stable distances",
                                        "textbook, correct distances", "linequad cells"};
    return names[k];
}

GradedTrack grade_linequad_track(const Model::Track& oracle, const Model::Track& fast) {
    GradedTrack g;
    auto fail = [&](TrackOutcome o, int step) {
        g.outcome = o, g.failed_step = step;
        return g;
    };
    if (fast.start != oracle.start || fast.start_undecided != oracle.start_undecided)
        return fail(fast.start.empty() ? TrackOutcome::lost : TrackOutcome::wrong_cell, 0);
    for (std::size_t k = 0; k < oracle.steps.size() || k < fast.steps.size(); ++k) {
        int step = int(k) + 1;
        if (k >= fast.steps.size()) return fail(TrackOutcome::missed, step);
        if (k >= oracle.steps.size()) return fail(TrackOutcome::extra, step);
        const Model::Step &e = oracle.steps[k], &f = fast.steps[k];
        ++g.steps;
        double ulp = std::nextafter(std::fabs(e.t), infinity) - std::fabs(e.t);
        g.max_t_ulps = std::max(g.max_t_ulps, std::fabs(f.t - e.t) / ulp);
        if (f.cells != e.cells || f.undecided != e.undecided)
            return fail(f.cells.empty() ? TrackOutcome::lost : TrackOutcome::wrong_cell, step);
        if (!(f.t == e.t && std::signbit(f.t) == std::signbit(e.t)) || f.surfaces != e.surfaces)
            return fail(TrackOutcome::inexact, step);
    }
    if (fast.truncated != oracle.truncated || fast.error.code != oracle.error.code)
        return fail(TrackOutcome::inexact, int(oracle.steps.size()));
    return g;
}
const char* track_family_name(TrackFamily f) {
    static const char* const names[] = {"generic", "far_source", "axis_parallel", "along_plane",
                                        "corner",  "grazing",    "backscatter"};
    return names[int(f)];
}

GradedTrack grade_track(const Model::Track& exact, const TrackerRun& run) {
    GradedTrack g;
    auto fail = [&](TrackOutcome o, int step) {
        g.outcome = o, g.failed_step = step;
        return g;
    };
    if (!exact.start_undecided.empty()) return fail(TrackOutcome::undecided, 0);
    if (exact.start.size() > 1) return fail(TrackOutcome::overlap, 0);
    int expected = exact.start.empty() ? -1 : exact.start[0];
    if (run.start != expected)
        return fail(run.start < 0 ? TrackOutcome::lost : TrackOutcome::wrong_cell, 0);
    if (expected < 0) return g; // starts outside the model, and knows it
    // The tracker's steps into another cell: a crossing of a surface inside its cell (a union's)
    // is no step of the exact track, which records changes of cell only.
    std::vector<TrackerStep> moves;
    int current = run.start;
    for (const TrackerStep& s : run.steps) {
        // A step shorter than the codes' own coincidence tolerance: the crossing of a surface
        // the particle already sits on (OpenMC #2618's coincident spheres).
        if (s.length < fp_coincident) ++g.zero_length_steps;
        if (s.cell != current) moves.push_back(s), current = s.cell;
    }
    for (std::size_t k = 0;; ++k) {
        int step = int(k) + 1;
        if (k >= exact.steps.size()) {
            if (k < moves.size()) return fail(TrackOutcome::extra, step);
            return g;
        }
        const Model::Step& e = exact.steps[k];
        if (!e.undecided.empty()) return fail(TrackOutcome::undecided, step);
        if (e.cells.size() > 1) return fail(TrackOutcome::overlap, step);
        if (k >= moves.size())
            return fail(run.escaped ? TrackOutcome::missed : TrackOutcome::stuck, step);
        const TrackerStep& s = moves[k];
        ++g.steps;
        double ulp = std::nextafter(std::fabs(e.t), infinity) - std::fabs(e.t);
        g.max_t_ulps = std::max(g.max_t_ulps, std::fabs(s.t - e.t) / ulp);
        expected = e.cells.empty() ? -1 : e.cells[0];
        if (s.cell != expected)
            return fail(s.cell < 0 ? TrackOutcome::lost : TrackOutcome::wrong_cell, step);
        if (expected < 0) return g; // left the model, as the exact track does
    }
}

std::optional<TrackRay> track_ray(const Model& m, Vec3 lo, Vec3 hi, TrackFamily f,
                                  std::uint64_t seed, std::uint64_t i) {
    std::mt19937_64 rng(seed * 0x9e3779b97f4a7c15ull + std::uint64_t(f) * 0x100000001b3ull + i);
    auto uniform = [&](double a, double b) {
        return std::uniform_real_distribution<double>(a, b)(rng);
    };
    auto point = [&] {
        return Vec3{uniform(lo.x, hi.x), uniform(lo.y, hi.y), uniform(lo.z, hi.z)};
    };
    auto direction = [&] {
        std::normal_distribution<double> n;
        for (;;) {
            Vec3 d{n(rng), n(rng), n(rng)};
            if (std::fabs(d.x) + std::fabs(d.y) + std::fabs(d.z) > 1e-3) return d;
        }
    };
    const double size = std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z});
    switch (f) {
    case TrackFamily::generic:
        return TrackRay{point(), direction()};
    case TrackFamily::far_source: {
        // Aimed at a point of the box from 2^10 to 2^40 box sizes away.
        Vec3 target = point(), d = direction();
        double far = std::ldexp(size, 10 + int(i % 31));
        double len = std::sqrt(dot3(d, d));
        Vec3 p{target.x - far * d.x / len, target.y - far * d.y / len, target.z - far * d.z / len};
        return TrackRay{p, d};
    }
    case TrackFamily::axis_parallel: {
        Vec3 u{};
        int axis = int(i % 3);
        double sign = (i / 3) % 2 ? -1.0 : 1.0;
        u = axis == 0 ? Vec3{sign, 0, 0} : axis == 1 ? Vec3{0, sign, 0} : Vec3{0, 0, sign};
        return TrackRay{point(), u};
    }
    case TrackFamily::along_plane: {
        // On an axis-aligned plane of the model (its coordinate there exactly the plane's),
        // moving within it.
        std::vector<std::pair<int, double>> planes = axis_planes(m);
        if (planes.empty()) return std::nullopt;
        auto [axis, at] = planes[i % planes.size()];
        Vec3 p = point(), u = direction();
        if (axis == 0) p.x = at, u.x = 0;
        if (axis == 1) p.y = at, u.y = 0;
        if (axis == 2) p.z = at, u.z = 0;
        return TrackRay{p, u};
    }
    case TrackFamily::corner: {
        // Through a corner of three axis-aligned planes, exactly: from a point of the box whose
        // difference to the corner is exact (u = corner - p, so p + 1 u is the corner), or from
        // the corner itself (every other ray), outwards or inwards at random.
        std::vector<double> at[3];
        for (auto [axis, x] : axis_planes(m))
            at[axis].push_back(x);
        if (at[0].empty() || at[1].empty() || at[2].empty()) return std::nullopt;
        Vec3 corner{at[0][rng() % at[0].size()], at[1][rng() % at[1].size()],
                    at[2][rng() % at[2].size()]};
        if (i % 2) return TrackRay{corner, direction()};
        Vec3 p = point();
        Vec3 u{corner.x - p.x, corner.y - p.y, corner.z - p.z};
        bool exact = std::isfinite(u.x + u.y + u.z) && p.x + u.x == corner.x &&
                     p.y + u.y == corner.y && p.z + u.z == corner.z && !(u == Vec3{});
        if (!exact) return TrackRay{corner, direction()};
        return TrackRay{p, u};
    }
    case TrackFamily::grazing: {
        // The curved surfaces: spheres, cylinders and quadrics with a quadratic part.
        std::vector<const SurfaceShape*> curved;
        for (const Model::Surface& s : m.surfaces()) {
            const Quadric* q = std::get_if<Quadric>(&s.shape);
            bool flat = std::holds_alternative<Plane>(s.shape) ||
                        (q && q->q[0] == 0 && q->q[1] == 0 && q->q[2] == 0 && q->q[3] == 0 &&
                         q->q[4] == 0 && q->q[5] == 0);
            if (!flat) curved.push_back(&s.shape);
        }
        if (curved.empty()) return std::nullopt;
        const SurfaceShape& surface = *curved[i % curved.size()];
        for (int attempt = 0; attempt < 1000; ++attempt) {
            Line l{point(), direction(), Range::line};
            Result r = std::visit([&](const auto& x) { return correct::intersect(x, l); }, surface);
            if (r.count == 0) continue;
            Vec3 at = r.hits[rng() % r.count].p, w = direction();
            Vec3 n = std::visit([&](const auto& x) { return normal(x, at); }, surface);
            double nn = dot3(n, n);
            if (!(nn > 0) || !std::isfinite(nn)) continue;
            double along = dot3(w, n) / nn;
            Vec3 u{w.x - along * n.x, w.y - along * n.y, w.z - along * n.z};
            double len = std::sqrt(dot3(u, u));
            if (!(len > 1e-3)) continue;
            double back = uniform(0, size) / len;
            return TrackRay{{at.x - back * u.x, at.y - back * u.y, at.z - back * u.z}, u};
        }
        return std::nullopt; // no line of 1,000 met the surface in the box
    }
    case TrackFamily::backscatter: {
        for (int attempt = 0; attempt < 1000; ++attempt) {
            Vec3 p = point(), d = direction();
            Model::Track t = m.track(p, d, 1);
            if (t.steps.empty()) continue;
            double len = std::sqrt(dot3(d, d));
            double past = t.steps[0].t + std::ldexp(size, -20 - int(i % 31)) / len;
            Vec3 at{p.x + past * d.x, p.y + past * d.y, p.z + past * d.z}, w = direction();
            // Turned back: against d, by up to a right angle.
            double into = dot3(w, d);
            if (into > 0)
                w = {w.x - 2 * into / (len * len) * d.x, w.y - 2 * into / (len * len) * d.y,
                     w.z - 2 * into / (len * len) * d.z};
            if (!(dot3(w, d) < 0)) continue;
            return TrackRay{at, w};
        }
        return std::nullopt;
    }
    }
    return std::nullopt;
}

std::string query_line(const std::string& id, Vec3 p, Vec3 u) {
    return "{\"id\":\"" + id + "\",\"p\":[\"" + hex(p.x) + "\",\"" + hex(p.y) + "\",\"" + hex(p.z) +
           "\"],\"u\":[\"" + hex(u.x) + "\",\"" + hex(u.y) + "\",\"" + hex(u.z) + "\"]}";
}

PointSample sample_points(const Model& m, Vec3 lo, Vec3 hi, std::uint64_t seed, std::uint64_t n) {
    PointSample out;
    std::map<std::vector<int>, std::uint64_t> overlaps;
    for (std::uint64_t i = 0; i < n; ++i) {
        std::mt19937_64 rng(seed * 0x9e3779b97f4a7c15ull + 0x5eed0000ull + i);
        auto uniform = [&](double a, double b) {
            return std::uniform_real_distribution<double>(a, b)(rng);
        };
        Vec3 p{uniform(lo.x, hi.x), uniform(lo.y, hi.y), uniform(lo.z, hi.z)};
        std::normal_distribution<double> normal_value;
        Vec3 u{normal_value(rng), normal_value(rng), normal_value(rng)};
        if (u == Vec3{}) u = {0, 0, 1};
        Model::Location at = m.locate(p, u);
        if (!at.error.ok()) continue;
        ++out.points;
        if (!at.undecided.empty()) {
            ++out.undecided;
        } else if (at.cells.size() > 1) {
            if (out.first_overlap.empty())
                out.first_overlap = query_line("overlap/" + std::to_string(i), p, u);
            ++overlaps[at.cells];
        } else if (at.cells.empty()) {
            if (out.first_gap.empty()) out.first_gap = query_line("gap/" + std::to_string(i), p, u);
            ++out.in_none;
        }
    }
    out.overlaps.assign(overlaps.begin(), overlaps.end());
    std::sort(out.overlaps.begin(), out.overlaps.end(),
              [](const auto& a, const auto& b) { return a.second > b.second; });
    return out;
}

} // namespace linequad
