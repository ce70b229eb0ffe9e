// The README's example, built against the installed package: a plain shape, then a prepared
// one with a range and a hit test, then a packet of two lines through the batch solver.
#include <linequad/linequad.hpp>

#include <cstdio>

int main() {
    using namespace linequad;
    Cylinder c{{0, 0, 0}, {0, 0, 10}, 5};
    Result r = stable::intersect(c, {{-10, 4, 2}, {1, 0, 0}});
    std::printf("%d hits: %g %g\n", int(r.count), r.hits[0].t, r.hits[1].t);
    Prepared<Cylinder> p = prepare(c);
    Result shadow = correct::intersect(p, {{-10, 4, 2}, {1, 0, 0}, Interval(0, 12.5)}, {Need::any});
    if (!shadow.ok()) std::puts(message(shadow.error()).c_str());
    std::printf("hit test: %d hit at %g (within %g)\n", int(shadow.count), shadow.hits[0].t,
                shadow.hits[0].bound);
    // Eight lines (a full block of lanes on either instruction set), the README's two in turn.
    double x[8], y[8], z[8], vx[8], vy[8], vz[8];
    for (int i = 0; i < 8; ++i)
        x[i] = -10, y[i] = i % 2 ? 1 : 4, z[i] = i % 2 ? 9 : 2, vx[i] = 1, vy[i] = vz[i] = 0;
    Result hits[8];
    Query nearest{Need::nearest, true};
    correct::intersect(p, LineArrays{x, y, z, vx, vy, vz, 8, Range::ray}, nearest, hits);
    // The second line meets the circle x^2 + 1 = 25 first at t = 10 - sqrt(24): the scalar
    // solver's correctly rounded answer.
    Result second = correct::intersect(p, {{-10, 1, 9}, {1, 0, 0}, Range::ray}, nearest);
    std::printf("batch: t = %g, %g\n", hits[0].hits[0].t, hits[1].hits[0].t);
    bool batch_ok = second.count == 1;
    for (int i = 0; i < 8; ++i)
        batch_ok =
            batch_ok && hits[i].count == 1 && hits[i].hits[0].t == (i % 2 ? second.hits[0].t : 7.0);
    return r.count == 2 && r.hits[0].t == 7 && r.hits[1].t == 13 && shadow.count == 1 &&
                   shadow.hits[0].t - 7 <= shadow.hits[0].bound &&
                   7 - shadow.hits[0].t <= shadow.hits[0].bound && batch_ok
               ? 0
               : 1;
}
