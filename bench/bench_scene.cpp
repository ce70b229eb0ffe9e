// Rays per second through scenes of closed frusta (thin rods, as strands and particle tracks are
// modelled), for the scene's stable and correct solvers, nearest and any, through its own
// hierarchy and through Embree's BVH (scene_embree_bvh: linequad's solvers behind Embree's user
// geometry), and for Embree's own float cone curves with end discs on the same frusta (when
// Embree is built in). Run interleaved:
//   build/bench/linequad_scene_bench --benchmark_repetitions=5
//       --benchmark_enable_random_interleaving=true --benchmark_report_aggregates_only=true
#include "linequad/linequad.hpp"

#include <benchmark/benchmark.h>

#include <cmath>
#include <map>
#include <memory>
#include <random>

#ifdef LINEQUAD_BENCH_EMBREE
#include <embree3/rtcore.h>
#endif

namespace {

using namespace linequad;

// n frusta of length 1 to 2 and radii 0.02 to 0.1, at random in a cube whose side grows as
// n^(1/3) (a constant density: about 0.3 rods per unit cube), and 4096 rays across it.
struct World {
    std::vector<Shape> shapes;
    std::vector<Frustum> frusta;
    std::vector<Line> rays;
};

const World& world(int n) {
    static std::map<int, std::unique_ptr<World>> cache;
    auto& w = cache[n];
    if (w) return *w;
    w = std::make_unique<World>();
    std::mt19937_64 rng{std::uint64_t(n)};
    double side = 1.5 * std::cbrt(double(n));
    std::uniform_real_distribution<double> pos(0, side), dir(-1, 1), len(1, 2), rad(0.02, 0.1);
    auto unit = [&] {
        for (;;) {
            Vec3 d{dir(rng), dir(rng), dir(rng)};
            double l = std::sqrt(dot(d, d));
            if (l > 0.1 && l <= 1) return (1 / l) * d;
        }
    };
    for (int i = 0; i < n; ++i) {
        Vec3 c0{pos(rng), pos(rng), pos(rng)};
        Frustum f{c0, rad(rng), c0 + len(rng) * unit(), rad(rng), true, true};
        w->frusta.push_back(f);
        w->shapes.push_back(f);
    }
    for (int i = 0; i < 4096; ++i)
        w->rays.push_back({{pos(rng), pos(rng), pos(rng)}, unit(), Range::ray});
    return *w;
}

void scene_rays(benchmark::State& state, SceneSolver solver, Need need, SceneTraversal traversal) {
    const World& w = world(int(state.range(0)));
    Scene scene(w.shapes, solver, traversal);
    if (scene.traversal() != traversal) return state.SkipWithError("traversal not available");
    SceneAnswer a;
    std::size_t i = 0, hits = 0, solved = 0, refined = 0;
    for (auto _ : state) {
        scene.intersect(w.rays[i++ & 4095], {need, false}, a);
        hits += a.hits.size();
        solved += a.shapes_solved;
        refined += a.exact_comparisons > 0;
        benchmark::DoNotOptimize(a.hits.data());
    }
    double n = double(state.iterations());
    state.counters["rays/s"] = benchmark::Counter(n, benchmark::Counter::kIsRate);
    state.counters["hits/ray"] = double(hits) / n;
    state.counters["solved/ray"] = double(solved) / n;
    // The rays whose order needed an exact comparison of two shapes' roots (correct scenes).
    state.counters["refined/ray"] = double(refined) / n;
}

#ifdef LINEQUAD_BENCH_EMBREE
// The same frusta as Embree cone linear curves with end discs (float vertices and radii), one
// BVH, rtcIntersect1 (nearest) or rtcOccluded1 (any).
void embree_rays(benchmark::State& state, Need need) {
    const World& w = world(int(state.range(0)));
    RTCDevice device = rtcNewDevice("threads=1");
    RTCScene scene = rtcNewScene(device);
    rtcSetSceneFlags(scene, RTC_SCENE_FLAG_ROBUST);
    RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_CONE_LINEAR_CURVE);
    std::size_t n = w.frusta.size();
    auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(
        geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4, 4 * sizeof(float), 2 * n));
    auto* index = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
        geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT, sizeof(unsigned), n));
    auto* flags = static_cast<unsigned char*>(rtcSetNewGeometryBuffer(
        geom, RTC_BUFFER_TYPE_FLAGS, 0, RTC_FORMAT_UCHAR, sizeof(unsigned char), n));
    for (std::size_t k = 0; k < n; ++k) {
        const Frustum& f = w.frusta[k];
        float* p = v + 8 * k;
        p[0] = float(f.C0.x), p[1] = float(f.C0.y), p[2] = float(f.C0.z), p[3] = float(f.r0);
        p[4] = float(f.C1.x), p[5] = float(f.C1.y), p[6] = float(f.C1.z), p[7] = float(f.r1);
        index[k] = unsigned(2 * k);
        flags[k] = 0; // no neighbours: both end discs
    }
    rtcCommitGeometry(geom);
    rtcAttachGeometry(scene, geom);
    rtcReleaseGeometry(geom);
    rtcCommitScene(scene);
    std::size_t i = 0, hits = 0;
    for (auto _ : state) {
        const Line& l = w.rays[i++ & 4095];
        RTCIntersectContext context;
        rtcInitIntersectContext(&context);
        RTCRayHit rh{};
        rh.ray.org_x = float(l.L0.x), rh.ray.org_y = float(l.L0.y), rh.ray.org_z = float(l.L0.z);
        rh.ray.dir_x = float(l.v.x), rh.ray.dir_y = float(l.v.y), rh.ray.dir_z = float(l.v.z);
        rh.ray.tnear = 0, rh.ray.tfar = INFINITY, rh.ray.mask = ~0u;
        rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        if (need == Need::any) {
            rtcOccluded1(scene, &context, &rh.ray);
            hits += rh.ray.tfar < 0; // Embree marks an occluded ray with tfar = -inf
        } else {
            rtcIntersect1(scene, &context, &rh);
            hits += rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
        }
        benchmark::DoNotOptimize(rh);
    }
    double count = double(state.iterations());
    state.counters["rays/s"] = benchmark::Counter(count, benchmark::Counter::kIsRate);
    state.counters["hits/ray"] = double(hits) / count;
    rtcReleaseScene(scene);
    rtcReleaseDevice(device);
}
#endif

