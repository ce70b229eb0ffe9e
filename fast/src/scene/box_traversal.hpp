// Another traversal of a scene's bounded boxes than its own hierarchy: Embree's BVH, which lives
// in a library of its own (linequad::embree, fast/src/scene/embree_traversal.cpp) so that
// linequad::fast needs nothing but the C++ standard library. Linking that library registers it;
// a scene then traverses with it where SceneTraversal allows.
#pragma once

#include "linequad/scene.hpp"

#include <cstdint>
#include <memory>
#include <vector>

namespace linequad::detail {

class BoxTraversal {
  public:
    // What the scene does with a shape the line may come near: solves it, and returns the end of
    // the range still in question (-inf: stop, the query has its answer).
    using Visit = double (*)(void* data, std::uint32_t shape);
    virtual ~BoxTraversal() = default;
    // Calls visit for the bounded shapes the line may come near over [t0, end], as the
    // hierarchy's traversal does; false (nothing visited) when it cannot take this line, and the
    // scene must traverse its own way.
    virtual bool traverse(const Line& line, double end, bool any, Visit visit,
                          void* data) const = 0;
};

// A traversal over the boxes of the shapes ids (boxes indexed by shape), or null when it cannot
// hold them.
using BoxTraversalMaker = std::unique_ptr<BoxTraversal> (*)(const std::vector<Box>& boxes,
                                                            const std::vector<std::uint32_t>& ids);

// Called once, by the Embree component's registration when a program links it.
void register_embree(BoxTraversalMaker make);

} // namespace linequad::detail
