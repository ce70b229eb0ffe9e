// How often a ray leaving a hit finds the surface it left again: the usual epsilon against the
// proven offset (linequad/spawn.hpp), graded against geometry the oracle decides.
//
// Two kinds of spawned ray, each with an exact answer. through: from each crossing of a family's
// case, on along the same line: its next crossing is the line's next hit, as the oracle finds it
// on the line itself (none after the last). reflect: off the first crossing of the same line
// with the shape made whole (unbounded, no caps: a convex solid), mirrored in the tangent plane,
// out of the solid: it meets the shape no more.
//
// A method poses the spawned ray from its own solver's hit and answers with that solver. Its
// first hit is a self-hit when the exact answer has none, or when it lies nearer the point left
// than the exact next crossing; the answer is lost when it has no hit but the exact one does.
// Spawns whose parent the method's solver misclassified (another number of hits) are not its
// to grade, and are counted apart.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace linequad::audit {

enum class SpawnMethod : std::uint8_t {
    stable_epsilon, // stable; from its hit point, t >= epsilon / |d| (the usual shadow epsilon)
    correct_at_hit, // correct; from its (correctly rounded) hit point, t >= 0
    stable_spawned, // stable; from spawn_ray of its hit, t >= 0
    correct_spawned // correct; from spawn_ray of its hit, t >= 0
};
inline constexpr int spawn_method_count = 4;
const char* spawn_method_name(SpawnMethod m);

struct SpawnTally {
    std::uint64_t spawns = 0;    // graded
    std::uint64_t self_hits = 0; // the first hit is the crossing left (or a phantom near it)
    std::uint64_t lost = 0;      // no hit where there is one
    std::uint64_t refused = 0;   // spawn_ray refused the direction (along_surface, ...)
    std::uint64_t misparent = 0; // the solver's parent answer differs from the oracle's
};

struct SpawnRow {
    std::string family, kind; // kind: "through" or "reflect"
    SpawnTally methods[spawn_method_count];
};

struct SpawnAuditOptions {
    std::uint64_t cases = 500; // per family and shape
    std::uint64_t seed = 1;
    double epsilon = 1e-4; // the distance stable_epsilon skips
};

std::vector<SpawnRow> run_spawn_audit(const SpawnAuditOptions& o);
std::string spawn_report_markdown(const std::vector<SpawnRow>& rows, const SpawnAuditOptions& o,
                                  const std::string& command);

} // namespace linequad::audit
