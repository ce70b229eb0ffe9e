// The README's example, built against the installed package: a plain shape, then a prepared
// one with a range and a hit test.
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
    return r.count == 2 && r.hits[0].t == 7 && r.hits[1].t == 13 && shadow.count == 1 &&
                   shadow.hits[0].t - 7 <= shadow.hits[0].bound &&
                   7 - shadow.hits[0].t <= shadow.hits[0].bound
               ? 0
               : 1;
}