void register_all() {
    for (int n : {1000, 100000}) {
        for (auto [traversal, tname] : {std::pair{SceneTraversal::hierarchy, "scene/"},
                                        std::pair{SceneTraversal::embree, "scene_embree_bvh/"}}) {
            if (!scene_traversal_available(traversal)) continue;
            for (auto [solver, sname] : {std::pair{SceneSolver::stable, "stable"},
                                         std::pair{SceneSolver::correct, "correct"}})
                for (auto [need, nname] :
                     {std::pair{Need::nearest, "nearest"}, std::pair{Need::any, "any"}})
                    benchmark::RegisterBenchmark(
                        (std::string(tname) + sname + "/" + nname).c_str(),
                        [solver = solver, need = need, traversal = traversal](benchmark::State& s) {
                            scene_rays(s, solver, need, traversal);
                        })
                        ->Arg(n);
        }
#ifdef LINEQUAD_BENCH_EMBREE
        for (auto [need, nname] :
             {std::pair{Need::nearest, "nearest"}, std::pair{Need::any, "any"}})
            benchmark::RegisterBenchmark(
                (std::string("embree_cone_curves/") + nname).c_str(),
                [need = need](benchmark::State& s) { embree_rays(s, need); })
                ->Arg(n);
#endif
    }
}

} // namespace

int main(int argc, char** argv) {
    register_all();
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    return 0;
}
