// The tracking audit: rays tracked through a model (linequad/cells.hpp) by a tracker as transport
// codes write it, each step graded against the model's exact track. docs/cells.md says more.
#pragma once

#include "linequad/audit_solver.hpp"
#include "linequad/cells.hpp"

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace linequad {

// One step of a tracker: the distance travelled so far when it crossed into `cell` (-1: it found
// no cell, after its nudge), its position then.
struct TrackerStep {
    double t;      // the sum of its distances: where along the ray it thinks it is
    double length; // this step's own distance
    int cell;      // -1: none found
};
struct TrackerRun {
    int start = -1; // the cell it found at the ray's origin (-1: none)
    std::vector<TrackerStep> steps;
    bool escaped = false; // it found no surface ahead
};

// The tracker OpenMC (src/particle.cpp, src/surface.cpp) and codes like it write: each surface's
// distance by the textbook quadratic (the half-b formula in double, a root with |f| < 1e-12 at
// the particle's position taken as the surface it is on), the nearest of the current cell's
// surfaces (a later one only if nearer by a relative 1e-14), the particle moved by it, the next
// cell searched for among all cells (the crossed surface's side known, others by the sign of f,
// |f| < 1e-12 counting as on the surface and taking the side u points into), then once more
// after a nudge of 1e-8 along u; none found: lost.
// `distances`: the textbook quadratic as OpenMC writes it, or linequad's stable or correct solver
// on the same loop (the surface just crossed posed `coincident`, as the codes pose it): what
// better distances alone change, the rest of the tracker as it is.
enum class TrackerDistances : std::uint8_t { textbook, stable, correct };
inline constexpr int tracker_distances_count = 3;
const char* tracker_distances_name(TrackerDistances d);
TrackerRun textbook_track(const Model& m, Vec3 p, Vec3 u, int max_steps,
                          TrackerDistances distances = TrackerDistances::textbook);
// The same loop with a user's distances: a solver from outside (a plugin's, run in its worker)
// that takes the model's planes and quadrics, asked once a step for the current cell's surfaces
// (the one the particle sits on posed `coincident`, the ray from the particle's position), its
// first hit beyond the particle taken as each one's distance. A refusal, a crash or a case it
// cannot hold: no surface ahead. Where it has a sense entry (ExternalSolver::has_sense), its
// cell search takes each surface's side from it too (the crossed surface's, as the loop's, from
// u against the normal); a failed call leaves that side undecided: no cell found by it.
TrackerRun textbook_track(const Model& m, Vec3 p, Vec3 u, int max_steps,
                          const audit::ExternalSolver& distances);
// Why such a solver cannot give a model's distances (its lines not L0, v and t along v, its
// surfaces not as posed, or a plane or a quadric it does not take); empty when it can.
std::string external_distances_problem(const Model& m, const audit::ExternalSolver& s);

// How a ray's track went against the exact one.
enum class TrackOutcome : std::uint8_t {
    right,      // every step into the right cell (distances graded apart)
    lost,       // found no cell where the exact track is in one
    wrong_cell, // entered a cell the exact track is not in at that step
    missed,     // found no surface ahead while the exact track crosses on
    extra,      // crossed where the exact track does not
    overlap,    // the exact track is in several cells at once (the model's fault)
    undecided,  // the exact track runs along a surface: no step to grade
    stuck,      // more steps than max_steps (a run of steps of length ~0)
    inexact,    // linequad's cells: every cell right, a distance or a surface crossed not the
                // oracle's bits
};
inline constexpr int track_outcome_count = 9;
const char* track_outcome_name(TrackOutcome o);

struct GradedTrack {
    TrackOutcome outcome = TrackOutcome::right;
    int failed_step = -1;      // the step where it went wrong (0: the start)
    int steps = 0;             // steps graded
    double max_t_ulps = 0;     // the largest |t - exact t| over the graded steps, in ulps of t
    int zero_length_steps = 0; // steps shorter than 1e-12, the codes' coincidence tolerance
};
GradedTrack grade_track(const Model::Track& exact, const TrackerRun& run);

// linequad's own tracker (fast/'s Model::track, the correct solver's crossings in exact order)
// graded against the oracle's track (exact::track in robust/): right only where the two are the
// same bit for bit (every step's distance, surfaces and cells, the start, the truncation),
// overlaps and undecided steps included.
GradedTrack grade_linequad_track(const Model::Track& oracle, const Model::Track& fast);

// The trackers the audit grades: the one transport codes write with its own distances, with
// stable's and with correct's (TrackerDistances), and linequad's cells.
inline constexpr int tracker_count = tracker_distances_count + 1;
const char* tracker_name(int k); // "textbook", "+ stable distances", ..., "linequad cells"

// The ray families the audit runs on a model: where its box (the region sources are drawn from)
// is given.
// corner: aimed, from a point of the box, exactly through a point where three of the model's
// axis-aligned planes meet (a lattice cell's corner), or starting there.
// grazing: tangent to one of the model's curved surfaces at a point of it (a line's correctly
// rounded hit there), from up to a box size before it: a ray that skims the surface.
// backscatter: from a point 2^-20 to 2^-50 box sizes past the first surface a generic ray
// crosses, turned back towards it (a particle scattered just after a crossing).
enum class TrackFamily : std::uint8_t {
    generic,
    far_source,
    axis_parallel,
    along_plane,
    corner,
    grazing,
    backscatter
};
inline constexpr int track_family_count = 7;
const char* track_family_name(TrackFamily f);

struct TrackRay {
    Vec3 p, u;
};
// Ray i of a family, reproducible from (seed, i); none where the family does not apply to the
// model (along_plane in a model without planes).
std::optional<TrackRay> track_ray(const Model& m, Vec3 box_lo, Vec3 box_hi, TrackFamily f,
                                  std::uint64_t seed, std::uint64_t i);

struct TrackingTally {
    std::uint64_t rays = 0, steps = 0, zero_length_steps = 0;
    std::array<std::uint64_t, track_outcome_count> outcomes{};
    double max_t_ulps = 0;
    std::string worst;      // the first failing ray, as a query line (query_line)
    std::string worst_what; // how it failed: "extra at step 1"
};

// A ray as a line of `linequad cells MODEL`'s queries, its numbers exact: {"id", "p", "u"}.
std::string query_line(const std::string& id, Vec3 p, Vec3 u);

// Points drawn uniformly in the box and located exactly (each with a direction of its own, which
// decides a point on a surface): those in two cells or more (an overlap, the model's fault) and
// those in none (a gap, or a box reaching beyond the model), OpenMC's --geometry-debug asked at
// points rather than where particles happen to pass.
struct PointSample {
    std::uint64_t points = 0, in_none = 0, undecided = 0;
    // Overlaps by the cells holding the point (indices, in order), how many points each.
    std::vector<std::pair<std::vector<int>, std::uint64_t>> overlaps;
    std::string first_overlap, first_gap; // query lines
};
PointSample sample_points(const Model& m, Vec3 box_lo, Vec3 box_hi, std::uint64_t seed,
                          std::uint64_t n);

} // namespace linequad
