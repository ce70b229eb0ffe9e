// A model's checks and its exact queries. Along a ray every surface's sense is known exactly: the
// sense at its origin (with the direction, linequad/surfaces.hpp), flipped at each of its
// crossings, which the correct solver gives in order, correctly rounded; crossings of different
// surfaces whose rounded t is the same double are ordered by their exact roots
// (scene/exact_order.hpp). So the cell a particle is in, and the point where that changes, are
// exact, and only the distance is rounded (once, correctly).
#include "linequad/cells.hpp"

#include "scene/exact_order.hpp"

#include "linequad/prepared.hpp"
#include "linequad/solvers.hpp"

#include <algorithm>
#include <limits>
#include <map>
#include <set>

namespace linequad {

namespace {

std::string id_text(std::int64_t id) {
    return std::to_string(id);
}

Error check_surface(const SurfaceShape& s) {
    // The sense's own checks of the surface, at a point that always passes.
    return std::visit([](const auto& x) { return check_sense(x, Vec3{}); }, s);
}

Sense flipped(Sense s) {
    return s == Sense::positive ? Sense::negative : s == Sense::negative ? Sense::positive : s;
}

// A crossing of one surface along the ray (its root number `root`), correctly rounded. A
// tangency touches and keeps the sense: it is no event.
struct Event {
    double t;
    int surface, root;
};

// The exact roots of each surface along one ray, formed only for surfaces whose crossings tie in
// their rounded t with another's.
class ExactRootsOnRay {
  public:
    ExactRootsOnRay(const std::vector<Model::Surface>& surfaces, const Line& ray)
        : surfaces_(surfaces), ray_(ray), formed_(surfaces.size()) {}
    const detail::ExactRoots& of(int surface) {
        std::optional<detail::ExactRoots>& roots = formed_[std::size_t(surface)];
        if (!roots)
            roots = std::visit([&](const auto& s) { return detail::exact_roots(prepare(s), ray_); },
                               surfaces_[std::size_t(surface)].shape);
        return *roots;
    }
    // sgn(t_a - t_b), exactly.
    int compare(const Event& a, const Event& b) {
        if (a.surface == b.surface) return a.root < b.root ? -1 : a.root > b.root ? 1 : 0;
        const detail::ExactRoots &ra = of(a.surface), &rb = of(b.surface);
        return detail::compare_roots(ra.roots[a.root], ra.D[a.root], rb.roots[b.root],
                                     rb.D[b.root]);
    }

