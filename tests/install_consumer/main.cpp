#include <linequad/linequad.hpp>

#include <cstdio>

int main() {
    linequad::Cylinder c{{0, 0, 0}, {0, 0, 10}, 5};
    linequad::Result r = linequad::stable::intersect(c, {{-10, 4, 2}, {1, 0, 0}});
    std::printf("%d hits: %g %g\n", r.count, r.hits[0].t, r.hits[1].t);
    return r.count == 2 && r.hits[0].t == 7 && r.hits[1].t == 13 ? 0 : 1;
}
