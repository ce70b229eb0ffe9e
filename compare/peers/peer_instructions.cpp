// Solves N posed generic cases with one peer library, for counting instructions under callgrind
// (scripts/peers.sh runs it twice, with N and with 0, and prints the difference over N). The
// cases are built and posed before any is solved, the same for every N, so only the solves
// differ between the two runs.
//   linequad_peer_instructions PEER SHAPE N
#include "peers/peers.hpp"

#include "linequad/families.hpp"

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

int main(int argc, char** argv) {
    using namespace linequad;
    if (argc != 4) {
        std::fprintf(stderr, "usage: %s PEER SHAPE N (N <= 4096)\n", argv[0]);
        return 2;
    }
    const audit::ExternalSolver* peer = nullptr;
    for (const audit::ExternalSolver& p : peers::solvers())
        if (p.name == argv[1]) peer = &p;
    int shape = shape_named(argv[2]);
    long n = std::atol(argv[3]);
    if (!peer || shape < 0 || n < 0 || n > 4096) {
        std::fprintf(stderr, "no peer '%s' or shape '%s' built in, or N out of range\n", argv[1],
                     argv[2]);
        return 2;
    }
    // Generic segments on axis-aligned frames (every peer takes segments from t0 = 0), posed as
    // the peer takes them; those it cannot pose are left out.
    std::vector<Case> cases;
    for (std::uint64_t i = 0; cases.size() < 4096 && i < 16384; ++i) {
        Case c =
            make_case(Family::generic, shape, Range::segment, 1, i, Frames::axis, peer->precision);
        if (std::optional<Case> p = audit::posed_for(*peer, c)) cases.push_back(*p);
    }
    if (cases.empty() || !peer->takes(cases[0].shape)) {
        std::fprintf(stderr, "%s cannot take %s\n", argv[1], argv[2]);
        return 2;
    }
    audit::CrashGuard guard;
    unsigned hits = 0;
    for (long i = 0; i < n; ++i) {
        const Case& c = cases[std::size_t(i) % cases.size()];
        std::optional<Result> r = (*peer)(c.shape, c.line);
        hits += r && r->ok() ? r->count : 0;
    }
    std::printf("%u\n", hits); // keeps the solves observable
    return 0;
}
