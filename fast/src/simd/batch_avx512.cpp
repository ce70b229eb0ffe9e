// The AVX-512 batch kernel: each shape's stable core on eight double lanes (stable), through the
// lane steps of simd/stable_lanes.hpp.
#include "simd/lanes_avx512.hpp"
#include "simd/stable_lanes.hpp"

namespace linequad::detail {

template <class S>
void stable_x8(const S& s, double shape_extent, const double* const soa[6], std::size_t i,
               Interval range, Query q, LaneBlock<double, 8>& out) {
    stable_lanes<D8>(s, shape_extent, soa, i, range, q, out);
}

#define LINEQUAD_INSTANTIATE_KERNEL(S)                                                             \
    template void stable_x8(const S&, double, const double* const[6], std::size_t, Interval,       \
                            Query, LaneBlock<double, 8>&);
LINEQUAD_FOR_EACH_SHAPE(LINEQUAD_INSTANTIATE_KERNEL)

} // namespace linequad::detail
