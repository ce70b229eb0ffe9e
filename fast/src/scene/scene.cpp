// The scene: prepared shapes, their boxes, and a bounding volume hierarchy over the boxes,
// traversed in double with a slab test widened by its own rounding error; in a leaf, a capsule
// around each shape's axis is tested before the shape is solved.
#include "linequad/scene.hpp"

#include "forms/finish.hpp"
#include "forms/traits.hpp"
#include "linequad/solvers.hpp"
#include "numeric/fp_environment.hpp"
#include "scene/bounds.hpp"
#include "scene/box_traversal.hpp"
#include "scene/exact_order.hpp"
#include "scene/slab.hpp"
#include "shapes/all.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <memory>
#include <optional>
#include <variant>

namespace linequad {

namespace {

using detail::merged;
using detail::slab;
using detail::SlabLine;
using PreparedShape = detail::PreparedVariant<Shape>;

template <class S>
Box bounds_of(const S& s) {
    return detail::ShapeTraits<S>::bounds(s);
}
template <class S>
detail::BoundingCapsule bounding_capsule_of(const S& s) {
    return detail::ShapeTraits<S>::bounding_capsule(s);
}

// A node's shapes are order[first, first + count) when it is a leaf (count > 0); otherwise its
// children are the next node and node `second`.
struct Node {
    Box box;
    std::uint32_t first = 0, count = 0, second = 0;
};

constexpr std::uint32_t leaf_size = 4;
// Levels split by the surface area heuristic; below them, medians (see Impl::build).
constexpr int sah_depth = 64;
// The traversal's stack: one entry per level at most, plus one.
constexpr int max_depth = sah_depth + 32;

// The smallest t that is not tied with best: hits at t <= tie_end(best) may round to best.
double tie_end(double best) {
    return best == std::numeric_limits<double>::infinity()
               ? best
               : std::nextafter(best, std::numeric_limits<double>::infinity());
}

} // namespace

struct Scene::Impl {
    SceneSolver solver;
    std::vector<PreparedShape> shapes;
    std::vector<Box> boxes;
    std::vector<detail::BoundingCapsule> capsules; // of the bounded shapes (indexed like shapes)
    std::vector<std::uint32_t> order;     // the bounded shapes, in the hierarchy's leaf order
    std::vector<std::uint32_t> unbounded; // shapes that are not finite: solved for every line
    std::vector<Node> nodes;
    int depth = 0;                                // the deepest node's level (the root's is 0)
    std::unique_ptr<detail::BoxTraversal> embree; // when the scene traverses with Embree
    Error error;
    std::uint32_t error_shape = no_shape;

    // Nodes over order[first, last), split by the surface area heuristic over 16 bins of the
    // boxes' centres along each axis (the split that least expects a line through the node to
    // meet boxes on both sides); at the median of the widest axis when every centre coincides.
    std::uint32_t build(std::uint32_t first, std::uint32_t last, int depth = 0) {
        std::uint32_t index = std::uint32_t(nodes.size());
        this->depth = std::max(this->depth, depth);
        nodes.emplace_back();
        Box box = boxes[order[first]];
        Box centres{detail::everything().hi, detail::everything().lo};
        for (std::uint32_t k = first; k < last; ++k) {
            const Box& b = boxes[order[k]];
            box = merged(box, b);
            Vec3 c = 0.5 * (b.lo + b.hi);
            centres = merged(centres, {c, c});
        }
        nodes[index].box = box;
        if (last - first <= leaf_size) {
            nodes[index].first = first, nodes[index].count = last - first;
            return index;
        }
        // Past sah_depth, median splits: the depth stays below sah_depth + 31, which bounds
        // the traversal's stack, however lopsided the heuristic's splits were.
        std::uint32_t middle =
            depth < sah_depth ? split(first, last, centres) : median_split(first, last, centres);
        build(first, middle, depth + 1);
        std::uint32_t second = build(middle, last, depth + 1);
        nodes[index].second = second;
        return index;
    }

    double centre(std::uint32_t s, int axis) const {
        return 0.5 * (boxes[s].lo[axis] + boxes[s].hi[axis]);
    }

    static double area(const Box& b) {
        Vec3 e = b.hi - b.lo;
        return e.x * e.y + e.y * e.z + e.z * e.x;
    }

