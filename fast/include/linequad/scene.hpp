// Many shapes, one line: which of them it hits, and in what order.
//     linequad::Scene scene(shapes);                   // built once: prepared, bounded, a BVH
//     linequad::SceneAnswer a;                         // reused: no allocation once it is warm
//     scene.intersect(ray, {Need::nearest, true}, a);  // a.hits[0]: the nearest hit, its shape
// Each shape is solved by the scene's solver (stable or correct) over the line's range; shapes
// whose bounding box or capsule the line misses are never solved. The boxes are rounded outward,
// and the slab and capsule tests are widened by their own rounding errors, so culling never
// loses a hit.
#pragma once

#include "linequad/prepared.hpp"
#include "linequad/result.hpp"
#include "linequad/shapes.hpp"
#include "linequad/spawn.hpp"

#include <cstdint>
#include <limits>
#include <memory>
#include <vector>

namespace linequad {

// The solver a scene answers with: stable (fast; t within a few ulps, the order of two hits
// closer than that not certain) or correct (t and points correctly rounded, and the hits in
// their exact order: by their rounded t, and where two round to the same double, by an exact
// comparison of their roots, which is needed only there).
enum class SceneSolver : std::uint8_t { stable, correct };

// What finds the shapes a line comes near: linequad's own hierarchy of double boxes, or Embree's
// (its BVH over the same boxes as user geometry, traversed with a float ray; the boxes are
// widened to cover that ray's rounding, so it loses no shape either; 2.5 to 4.4 times faster on
// scenes of rods, bench/bench_scene.cpp). Embree is there when linequad was built with it
// (scene_traversal_available); automatic takes it then, and the hierarchy otherwise. A scene asked
// for Embree without it, or whose boxes float cannot hold around their centre, uses its own; so
// does a line whose slab parameters overflow (a direction of subnormal size). The answers are the
// same either way (but for which hit `any` finds first, and a refusal from a shape beyond the
// nearest hit, which one order may solve and the other not).
enum class SceneTraversal : std::uint8_t { automatic, hierarchy, embree };
bool scene_traversal_available(SceneTraversal t);

inline constexpr std::uint32_t no_shape = std::numeric_limits<std::uint32_t>::max();

struct SceneHit {
    Hit hit;
    std::uint32_t shape; // the shape's index in the scene
    std::uint8_t index;  // its place among its shape's hits on the line (0: the shape's nearest)
    // Another hit of this answer, on another shape, is at the same t (listed in shape order). A
    // correct scene decides the order of hits that round to the same double exactly, so there
    // tied means the same real t; a stable scene only compares its doubles.
    bool tied;
};

// A line's answer. need = any: at most one hit, the first proven (not the nearest); nearest: the
// nearest hit and every hit tied with it; all: every hit, in order of t (exact order for a
// correct scene). A line along a surface (the solver's on_surface) adds the interval's first
// point in the range as a hit of kind tangent. error: the line's or the scene's (error_shape
// names the shape, or no_shape for the line); no hit is then given. Only shapes the line comes
// near, within the part of the range still in question, are solved: a solver's refusal of what
// double cannot hold (out_of_range) on a shape beyond the nearest hit, or never near the line, does
// not make the answer an error.
struct SceneAnswer {
    std::vector<SceneHit> hits;
    Error error;
    std::uint32_t error_shape = no_shape;
    std::uint32_t shapes_solved = 0; // how many shapes were solved (the others were culled)
    // Correct scenes: exact comparisons of two shapes' roots, made where hits rounded to the
    // same double (0 for nearly every line).
    std::uint32_t exact_comparisons = 0;
    bool ok() const { return error.ok(); }
};

// An axis-aligned box, lo <= hi in each coordinate (infinite for shapes that are not finite).
struct Box {
    Vec3 lo, hi;
};

class Scene {
  public:
    // Prepares every shape and builds the hierarchy of boxes. A shape that cannot be solved
    // (validate()'s errors) is kept as the scene's error: every query then returns it, naming
    // the shape.
    explicit Scene(const std::vector<Shape>& shapes, SceneSolver solver = SceneSolver::correct,
                   SceneTraversal traversal = SceneTraversal::automatic);
    ~Scene();
    Scene(Scene&&) noexcept;
    Scene& operator=(Scene&&) noexcept;

    std::size_t size() const;
    SceneSolver solver() const;
    SceneTraversal traversal() const;  // the one in use: hierarchy or embree
    Error error() const;               // the first bad shape's error, or none
    std::uint32_t error_shape() const; // that shape, or no_shape
    Box bounds(std::uint32_t i) const; // shape i's box, rounded outward
    int depth() const;                 // the hierarchy's depth (the root alone: 0)

    // The line against every shape, as the query asks (see SceneAnswer). out is overwritten.
    void intersect(const Line& line, Query query, SceneAnswer& out) const;

    // A ray leaving a hit of this scene (linequad/spawn.hpp), off the surface of the hit's shape.
    // Other shapes are not considered: one that touches the hit point is another surface, which
    // the spawned ray may meet at t = 0. A shape index outside the scene: bad_option, "shape".
    SpawnedRay spawn_ray(const SceneHit& from, Vec3 direction) const;

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

} // namespace linequad