  private:
    const std::vector<Model::Surface>& surfaces_;
    Line ray_;
    std::vector<std::optional<detail::ExactRoots>> formed_; // a slot per surface, filled when asked
};

} // namespace

std::optional<Model> Model::build(std::vector<Surface> surfaces,
                                  const std::vector<CellSource>& cells, std::string& error) {
    Model m;
    std::map<std::int64_t, int> by_id;
    for (std::size_t i = 0; i < surfaces.size(); ++i) {
        const Surface& s = surfaces[i];
        if (Error e = check_surface(s.shape); !e.ok()) {
            error = "surface " + id_text(s.id) + ": " + message(e);
            return std::nullopt;
        }
        if (!by_id.emplace(s.id, int(i)).second) {
            error = "surface " + id_text(s.id) + " is defined twice";
            return std::nullopt;
        }
    }
    if (cells.empty()) {
        error = "the model has no cells";
        return std::nullopt;
    }
    std::set<std::int64_t> cell_ids;
    for (const CellSource& c : cells) {
        std::string where = "cell " + id_text(c.id);
        if (!cell_ids.insert(c.id).second) {
            error = where + " is defined twice";
            return std::nullopt;
        }
        std::string why;
        std::optional<Region> region = Region::parse(c.region, why);
        if (!region) {
            error = where + ": region \"" + c.region + "\": " + why;
            return std::nullopt;
        }
        for (Region::Token& t : region->tokens()) {
            if (t.op != Region::Op::half_space) continue;
            auto found = by_id.find(t.id);
            if (found == by_id.end()) {
                error = where + ": region \"" + c.region + "\" names surface " + id_text(t.id) +
                        ", which the model does not define";
                return std::nullopt;
            }
            t.surface = found->second;
        }
        m.cells_.push_back({c.id, c.name, std::move(*region)});
    }
    m.surfaces_ = std::move(surfaces);
    return m;
}

int Model::cell_index(std::int64_t id) const {
    for (std::size_t i = 0; i < cells_.size(); ++i)
        if (cells_[i].id == id) return int(i);
    return -1;
}
int Model::surface_index(std::int64_t id) const {
    for (std::size_t i = 0; i < surfaces_.size(); ++i)
        if (surfaces_[i].id == id) return int(i);
    return -1;
}

std::optional<std::vector<Sense>> Model::senses_at(Vec3 p, Vec3 u, Error& error) const {
    std::vector<Sense> senses;
    senses.reserve(surfaces_.size());
    for (const Surface& s : surfaces_) {
        SenseResult r = std::visit([&](const auto& x) { return sense(x, p, u); }, s.shape);
        if (!r.ok()) {
            error = r.error;
            return std::nullopt;
        }
        senses.push_back(r.sense);
    }
    return senses; // a model has a surface (every region names one): sense() checked p and u
}

Model::Location Model::locate(Vec3 p, Vec3 u) const {
    Location where;
    std::optional<std::vector<Sense>> senses = senses_at(p, u, where.error);
    if (!senses) return where;
    for (std::size_t c = 0; c < cells_.size(); ++c) {
        std::optional<bool> in = cells_[c].region.contains(*senses);
        if (!in)
            where.undecided.push_back(int(c));
        else if (*in)
            where.cells.push_back(int(c));
    }
    return where;
}

// Every surface's roots on the ray p + t u, t > 0 (a root at t = 0 is where the particle is,
// which its sense with the direction already takes into account), in their exact order; at each
// point where some surface is crossed (an exact tie: several), `at(t, first, last)` with `senses`
// already flipped past it, until it returns true. False, with `error` set, where a surface
// refuses the ray.
template <class At>
bool Model::walk(Vec3 p, Vec3 u, std::vector<Sense>& senses, Error& error, At at) const {
    Line ray{p, u, Interval(0, std::numeric_limits<double>::infinity())};
    std::vector<Event> events;
    for (std::size_t s = 0; s < surfaces_.size(); ++s) {
        if (senses[s] == Sense::on) continue; // the ray lies in it: no crossing
        Result r = std::visit(
            [&](const auto& x) {
                return correct::intersect(x, ray, {Need::all, false});
            },
            surfaces_[s].shape);
        if (!r.ok()) {
            error = r.error();
            return false;
        }
        for (int k = 0; k < r.count; ++k)
            if (r.hits[k].t > 0 && r.hits[k].kind == HitKind::cross)
                events.push_back({r.hits[k].t, int(s), k});
    }
    std::stable_sort(events.begin(), events.end(),
                     [](const Event& a, const Event& b) { return a.t < b.t; });
    // Roots that round to the same double, ordered exactly; exact ties then act together.
    ExactRootsOnRay exact(surfaces_, ray);
    for (std::size_t i = 0; i < events.size();) {
        std::size_t end = i;
        while (end < events.size() && events[end].t == events[i].t)
            ++end;
        if (end - i > 1)
            std::stable_sort(
                events.begin() + long(i), events.begin() + long(end),
                [&](const Event& a, const Event& b) { return exact.compare(a, b) < 0; });
        for (std::size_t tie = i; tie < end;) {
            std::size_t tie_end = tie + 1;
            while (tie_end < end && exact.compare(events[tie], events[tie_end]) == 0)
                ++tie_end;
            std::vector<int> crossed;
            for (std::size_t k = tie; k < tie_end; ++k) {
                Sense& s = senses[std::size_t(events[k].surface)];
                s = flipped(s);
                crossed.push_back(events[k].surface);
            }
            std::sort(crossed.begin(), crossed.end());
            crossed.erase(std::unique(crossed.begin(), crossed.end()), crossed.end());
            if (at(events[tie].t, crossed)) return true;
            tie = tie_end;
        }
        i = end;
    }
    return true;
}

void Model::cells_holding(const std::vector<Sense>& senses, std::vector<int>& in,
                          std::vector<int>& undecided) const {
    for (std::size_t c = 0; c < cells_.size(); ++c) {
        std::optional<bool> holds = cells_[c].region.contains(senses);
        if (!holds)
            undecided.push_back(int(c));
        else if (*holds)
            in.push_back(int(c));
    }
}

Model::Crossing Model::next_crossing(int cell, Vec3 p, Vec3 u) const {
    Crossing out;
    if (cell < 0 || std::size_t(cell) >= cells_.size()) {
        out.error = {ErrorCode::bad_option, "cell"};
        return out;
    }
    std::optional<std::vector<Sense>> senses = senses_at(p, u, out.error);
    if (!senses) return out;
    const Region& region = cells_[std::size_t(cell)].region;
    std::optional<bool> inside = region.contains(*senses);
    if (!inside) {
        out.exit = Exit::along;
        return out;
    }
    if (!*inside) {
        out.exit = Exit::not_inside;
        return out;
    }
    out.exit = Exit::escapes;
    bool walked = walk(p, u, *senses, out.error, [&](double t, const std::vector<int>& crossed) {
        if (region.contains(*senses) == std::optional<bool>(true)) return false;
        out.exit = Exit::leaves;
        out.t = t;
        out.surfaces = crossed;
        cells_holding(*senses, out.entered, out.undecided_entered);
        return true;
    });
    if (!walked) out.exit = Exit::error;
    return out;
}

Model::Track Model::track(Vec3 p, Vec3 u, int max_steps) const {
    Track out;
    std::optional<std::vector<Sense>> senses = senses_at(p, u, out.error);
    if (!senses) return out;
    cells_holding(*senses, out.start, out.start_undecided);
    std::vector<int> before = out.start, before_undecided = out.start_undecided;
    walk(p, u, *senses, out.error, [&](double t, const std::vector<int>& crossed) {
        Step step{t, crossed, {}, {}};
        cells_holding(*senses, step.cells, step.undecided);
        if (step.cells == before && step.undecided == before_undecided) return false;
        before = step.cells, before_undecided = step.undecided;
        out.steps.push_back(std::move(step));
        if (int(out.steps.size()) >= max_steps) {
            out.truncated = true;
            return true;
        }
        return false;
    });
    return out;
}

const char* exit_name(Model::Exit e) {
    switch (e) {
    case Model::Exit::leaves:
        return "leaves";
    case Model::Exit::escapes:
        return "escapes";
    case Model::Exit::along:
        return "along";
    case Model::Exit::not_inside:
        return "not_inside";
    case Model::Exit::error:
        return "error";
    }
    return "?";
}

} // namespace linequad