    std::uint32_t split(std::uint32_t first, std::uint32_t last, const Box& centres) {
        constexpr int bins = 16;
        double best_cost = std::numeric_limits<double>::infinity();
        int best_axis = -1;
        double best_at = 0;
        for (int axis = 0; axis < 3; ++axis) {
            double lo = centres.lo[axis], hi = centres.hi[axis];
            if (!(hi > lo) || !std::isfinite(hi - lo)) continue;
            double scale = bins / (hi - lo);
            Box bin_box[bins];
            std::uint32_t count[bins] = {};
            for (std::uint32_t k = first; k < last; ++k) {
                int b = std::min(bins - 1, int((centre(order[k], axis) - lo) * scale));
                bin_box[b] = count[b]++ ? merged(bin_box[b], boxes[order[k]]) : boxes[order[k]];
            }
            // Cost of splitting after bin j: area(left) n(left) + area(right) n(right).
            double right_area[bins];
            std::uint32_t right_count[bins];
            Box acc{};
            std::uint32_t n = 0;
            for (int j = bins - 1; j > 0; --j) {
                if (count[j]) acc = n ? merged(acc, bin_box[j]) : bin_box[j], n += count[j];
                right_area[j] = n ? area(acc) : 0, right_count[j] = n;
            }
            n = 0;
            for (int j = 0; j < bins - 1; ++j) {
                if (count[j]) acc = n ? merged(acc, bin_box[j]) : bin_box[j], n += count[j];
                if (n == 0 || right_count[j + 1] == 0) continue;
                double cost = area(acc) * n + right_area[j + 1] * right_count[j + 1];
                if (cost < best_cost)
                    best_cost = cost, best_axis = axis, best_at = lo + (j + 1) / scale;
            }
        }
        auto begin = order.begin() + first, end = order.begin() + last;
        if (best_axis >= 0) {
            auto middle = std::partition(
                begin, end, [&](std::uint32_t s) { return centre(s, best_axis) < best_at; });
            if (middle != begin && middle != end) return std::uint32_t(middle - order.begin());
        }
        return median_split(first, last, centres);
    }

    std::uint32_t median_split(std::uint32_t first, std::uint32_t last, const Box& centres) {
        auto begin = order.begin() + first, end = order.begin() + last;
        Vec3 spread = centres.hi - centres.lo;
        int axis = spread.x >= spread.y && spread.x >= spread.z ? 0 : spread.y >= spread.z ? 1 : 2;
        std::uint32_t middle = first + (last - first) / 2;
        std::nth_element(begin, order.begin() + middle, end, [&](std::uint32_t a, std::uint32_t b) {
            return centre(a, axis) < centre(b, axis);
        });
        return middle;
    }

    Result solve(std::uint32_t i, const Line& line, Query q) const {
        return std::visit(
            [&](const auto& p) {
                return solver == SceneSolver::correct ? correct::intersect(p, line, q)
                                                      : stable::intersect(p, line, q);
            },
            shapes[i]);
    }

