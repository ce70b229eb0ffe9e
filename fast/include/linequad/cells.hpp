// Cells and models: the geometry particle-transport codes (OpenMC, MCNP, Celeritas' ORANGE)
// track particles through. A model is a set of surfaces with ids and of cells, each a region
// over the surfaces' signed half-spaces; the queries are the ones a tracker asks, answered
// exactly: which cells hold a point, and from a point moving along u inside a cell, how far to its
// boundary, through which surfaces, into which cells. docs/cells.md says more.
#pragma once

#include "linequad/result.hpp"
#include "linequad/shapes.hpp"
#include "linequad/surfaces.hpp"
#include "linequad/vec3.hpp"

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace linequad {

// The surfaces a model is built from: planes and general quadrics, and the sphere and the
// cylinder along a coordinate axis as OpenMC defines them from their centre and radius (a
// Cylinder with `finite` false and no caps, C and H apart on one axis): their f,
// sum (p_i - c_i)^2 - r^2 over the axes across, is exact for any doubles, where its expansion
// into general-quadric coefficients (c_i^2 - r^2) is seldom a double.
using SurfaceShape = std::variant<Plane, Quadric, Sphere, Cylinder>;

// The sense of a point against such a sphere or cylinder (negative inside), as sense() answers it
// for planes and quadrics (linequad/surfaces.hpp); check_sense also refuses a cylinder that is
// finite, capped or not along a coordinate axis (bad_option), and a radius that is not positive.
SenseResult sense(const Sphere& s, Vec3 p);
SenseResult sense(const Cylinder& s, Vec3 p);
SenseResult sense(const Sphere& s, Vec3 p, Vec3 u);
SenseResult sense(const Cylinder& s, Vec3 p, Vec3 u);
Error check_sense(const Sphere& s, Vec3 p, const Vec3* u = nullptr);
Error check_sense(const Cylinder& s, Vec3 p, const Vec3* u = nullptr);

// A region in OpenMC's syntax over surface ids: "-1 2 ~(3 | -4)". A signed id is a half-space
// (-7: f < 0, the negative sense; 7 or +7: f > 0), juxtaposition is intersection, `|` union, `~`
// complement, with parentheses; complement binds tightest, then intersection, then union.
class Region {
  public:
    enum class Op : std::uint8_t { half_space, intersection, union_, complement };
    struct Token {
        Op op;
        bool positive = false; // half_space: the sense, f > 0
        std::int64_t id = 0;   // half_space: the surface's id as written
        int surface = -1;      // half_space: its index in the model, once resolved
    };

    // The region parsed; on a malformed text, none, and `error` says what and at which column
    // (counted from 1).
    static std::optional<Region> parse(std::string_view text, std::string& error);

    // Postfix: each operator after its operands.
    const std::vector<Token>& tokens() const { return tokens_; }
    std::vector<Token>& tokens() { return tokens_; }

    // Whether a point lies in the region, from the sense of each surface there (indexed by the
    // model's surface index; Sense::on where the sense is not decided: the point moves along
    // that surface). Three-valued: nullopt where the answer rests on an undecided sense.
    std::optional<bool> contains(const std::vector<Sense>& senses) const;

  private:
    std::vector<Token> tokens_;
};

class Model {
  public:
    struct Surface {
        std::int64_t id;
        SurfaceShape shape;
    };
    struct Cell {
        std::int64_t id;
        std::string name;
        Region region;
    };
    // A cell as written: its region still text.
    struct CellSource {
        std::int64_t id;
        std::string name;
        std::string region;
    };

    // The model, checked: every surface valid (no NaN or infinite coefficient, not all zero),
    // surface and cell ids unique, every region well formed and naming only the model's
    // surfaces, at least one cell. On the first problem, none, and `error` names it (the surface
    // or cell by id, the column in the region).
    static std::optional<Model> build(std::vector<Surface> surfaces,
                                      const std::vector<CellSource>& cells, std::string& error);

    const std::vector<Surface>& surfaces() const { return surfaces_; }
    const std::vector<Cell>& cells() const { return cells_; }
    // The index of the cell or surface with this id, or -1.
    int cell_index(std::int64_t id) const;
    int surface_index(std::int64_t id) const;

    // Where a particle at p moving along u is: the cells whose region holds p, a point on a
    // surface taking the side u points into (Sense with a direction, linequad/surfaces.hpp).
    // Several cells: an overlap; none: a gap, or outside the model. `undecided`: cells whose
    // membership rests on a surface the particle moves along (its line lies in the surface).
    struct Location {
        std::vector<int> cells, undecided;
        Error error; // p or u not finite, u zero
    };
    Location locate(Vec3 p, Vec3 u) const;

    // From p moving along u inside cell `cell` (an index): where the particle leaves it. Every
    // sense is exact along the ray; each surface's crossings come from the correct solver, and
    // crossings whose correctly rounded t is the same double are ordered exactly.
    enum class Exit : std::uint8_t {
        leaves,     // at t: the first crossing after which p + t u is no longer in the cell
        escapes,    // the ray never leaves it (an unbounded cell)
        along,      // the ray lies in a surface the cell's region rests on: no side to take
        not_inside, // p, moving along u, is not in the cell
        error,      // bad p or u, or no such cell
    };
    struct Crossing {
        Exit exit = Exit::error;
        double t = 0;              // leaves: the distance in units of |u|, correctly rounded
        std::vector<int> surfaces; // leaves: every surface crossed at that point (several: a tie)
        std::vector<int> entered;  // leaves: the cells holding the points just beyond
        std::vector<int> undecided_entered; // leaves: cells whose membership there is undecided
        Error error;
    };
    Crossing next_crossing(int cell, Vec3 p, Vec3 u) const;

    // The exact reference a tracker is graded against: every point along the ray p + t u
    // (t > 0) where the set of cells holding it changes, in order, after the cells at p itself;
    // at most max_steps of them (`truncated` if more remain).
    struct Step {
        double t;                   // correctly rounded
        std::vector<int> surfaces;  // crossed there (several: a tie)
        std::vector<int> cells;     // holding the points just beyond
        std::vector<int> undecided; // whose membership is undecided there
    };
    struct Track {
        std::vector<int> start, start_undecided;
        std::vector<Step> steps;
        bool truncated = false;
        Error error;
    };
    Track track(Vec3 p, Vec3 u, int max_steps) const;

  private:
    std::vector<Surface> surfaces_;
    std::vector<Cell> cells_;
    // Each surface's sense at p moving along u; none (error set) for bad inputs.
    std::optional<std::vector<Sense>> senses_at(Vec3 p, Vec3 u, Error& error) const;
    template <class At>
    bool walk(Vec3 p, Vec3 u, std::vector<Sense>& senses, Error& error, At at) const;
    void cells_holding(const std::vector<Sense>& senses, std::vector<int>& in,
                       std::vector<int>& undecided) const;
};

const char* exit_name(Model::Exit e); // "leaves", "escapes", "along", "not_inside", "error"

} // namespace linequad
