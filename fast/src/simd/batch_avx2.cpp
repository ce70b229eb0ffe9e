// The AVX2 batch kernels: each shape's stable core on four double lanes (stable) or eight float
// lanes (stable32), through the lane steps of simd/stable_lanes.hpp; correct's Newton rung on
// four double lanes (simd/correct_lanes.hpp).
// The lane type first: the kernels' templates find its operations by name.
#include "simd/lanes_avx2.hpp"

#include "simd/correct_lanes.hpp"
#include "simd/stable_lanes.hpp"

namespace linequad::detail {

template <class S>
void stable_x4(const S& s, double shape_extent, const double* const soa[6], std::size_t i,
               Interval range, Query q, LaneBlock<double, 4>& out) {
    stable_lanes<D4>(s, shape_extent, soa, i, range, q, out);
}
template <class S>
void stable32_x8(const S& s, double shape_extent, const float* const soa[6], std::size_t i,
                 Interval range, Query q, LaneBlock<float, 8>& out) {
    stable_lanes<F8>(s, shape_extent, soa, i, range, q, out);
}

#define LINEQUAD_INSTANTIATE_KERNEL(S)                                                             \
    template void stable_x4(const S&, double, const double* const[6], std::size_t, Interval,       \
                            Query, LaneBlock<double, 4>&);                                         \
    template void stable32_x8(const S&, double, const float* const[6], std::size_t, Interval,      \
                              Query, LaneBlock<float, 8>&);
LINEQUAD_FOR_EACH_QUADRIC_SHAPE(LINEQUAD_INSTANTIATE_KERNEL)

template <class S>
void correct_x4(const Prepared<S>& s, int orientation, const double* const soa[6], std::size_t i,
                Interval range, Query q, CorrectBlock<4>& out) {
    correct_lanes<D4>(s, orientation, soa, i, range, q, out);
}
#define LINEQUAD_INSTANTIATE_CORRECT(S)                                                            \
    template void correct_x4(const Prepared<S>&, int, const double* const[6], std::size_t,         \
                             Interval, Query, CorrectBlock<4>&);
LINEQUAD_FOR_EACH_CORRECT_LANES_SHAPE(LINEQUAD_INSTANTIATE_CORRECT)

} // namespace linequad::detail