    // Calls visit(shape) for every shape whose box and capsule the line may cross within its
    // range: the unbounded first, then nearer subtrees first. visit returns the range end still
    // of interest (or -infinity to stop).
    // any: the query stops at its first hit (Embree is then asked for occlusion).
    template <class Visit>
    void traverse(const Line& line, bool any, Visit&& visit) const {
        constexpr double stop = -std::numeric_limits<double>::infinity();
        double end = line.range.t1;
        for (std::uint32_t s : unbounded)
            if ((end = visit(s)) == stop) return;
        if (nodes.empty()) return;
        if (embree) {
            struct Thunk {
                const Impl& m;
                const Line& line;
                Visit& visit;
                double end;
            } thunk{*this, line, visit, end};
            auto call = [](void* p, std::uint32_t s) {
                Thunk& t = *static_cast<Thunk*>(p);
                if (!detail::may_cross(t.m.capsules[s], t.line)) return t.end;
                return t.end = t.visit(s);
            };
            if (embree->traverse(line, end, any, call, &thunk)) return;
        }
        SlabLine slab_line(line);
        struct Entry {
            std::uint32_t node;
            double t0; // where the line may enter the node's box
        };
        Entry stack[max_depth + 1];
        int top = 0;
        double t0 = line.range.t0, t1 = end;
        if (!slab(nodes[0].box, slab_line, t0, t1)) return;
        stack[top++] = {0, t0};
        while (top > 0) {
            Entry e = stack[--top];
            if (e.t0 > end) continue;
            const Node& node = nodes[e.node];
            if (node.count > 0) {
                for (std::uint32_t k = node.first; k < node.first + node.count; ++k) {
                    if (!detail::may_cross(capsules[order[k]], line)) continue;
                    if ((end = visit(order[k])) == stop) return;
                }
                continue;
            }
            // Both children tested once; the nearer is taken first, its hits shortening the
            // range the other is then looked at over.
            std::uint32_t a = e.node + 1, b = node.second;
            double a0 = line.range.t0, a1 = end, b0 = line.range.t0, b1 = end;
            bool in_a = slab(nodes[a].box, slab_line, a0, a1);
            bool in_b = slab(nodes[b].box, slab_line, b0, b1);
            if (in_a && in_b && a0 > b0) {
                std::swap(a, b);
                std::swap(a0, b0);
                std::swap(in_a, in_b);
            }
            if (in_b) stack[top++] = {b, b0};
            if (in_a) stack[top++] = {a, a0};
        }
    }
};

namespace {

// Set by the Embree component (linequad::embree) when a program links it; null otherwise. Constant
// initialised, so that it is null before any registration runs.
std::atomic<detail::BoxTraversalMaker> embree_maker{nullptr};

} // namespace

void detail::register_embree(BoxTraversalMaker make) {
    embree_maker.store(make);
}

bool scene_traversal_available(SceneTraversal t) {
    return t != SceneTraversal::embree || embree_maker.load() != nullptr;
}

Scene::Scene(const std::vector<Shape>& shapes, SceneSolver solver, SceneTraversal traversal)
    : impl_(new Impl) {
    Impl& m = *impl_;
    m.solver = solver;
    m.shapes.reserve(shapes.size());
    m.boxes.reserve(shapes.size());
    for (std::uint32_t i = 0; i < shapes.size(); ++i) {
        m.shapes.push_back(
            std::visit([](const auto& s) { return PreparedShape(prepare(s)); }, shapes[i]));
        Error e = std::visit([](const auto& p) { return p.error(); }, m.shapes.back());
        if (!e.ok() && m.error.ok()) m.error = e, m.error_shape = i;
        Box box = e.ok() ? std::visit([](const auto& s) { return bounds_of(s); }, shapes[i])
                         : detail::everything();
        m.boxes.push_back(box);
        m.capsules.push_back(
            std::visit([](const auto& s) { return bounding_capsule_of(s); }, shapes[i]));
        (detail::bounded(box) ? m.order : m.unbounded).push_back(i);
    }
    if (!m.order.empty()) m.build(0, std::uint32_t(m.order.size()));
    // The own hierarchy stays: lines Embree's float ray cannot carry go through it.
    detail::BoxTraversalMaker make = embree_maker.load();
    if (traversal != SceneTraversal::hierarchy && !m.order.empty() && make)
        m.embree = make(m.boxes, m.order); // null if Embree cannot hold these boxes
}

Scene::~Scene() = default;
Scene::Scene(Scene&&) noexcept = default;
Scene& Scene::operator=(Scene&&) noexcept = default;

std::size_t Scene::size() const {
    return impl_->shapes.size();
}
SceneSolver Scene::solver() const {
    return impl_->solver;
}
SceneTraversal Scene::traversal() const {
    if (impl_->embree) return SceneTraversal::embree;
    return SceneTraversal::hierarchy;
}
Error Scene::error() const {
    return impl_->error;
}
std::uint32_t Scene::error_shape() const {
    return impl_->error_shape;
}
int Scene::depth() const {
    return impl_->depth;
}
Box Scene::bounds(std::uint32_t i) const {
    return impl_->boxes.at(i);
}
SpawnedRay Scene::spawn_ray(const SceneHit& from, Vec3 direction) const {
    if (from.shape >= impl_->shapes.size()) {
        SpawnedRay out;
        out.error = {ErrorCode::bad_option, "shape"};
        return out;
    }
    return std::visit([&](const auto& p) { return linequad::spawn_ray(p, from.hit, direction); },
                      impl_->shapes[from.shape]);
}

namespace {

// A line along a surface has no root to compare exactly.
constexpr std::uint8_t on_surface_index = 255;

// The hits of one shape's result, as scene hits (a line along the surface: its interval's
// first point, as a tangent hit).
template <class Add>
void each_hit(const Result& r, std::uint32_t shape, const Line& line, bool points, Add&& add) {
    for (int k = 0; k < r.count; ++k)
        add(SceneHit{r.hits[k], shape, std::uint8_t(k), false});
    if (r.on_surface) {
        Hit h{};
        h.t = r.s0;
        h.p = points && std::isfinite(r.s0) ? detail::point_at(line, r.s0) : Vec3{};
        h.bound = std::numeric_limits<double>::quiet_NaN();
        h.kind = HitKind::tangent, h.part = r.surface_part;
        h.certain = r.certainty == Certainty::certain;
        add(SceneHit{h, shape, on_surface_index, false});
    }
}

// Hits with equal t on different shapes are tied; within a tie, shape order (and a shape's own
// order: two of its hits can round to one t, an infinite one too).
void order_and_name_ties(std::vector<SceneHit>& hits) {
    std::sort(hits.begin(), hits.end(), [](const SceneHit& a, const SceneHit& b) {
        return a.hit.t < b.hit.t ||
               (a.hit.t == b.hit.t && std::pair(a.shape, a.index) < std::pair(b.shape, b.index));
    });
    for (std::size_t k = 1; k < hits.size(); ++k)
        if (hits[k].hit.t == hits[k - 1].hit.t && hits[k].shape != hits[k - 1].shape)
            hits[k].tied = hits[k - 1].tied = true;
}

// A hit's exact t, as the exact rung finds it: a root, or the first point of a line's interval
// along the surface ((num + S sqrt(D)) / den, S nonzero only for a disc's chord; or minus
// infinity, from an unbounded range).
struct ExactT {
    exact_form::SurdRoot<BigFloat> root;
    BigFloat D;
    bool minus_infinity = false;
};

int compare_exact(const ExactT& a, const ExactT& b) {
    if (a.minus_infinity || b.minus_infinity) return int(b.minus_infinity) - int(a.minus_infinity);
    return detail::compare_roots(a.root, a.D, b.root, b.D);
}

// The exact t of hit h from its shape's exact classification c, if c has it (it always should:
// the correct solver's exact rung found the hit).
std::optional<ExactT> exact_t(const detail::ExactRoots& c, const SceneHit& h) {
    ExactT t;
    if (h.index == on_surface_index) {
        if (c.outcome != exact_form::Outcome::on_surface) return std::nullopt;
        t.minus_infinity = !c.s0.bounded;
        t.root.N = c.s0.num, t.root.Den = c.s0.den, t.root.S = c.s0.S;
        t.D = c.s0_D;
        return t;
    }
    if (c.outcome != exact_form::Outcome::hits || h.index >= c.count) return std::nullopt;
    t.root = c.roots[h.index], t.D = c.D[h.index];
    return t;
}

// The exact order of the hits that rounded to the same double (correct scenes): each run of
// equal t on two or more shapes sorted by comparing their exact t, and tied only where those
// are equal on two shapes or more; with nearest, only the exactly nearest are kept.
void refine_ties(const std::vector<PreparedShape>& shapes, const Line& line, bool nearest,
                 std::vector<SceneHit>& hits, std::uint32_t& comparisons) {
    using Roots = detail::ExactRoots;
    for (std::size_t i = 0; i < hits.size();) {
        std::size_t j = i + 1;
        while (j < hits.size() && hits[j].hit.t == hits[i].hit.t)
            ++j;
        bool tie = false;
        for (std::size_t k = i; k < j; ++k)
            tie = tie || hits[k].tied;
        if (!tie) {
            i = j;
            continue;
        }
        std::vector<std::pair<std::uint32_t, Roots>> roots; // per shape of the run
        std::vector<std::pair<SceneHit, ExactT>> run;
        for (std::size_t k = i; k < j; ++k) {
            auto it = std::find_if(roots.begin(), roots.end(),
                                   [&](const auto& r) { return r.first == hits[k].shape; });
            if (it == roots.end()) {
                roots.emplace_back(
                    hits[k].shape,
                    std::visit([&](const auto& p) { return detail::exact_roots(p, line); },
                               shapes[hits[k].shape]));
                it = roots.end() - 1;
            }
            std::optional<ExactT> t = exact_t(it->second, hits[k]);
            if (!t) break; // never expected
            run.emplace_back(hits[k], std::move(*t));
        }
        if (run.size() != j - i) {
            i = j;
            continue;
        }
        auto compare = [&](std::size_t a, std::size_t b) {
            ++comparisons;
            return compare_exact(run[a].second, run[b].second);
        };
        // Runs hold a few hits: insertion sort, exact order first, then shape order.
        for (std::size_t k = 1; k < run.size(); ++k)
            for (std::size_t m = k; m > 0; --m) {
                int c = compare(m, m - 1);
                const SceneHit &a = run[m].first, &b = run[m - 1].first;
                if (c > 0 || (c == 0 && std::pair(a.shape, a.index) > std::pair(b.shape, b.index)))
                    break;
                std::swap(run[m], run[m - 1]);
            }
        // Runs of exactly equal t: tied where they hold two shapes or more.
        std::size_t first_end = run.size();
        for (std::size_t a = 0; a < run.size();) {
            std::size_t b = a + 1;
            bool shapes_differ = false;
            while (b < run.size() && compare(b, a) == 0) {
                shapes_differ = shapes_differ || run[b].first.shape != run[a].first.shape;
                ++b;
            }
            for (std::size_t k = a; k < b; ++k)
                run[k].first.tied = shapes_differ;
            if (a == 0) first_end = b;
            a = b;
        }
        for (std::size_t k = 0; k < run.size(); ++k)
            hits[i + k] = run[k].first;
        if (nearest) {
            hits.erase(hits.begin() + std::ptrdiff_t(i + first_end), hits.end());
            return;
        }
        i = j;
    }
}

} // namespace

void Scene::intersect(const Line& line, Query query, SceneAnswer& out) const {
    numeric::StandardEnvironment standard;
    const Impl& m = *impl_;
    out.hits.clear();
    out.error = {}, out.error_shape = no_shape, out.shapes_solved = 0, out.exact_comparisons = 0;
    // The line first, then the shapes: the order every solver checks them in.
    if (Error e = detail::check_line(line); !e.ok()) {
        out.error = e;
        return;
    }
    if (!m.error.ok()) {
        out.error = m.error, out.error_shape = m.error_shape;
        return;
    }
    constexpr double stop = -std::numeric_limits<double>::infinity();
    bool failed = false;
    auto solved = [&](std::uint32_t s, const Result& r) {
        ++out.shapes_solved;
        if (r.ok()) return true;
        out.error = r.error(), out.error_shape = s, failed = true;
        return false;
    };
    switch (query.need) {
    case Need::any:
        m.traverse(line, query.need == Need::any, [&](std::uint32_t s) {
            Result r = m.solve(s, line, query);
            if (!solved(s, r)) return stop;
            if (!r.any_hit()) return line.range.t1;
            each_hit(r, s, line, false, [&](const SceneHit& h) {
                if (out.hits.empty()) out.hits.push_back(h);
            });
            return stop;
        });
        break;
    case Need::nearest: {
        double best = std::numeric_limits<double>::infinity();
        m.traverse(line, query.need == Need::any, [&](std::uint32_t s) {
            Line l = line;
            l.range.t1 = std::min(line.range.t1, tie_end(best));
            Result r = m.solve(s, l, query);
            if (!solved(s, r)) return stop;
            each_hit(r, s, line, query.points, [&](const SceneHit& h) {
                if (h.hit.t < best) {
                    best = h.hit.t;
                    out.hits.clear();
                }
                if (h.hit.t == best) out.hits.push_back(h);
            });
            return std::min(line.range.t1, tie_end(best));
        });
        order_and_name_ties(out.hits);
        if (m.solver == SceneSolver::correct && !failed)
            refine_ties(m.shapes, line, true, out.hits, out.exact_comparisons);
        break;
    }
    case Need::all:
        m.traverse(line, query.need == Need::any, [&](std::uint32_t s) {
            Result r = m.solve(s, line, query);
            if (!solved(s, r)) return stop;
            each_hit(r, s, line, query.points, [&](const SceneHit& h) { out.hits.push_back(h); });
            return line.range.t1;
        });
        order_and_name_ties(out.hits);
        if (m.solver == SceneSolver::correct && !failed)
            refine_ties(m.shapes, line, false, out.hits, out.exact_comparisons);
        break;
    }
    if (failed) out.hits.clear();
}

} // namespace linequad
