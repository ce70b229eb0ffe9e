// Scenes in the audit: where many shapes along one line break a renderer's answer. Touching and
// nested cylinders, coaxial shapes, shapes sharing a rim, grids of thin rods far from the origin
// and rays leaving hits; each scene a pure function of (family, seed, index), built so
// that its contacts are exact (integer rotations, dyadic radii), and graded line by line
// against the exact oracle's scene (linequad::exact::intersect over every shape, hits in the
// order of their exact roots).
//
// The correct scene must equal the oracle bit for bit (every hit, its shape, its tie); the
// stable scene is graded as a renderer sees it: the nearest hit on another shape, missed,
// invented, or off in t, and the hits in another order. Each family also says how often a correct
// scene needed an exact comparison of roots (the price of its exact order).
#pragma once

#include "linequad/audit.hpp"
#include "linequad/case_io.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace linequad::audit {

enum class SceneFamily : std::uint8_t {
    touching,   // cylinders whose lateral surfaces touch along a line; lines through the contact
    nested,     // coaxial closed cylinders 2^-k apart in radius and height, and a frustum that
                // is the outer cylinder again
    coaxial,    // a cylinder, a frustum and a cone on one axis, sharing the base rim and disc
    shared_rim, // closed cylinders and a frustum stacked end to end: shared discs and rims
    far_grid,   // a grid of thin rods 2^k from the origin, crossed, grazed and hit through axes
    spawned,    // the other families' scenes, with rays leaving their nearest hits on along the
                // line, from spawn_ray's origin
    from_hit,   // the same rays from the hit point itself (a renderer's ray with no offset)
};
inline constexpr int scene_family_count = 7;
const char* scene_family_name(SceneFamily f);
bool parse_scene_family(const std::string& name, SceneFamily* f);

// A scene as written in the case format: its header, shapes and lines.
struct SceneCase {
    SceneHeader header;
    std::vector<SceneShape> shapes;
    std::vector<SceneLine> lines;
    std::vector<Shape> shape_list() const;
};

// Scene `index` of a family, with `lines` lines. k (in the header) is the family's difficulty:
// the offset exponent (touching, far_grid), the gap exponent (nested), 1 for rotated axes
// (coaxial, shared_rim), or the family whose scene the rays leave (spawned, from_hit).
SceneCase make_scene(SceneFamily f, std::uint64_t seed, std::uint64_t index, int lines);

// Every scene of a file in the case format (linequad/case_io.hpp); a single case, a malformed
// record or a scene with a repeated shape id is an error naming its line.
std::vector<SceneCase> read_scenes(const std::string& path, std::size_t max_line_bytes);
// The same from text (its lines); errors name the line.
std::vector<SceneCase> scenes_from_text(std::string_view text);
// Scenes in the case format, a record a line: what read_scenes reads back as they are.
std::string format_scenes(const std::vector<SceneCase>& scenes);

struct SceneTally {
    std::uint64_t scenes = 0, shapes = 0, lines = 0;
    std::uint64_t hits = 0;      // the oracle's hits (need all)
    std::uint64_t tie_lines = 0; // lines with two shapes hit at exactly one t
    std::uint64_t solved = 0;    // shapes solved by the correct scene (need nearest), summed
    // correct scene against the oracle, bit for bit
    std::uint64_t correct_differs_all = 0, correct_differs_nearest = 0, correct_refused = 0;
    std::uint64_t refined_all = 0, refined_nearest = 0; // lines with an exact comparison
    std::uint64_t comparisons_all = 0;
    // the correct scene traversing Embree's BVH (when built with it): lines graded, and those
    // whose answer (all or nearest) is not the oracle's
    std::uint64_t embree_lines = 0, embree_differs = 0;
    // stable scene, need nearest: its hit stands for (is nearest in t to) an exact hit of its
    // shape that is not among the nearest, no hit where there is one, a hit where there is none;
    // need all: another number of hits, or the same number on shapes in another order (beyond
    // exact ties)
    std::uint64_t stable_wrong = 0, stable_missed = 0, stable_phantom = 0;
    std::uint64_t stable_count_differs = 0, stable_misordered = 0, stable_refused = 0;
    // The nearest hit's position along the line, where the hit is right: |t - t_exact| |v| in
    // ulps of the larger of |L0| and the exact point (its coordinates' own rounding).
    Histogram stable_error;
    std::uint64_t stable_max_ulps = 0;
};

struct SceneRow {
    std::string family;
    SceneTally tally;
};

struct SceneAuditOptions {
    std::uint64_t scenes = 40; // per family
    int lines = 25;            // per scene
    std::uint64_t seed = 1;
    std::vector<SceneFamily> families; // empty: every family
    std::string cases_file;            // grade these scenes instead of the families'
    std::string write_cases;           // write the scenes graded here, in the case format
    std::size_t max_line_bytes = std::size_t(1) << 24;
};

// Grades every scene; rows by family in the families' order (a file's by its scenes' "family",
// "file" where none is given).
std::vector<SceneRow> run_scene_audit(const SceneAuditOptions& o);
std::string scene_report_markdown(const std::vector<SceneRow>& rows, const SceneAuditOptions& o,
                                  const std::string& command);

} // namespace linequad::audit
