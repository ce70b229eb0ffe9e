// Tracks N rays of a model's generic family with one tracker, for counting instructions under
// callgrind: bench/tracking_instructions.sh runs it tracking and not tracking the same rays, and
// divides the difference by the steps the tracker took (printed).
//   linequad_tracking_instructions MODEL TRACKER N TRACK
// TRACKER: textbook | stable | correct (the tracker transport codes write, with its own distances
// or linequad's: compare/src/run/tracking_audit.cpp) | exact (Model::track, linequad's correct
// tracker); TRACK: 1 to track, 0 to build the model and the rays only.
#include "linequad/case_io.hpp"
#include "linequad/tracking_audit.hpp"

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

using namespace linequad;

int main(int argc, char** argv) {
    if (argc != 5) {
        std::fprintf(stderr, "usage: %s MODEL textbook|stable|correct|exact N TRACK(0|1)\n",
                     argv[0]);
        return 2;
    }
    std::ifstream in(argv[1], std::ios::binary);
    std::stringstream text;
    text << in.rdbuf();
    ModelFile file;
    std::string why;
    if (!in || !parse_model(text.str(), &file, &why) || !file.box) {
        std::fprintf(stderr, "%s: %s\n", argv[1], why.empty() ? "no box" : why.c_str());
        return 2;
    }
    std::optional<Model> m = Model::build(std::move(file.surfaces), file.cells, why);
    if (!m) {
        std::fprintf(stderr, "%s: %s\n", argv[1], why.c_str());
        return 2;
    }
    std::string tracker = argv[2];
    long n = std::atol(argv[3]);
    bool track = std::atoi(argv[4]) != 0;
    std::vector<TrackRay> rays;
    for (long i = 0; i < n; ++i)
        if (auto r = track_ray(*m, (*file.box)[0], (*file.box)[1], TrackFamily::generic, 1,
                               std::uint64_t(i)))
            rays.push_back(*r);
    long steps = 0; // each tracker's own: its crossings, the exact tracker's cell changes
    if (track) {
        for (const TrackRay& r : rays) {
            if (tracker == "exact") {
                steps += long(m->track(r.p, r.u, 1000).steps.size());
                continue;
            }
            TrackerDistances d = tracker == "stable"    ? TrackerDistances::stable
                                 : tracker == "correct" ? TrackerDistances::correct
                                                        : TrackerDistances::textbook;
            steps += long(textbook_track(*m, r.p, r.u, 1000, d).steps.size());
        }
    }
    std::printf("%ld\n", steps);
    return 0;
}
