// The scene's traversal with Embree (Debian libembree-dev): linequad::embree, a library of its
// own, so that linequad::fast needs nothing but the C++ standard library. Linking it registers
// the traversal with the scene (a program that does not link it gets the scene's own hierarchy).
#include "scene/box_traversal.hpp"
#include "scene/slab.hpp"

#include <embree3/rtcore.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

namespace linequad::detail {

namespace {

// Embree's BVH over the bounded shapes' boxes, as user geometry whose callback hands each shape
// to the scene's visit. Embree traverses with a float ray and keeps only boxes within 2^60 of
// its origin, so the boxes are moved to a local frame, x_local = 2^m (x - c) around their centre
// c with 2^m fitting the scene into [-2, 2], and widened by delta (in world units), which covers
// how far that ray strays from the double line inside the scene's box G (every bounded box lies
// in G). The line is clipped to G (the slab test: [ta, tb] holds all of it in G) and restarted
// there as the float ray o + s d:
//   O = fl(fl(L0 + ta v) - c) (an fma, then one subtraction) is within 2^-52 (|c| + R) of the
//   exact point, R the largest |corner of G - c|, and o = float(2^m O) within 2^-24 R more;
//   d = float(2^k v), 2^k |v|_inf in [1, 2), is within 2^-24 |2^k v|_inf of 2^k v in each
//   component, and within G the line moves (t - ta) |v|_inf <= W along it: 2^-24 W more.
// So every point of the line in G is within 2^-24 (R + W) + 2^-51 (|c| + R) of the float ray's
// point at s = (t - ta) 2^(m - k) (plus float's and double's subnormal steps); delta doubles
// that, and Embree's robust traversal tests each of its boxes conservatively for its own ray. A
// shape's hits at t <= end are then all found: the callback narrows tfar to end's s, rounded up.
class EmbreeBoxes final : public BoxTraversal {
  public:
    // Nothing (ok() false) if Embree fails or G is not finite.
    EmbreeBoxes(const std::vector<Box>& boxes, const std::vector<std::uint32_t>& ids) : ids_(ids) {
        if (ids.empty()) return;
        Box all = boxes[ids[0]];
        for (std::uint32_t i : ids)
            all = merged(all, boxes[i]);
        global_ = all;
        centre_ = 0.5 * all.lo + 0.5 * all.hi; // any point will do; this one keeps R small
        double R = 0, W = 0;
        for (int i = 0; i < 3; ++i) {
            R = std::max({R, std::fabs(all.lo[i] - centre_[i]), std::fabs(all.hi[i] - centre_[i])});
            W = std::max(W, all.hi[i] - all.lo[i]);
        }
        delta_ =
            2 * (0x1p-24 * (R + W) + 0x1p-51 * (max_abs(centre_) + R)) * (1 + 0x1p-20) + 0x1p-1060;
        reach_ = R + W + 2 * delta_; // no point of the float ray that matters lies farther out
        if (!(reach_ > 0 && reach_ < 0x1p1000)) return;
        m_ = -std::ilogb(reach_); // 2^m reach in [1, 2)
        local_.reserve(ids.size());
        for (std::uint32_t i : ids) {
            const Box& b = boxes[i];
            RTCBounds f{};
            f.lower_x = down(local(b.lo.x - centre_.x - delta_));
            f.lower_y = down(local(b.lo.y - centre_.y - delta_));
            f.lower_z = down(local(b.lo.z - centre_.z - delta_));
            f.upper_x = up(local(b.hi.x - centre_.x + delta_));
            f.upper_y = up(local(b.hi.y - centre_.y + delta_));
            f.upper_z = up(local(b.hi.z - centre_.z + delta_));
            local_.push_back(f);
        }
        RTCDevice device = shared_device();
        if (!device) return;
        scene_ = rtcNewScene(device);
        rtcSetSceneFlags(scene_, RTC_SCENE_FLAG_ROBUST);
        RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_USER);
        rtcSetGeometryUserPrimitiveCount(geom, unsigned(ids.size()));
        rtcSetGeometryUserData(geom, this);
        rtcSetGeometryBoundsFunction(geom, &EmbreeBoxes::bounds, this);
        rtcSetGeometryIntersectFunction(geom, &EmbreeBoxes::intersect);
        rtcSetGeometryOccludedFunction(geom, &EmbreeBoxes::occluded);
        rtcCommitGeometry(geom);
        rtcAttachGeometry(scene_, geom);
        rtcReleaseGeometry(geom);
        rtcCommitScene(scene_);
        ok_ = rtcGetDeviceError(device) == RTC_ERROR_NONE;
    }
    ~EmbreeBoxes() {
        if (scene_) rtcReleaseScene(scene_);
    }
    EmbreeBoxes(const EmbreeBoxes&) = delete;
    EmbreeBoxes& operator=(const EmbreeBoxes&) = delete;
    bool ok() const { return ok_; }

