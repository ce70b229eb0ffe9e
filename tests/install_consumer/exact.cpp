#include <linequad/exact.hpp>

#include <cstdio>

int main() {
    linequad::Cylinder c{{0, 0, 0}, {0, 0, 10}, 5};
    linequad::Result r = linequad::exact::intersect(c, {{-10, 5, 2}, {1, 0, 0}});
    std::printf("%d hit, tangent: %d\n", r.count,
                int(r.hits[0].kind == linequad::HitKind::tangent));
    return r.count == 1 && r.hits[0].kind == linequad::HitKind::tangent && r.hits[0].t == 10 ? 0
                                                                                             : 1;
}
