// The shapes by their index in linequad::Shape, for code that is handed an index or a name (the
// case format, the families, the audit's groups): each call reaches the shape's own type.
#pragma once

#include "shapes/all.hpp"

#include <cstddef>
#include <string_view>
#include <variant>

namespace linequad {

template <class S>
struct ShapeTag {
    using type = S;
};

inline constexpr std::size_t shape_count = std::variant_size_v<Shape>;

// f(ShapeTag<S>{}) for the alternative S of Shape at `index` (index < shape_count).
template <class F, std::size_t I = 0>
decltype(auto) with_shape_type(std::size_t index, F&& f) {
    using S = std::variant_alternative_t<I, Shape>;
    if constexpr (I + 1 < shape_count) {
        if (index != I) return with_shape_type<F, I + 1>(index, std::forward<F>(f));
    }
    return f(ShapeTag<S>{});
}

inline const char* shape_name_at(std::size_t index) {
    return with_shape_type(
        index, [](auto tag) { return detail::ShapeTraits<typename decltype(tag)::type>::name; });
}

// The shape closed by its discs (as a collision library holds it); false when it cannot be (not
// finite). A closed solid by definition is closed already.
template <class S>
bool close_with_discs(S& s) {
    if constexpr (has_extent_options<S>) {
        if (!s.finite) return false;
        s.caps = true;
    }
    return true;
}
inline bool close_with_discs(Shape& s) {
    return std::visit([](auto& x) { return close_with_discs(x); }, s);
}

// The whole quadric the shape lies on (not finite, no caps) with `nappes` nappes for a cone; a
// closed solid by definition is whole already.
template <class S>
void make_whole(S& s, int nappes) {
    if constexpr (has_extent_options<S>) s.finite = false, s.caps = false;
    if constexpr (has_nappes<S>) s.nappes = nappes;
}
inline void make_whole(Shape& s, int nappes) {
    std::visit([&](auto& x) { make_whole(x, nappes); }, s);
}

// The index of the shape named `name`, or shape_count.
inline std::size_t shape_index(std::string_view name) {
    for (std::size_t i = 0; i < shape_count; ++i)
        if (name == shape_name_at(i)) return i;
    return shape_count;
}

} // namespace linequad