    // Calls visit(data, shape) for the bounded shapes the line may come near over [t0, end], as
    // the hierarchy's traversal does; false (nothing visited) when the line cannot be posed as a
    // float ray here, and the caller must traverse its own way.
    bool traverse(const Line& line, double end, bool any, Visit visit, void* data) const override {
        double ta = line.range.t0, tb = end;
        if (!slab(global_, SlabLine(line), ta, tb)) return true; // the line misses every box
        if (!std::isfinite(ta) || !std::isfinite(tb)) return false;
        int k = -std::ilogb(max_abs(line.v)); // 2^k |v|_inf in [1, 2)
        Vec3 O{std::fma(ta, line.v.x, line.L0.x) - centre_.x,
               std::fma(ta, line.v.y, line.L0.y) - centre_.y,
               std::fma(ta, line.v.z, line.L0.z) - centre_.z};
        if (!(max_abs(O) <= reach_)) return false;
        Query q;
        rtcInitIntersectContext(&q.context);
        q.self = this, q.visit = visit, q.data = data, q.ta = ta, q.e = m_ - k;
        RTCRayHit rh{};
        rh.ray.org_x = float(local(O.x)), rh.ray.org_y = float(local(O.y));
        rh.ray.org_z = float(local(O.z));
        rh.ray.dir_x = float(std::ldexp(line.v.x, k)),
        rh.ray.dir_y = float(std::ldexp(line.v.y, k));
        rh.ray.dir_z = float(std::ldexp(line.v.z, k));
        rh.ray.tnear = 0, rh.ray.tfar = q.s_after(tb), rh.ray.mask = ~0u;
        rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        if (any)
            rtcOccluded1(scene_, &q.context, &rh.ray);
        else
            rtcIntersect1(scene_, &q.context, &rh);
        return true;
    }

  private:
    // The query's state, after Embree's context (which the callbacks are handed).
    struct Query {
        RTCIntersectContext context;
        const EmbreeBoxes* self;
        Visit visit;
        void* data;
        double ta;
        int e; // the ray's point at s stands for the line's at t = ta + s 2^-e
        // The float ray's s for t = end, rounded up: at least (end - ta) 2^e.
        float s_after(double end) const {
            if (end == std::numeric_limits<double>::infinity()) return INFINITY;
            double d = end - ta;
            d += std::fabs(d) * 0x1p-50 + 0x1p-1074; // the subtraction's rounding
            return up(std::ldexp(d, e));
        }
        float on(std::uint32_t prim) const {
            double end = visit(data, self->ids_[prim]);
            return end == -std::numeric_limits<double>::infinity() ? -INFINITY : s_after(end);
        }
    };

    double local(double world_offset) const { return std::ldexp(world_offset, m_); }

    // One device for every scene, made once (a device per scene would cost more than building a
    // small scene's BVH); never released, so that no scene can outlive it. A single build thread:
    // the scene is built on the caller's thread, as the hierarchy is.
    static RTCDevice shared_device() {
        static RTCDevice d = rtcNewDevice("threads=1");
        return d;
    }
    // Rounded outward to float, and never to a subnormal (Embree may run with denormals read as
    // zero, which must not move a bound inward).
    static float down(double x) {
        float f = float(x);
        if (double(f) > x) f = std::nextafter(f, -INFINITY);
        if (std::fabs(f) < std::numeric_limits<float>::min() && f != 0)
            f = f > 0 ? 0.0f : -std::numeric_limits<float>::min();
        return f;
    }
    static float up(double x) {
        float f = float(x);
        if (double(f) < x) f = std::nextafter(f, INFINITY);
        if (std::fabs(f) < std::numeric_limits<float>::min() && f != 0)
            f = f < 0 ? 0.0f : std::numeric_limits<float>::min();
        return f;
    }
    static void bounds(const RTCBoundsFunctionArguments* args) {
        *args->bounds_o =
            static_cast<const EmbreeBoxes*>(args->geometryUserPtr)->local_[args->primID];
    }
    static void intersect(const RTCIntersectFunctionNArguments* args) {
        if (!args->valid[0]) return;
        const Query& q = *reinterpret_cast<const Query*>(args->context);
        float& tfar = RTCRayN_tfar(RTCRayHitN_RayN(args->rayhit, args->N), args->N, 0);
        tfar = std::min(tfar, q.on(args->primID));
    }
    static void occluded(const RTCOccludedFunctionNArguments* args) {
        if (!args->valid[0]) return;
        const Query& q = *reinterpret_cast<const Query*>(args->context);
        float& tfar = RTCRayN_tfar(args->ray, args->N, 0);
        tfar = std::min(tfar, q.on(args->primID)); // -inf: a hit, and Embree stops
    }

    std::vector<std::uint32_t> ids_; // the shape of each primitive
    std::vector<RTCBounds> local_;
    Box global_{};
    Vec3 centre_{};
    double delta_ = 0, reach_ = 0;
    int m_ = 0;
    RTCScene scene_ = nullptr;
    bool ok_ = false;
};

std::unique_ptr<BoxTraversal> make_embree_boxes(const std::vector<Box>& boxes,
                                                const std::vector<std::uint32_t>& ids) {
    auto made = std::make_unique<EmbreeBoxes>(boxes, ids);
    if (!made->ok()) return nullptr;
    return made;
}

} // namespace

} // namespace linequad::detail

// The registration, run when this object file is linked: the embree target asks the linker for
// this symbol (--undefined), so that a static library's member is not left out unread.
extern "C" {
extern const int linequad_embree_traversal;
const int linequad_embree_traversal =
    (linequad::detail::register_embree(&linequad::detail::make_embree_boxes), 1);
}
