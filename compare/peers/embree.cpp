// Embree 3.13: a ray against one cone linear curve (RTC_GEOMETRY_TYPE_CONE_LINEAR_CURVE), the
// frustum between two discs, with its end discs (no neighbour flags) or open (both flags set);
// one sphere point (RTC_GEOMETRY_TYPE_SPHERE_POINT); one round linear curve segment with equal
// radii (RTC_GEOMETRY_TYPE_ROUND_LINEAR_CURVE), a capsule.
#include "peers/peers.hpp"

#include <embree3/rtcore.h>

#include <cmath>
#include <cstring>

namespace linequad::peers {

namespace {

// One device and one scene holding one primitive of one type, whose vertices each case rewrites
// and commits: a linear curve segment (cone or round), or a sphere point.
class OnePrimitive {
  public:
    explicit OnePrimitive(RTCGeometryType type) : curve_(type != RTC_GEOMETRY_TYPE_SPHERE_POINT) {
        device_ = rtcNewDevice("threads=1");
        scene_ = rtcNewScene(device_);
        rtcSetSceneFlags(scene_, RTC_SCENE_FLAG_ROBUST);
        geom_ = rtcNewGeometry(device_, type);
        int vertices = curve_ ? 4 : 1;
        vertices_ = static_cast<float*>(rtcSetNewGeometryBuffer(
            geom_, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4, 4 * sizeof(float), vertices));
        if (curve_) {
            auto* index = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
                geom_, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT, sizeof(unsigned), 1));
            index[0] = 1; // the segment from vertex 1 to 2; 0 and 3 stand for neighbours
            flags_ = static_cast<unsigned char*>(rtcSetNewGeometryBuffer(
                geom_, RTC_BUFFER_TYPE_FLAGS, 0, RTC_FORMAT_UCHAR, sizeof(unsigned char), 1));
        }
        rtcAttachGeometry(scene_, geom_);
    }
    ~OnePrimitive() {
        rtcReleaseGeometry(geom_);
        rtcReleaseScene(scene_);
        rtcReleaseDevice(device_);
    }

    // The nearest hit of the posed ray with the segment (p0, r0)-(p1, r1); every input a float.
    // closed: no neighbour flags (a cone curve's ends then are discs, a round curve's spheres).
    std::optional<Result> nearest(Vec3 p0, double r0, Vec3 p1, double r1, bool closed,
                                  const Line& l) {
        Vec3 d = p1 - p0;
        const Vec3 v[4] = {p0 - d, p0, p1, p1 + d};
        const double r[4] = {r0, r0, r1, r1};
        for (int i = 0; i < 4; ++i)
            put(i, v[i], r[i]);
        flags_[0] = closed ? 0 : (RTC_CURVE_FLAG_NEIGHBOR_LEFT | RTC_CURVE_FLAG_NEIGHBOR_RIGHT);
        return trace(l);
    }
    // The nearest hit of the posed ray with the sphere point (C, r).
    std::optional<Result> nearest(Vec3 C, double r, const Line& l) {
        put(0, C, r);
        return trace(l);
    }

  private:
    void put(int i, Vec3 p, double r) {
        vertices_[4 * i + 0] = float(p.x), vertices_[4 * i + 1] = float(p.y);
        vertices_[4 * i + 2] = float(p.z), vertices_[4 * i + 3] = float(r);
    }
    Result trace(const Line& l) {
        rtcCommitGeometry(geom_);
        rtcCommitScene(scene_);
        RTCIntersectContext context;
        rtcInitIntersectContext(&context);
        RTCRayHit rh;
        std::memset(&rh, 0, sizeof rh);
        rh.ray.org_x = float(l.L0.x), rh.ray.org_y = float(l.L0.y), rh.ray.org_z = float(l.L0.z);
        rh.ray.dir_x = float(l.v.x), rh.ray.dir_y = float(l.v.y), rh.ray.dir_z = float(l.v.z);
        rh.ray.tnear = float(l.range.t0), rh.ray.tfar = float(l.range.t1);
        rh.ray.mask = ~0u;
        rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        rtcIntersect1(scene_, &context, &rh);
        Result out;
        if (rh.hit.geomID != RTC_INVALID_GEOMETRY_ID)
            out.hits[out.count++] =
                Hit{double(rh.ray.tfar), {}, NAN, HitKind::cross, Part::lateral, false};
        return out;
    }

    bool curve_;
    RTCDevice device_;
    RTCScene scene_;
    RTCGeometry geom_;
    float* vertices_;
    unsigned char* flags_ = nullptr;
};

OnePrimitive& cone_curve() {
    static OnePrimitive c(RTC_GEOMETRY_TYPE_CONE_LINEAR_CURVE);
    return c;
}
OnePrimitive& round_curve() {
    static OnePrimitive c(RTC_GEOMETRY_TYPE_ROUND_LINEAR_CURVE);
    return c;
}
OnePrimitive& sphere_point() {
    static OnePrimitive c(RTC_GEOMETRY_TYPE_SPHERE_POINT);
    return c;
}

// What a ray of Embree's is: from t0 >= 0, an origin and a direction of floats.
bool ray_like(const Line& l) {
    return l.range.t0 >= 0 && dot(l.v, l.v) > 0;
}

} // namespace

audit::ExternalSolver embree() {
    audit::ExternalSolver s;
    s.name = "embree";
    s.precision = Precision::binary32;
    s.answers = audit::Answers::nearest;
    s.parametrisation = audit::Parametrisation::line;
    s.surface = audit::Surface::as_posed;
    s.points = false, s.kinds = false, s.parts = false;
    s.mapping =
        "rtcIntersect1 against one RTC_GEOMETRY_TYPE_CONE_LINEAR_CURVE segment (vertices "
        "C0, C1 with radii r0, r1 as float4, RTC_SCENE_FLAG_ROBUST), org = L0, dir = v as "
        "given (not normalised: Embree's documentation allows any length), tnear = t0, "
        "tfar = t1; the answer is tfar of the closest hit. Caps: no neighbour flags "
        "(Embree closes the ends with discs); without caps both neighbour flags (open "
        "ends). A cylinder is the frustum r0 = r1 = r. Time includes committing the "
        "one-curve scene (a BVH build) per case. Sphere: one RTC_GEOMETRY_TYPE_SPHERE_POINT "
        "(C, r). Capsule: one RTC_GEOMETRY_TYPE_ROUND_LINEAR_CURVE segment C-H of radius "
        "r, no neighbour flags (spheres at both ends). Cannot represent: lines (t0 < 0), "
        "infinite shapes, the elliptic shapes and the ellipsoid.";
    s.on<Cylinder>() = [](const Cylinder& c, const Line& l) -> std::optional<Result> {
        if (!c.finite || !ray_like(l)) return std::nullopt;
        return cone_curve().nearest(c.C, c.r, c.H, c.r, c.caps, l);
    };
    s.on<Frustum>() = [](const Frustum& f, const Line& l) -> std::optional<Result> {
        if (!f.finite || !ray_like(l)) return std::nullopt;
        return cone_curve().nearest(f.C0, f.r0, f.C1, f.r1, f.caps, l);
    };
    s.on<Sphere>() = [](const Sphere& k, const Line& l) -> std::optional<Result> {
        if (!ray_like(l)) return std::nullopt;
        return sphere_point().nearest(k.C, k.r, l);
    };
    s.on<Capsule>() = [](const Capsule& k, const Line& l) -> std::optional<Result> {
        if (!ray_like(l)) return std::nullopt;
        return round_curve().nearest(k.C, k.r, k.H, k.r, true, l);
    };
    return s;
}

} // namespace linequad::peers
