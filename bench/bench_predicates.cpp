// Cost per call of the exact predicates (volume/mesh/predicates.h) on a few input families: random
// points (the filter decides), near-coplanar rounded points (the exact stage decides), and
// the intersection tests on random, nearby and vertex-sharing simplices. Prints one table row
// per family: ns per call and the share of answers that are +1 or true.
//
// usage: bench_predicates [repeats, default 200]

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <utility>
#include <vector>

#include "volume/mesh/predicates.h"

using namespace hdimesh;
using volume::Vec3;

namespace
{

struct Random
{
    std::uint64_t state;
    std::uint64_t next()
    {
        std::uint64_t z = (state += 0x9e3779b97f4a7c15ull);
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
        return z ^ (z >> 31);
    }
    double unit() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }
    Vec3 point() { return Vec3(unit(), unit(), unit()); }
};

constexpr int kCases = 4096;

/// Runs `call(i)` over the cases `repeats` times; returns ns per call and the share of
/// answers that are +1 or true. A template, so the predicate inlines as it does in the mesher.
template <class Call>
std::pair<double, double> time_calls(int repeats, const Call& call)
{
    long long positive = 0;
    const auto start = std::chrono::steady_clock::now();
    for (int r = 0; r < repeats; ++r)
        for (int i = 0; i < kCases; ++i) positive += call(i) > 0;
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const double calls = static_cast<double>(repeats) * kCases;
    return {seconds * 1e9 / calls, static_cast<double>(positive) / calls};
}

}  // namespace

int main(int argc, char** argv)
{
    const int repeats = argc > 1 ? std::atoi(argv[1]) : 200;
    Random random{2024};

    // Quadruples: random in the unit cube; d rounded onto plane abc near (100, 100, 100); and
    // exactly coplanar integers. Calling the exact stage directly on the random ones, whose
    // differences are inexact, gives its worst case (the longest expansions).
    std::vector<Vec3> random_points, coplanar_points, exact_coplanar_points;
    for (int i = 0; i < kCases; ++i)
    {
        // exactly coplanar (and for the first three, collinear on the xy projection) integers:
        // the filter can never decide them
        const Vec3 base(static_cast<double>(random.next() % 1000),
                        static_cast<double>(random.next() % 1000),
                        static_cast<double>(random.next() % 1000));
        const Vec3 u(1 + random.next() % 7, 1 + random.next() % 7, random.next() % 7);
        const Vec3 v(random.next() % 7, 1 + random.next() % 7, 1 + random.next() % 7);
        exact_coplanar_points.insert(exact_coplanar_points.end(),
                                     {base, base + u, base + 3 * u, base + 2 * u - 3 * v});
        for (int k = 0; k < 4; ++k) random_points.push_back(random.point());
        const Vec3 shift(100, 100, 100);
        const Vec3 a = random.point() + shift, b = random.point() + shift,
                   c = random.point() + shift;
        const double s = random.unit(), t = random.unit();
        coplanar_points.insert(coplanar_points.end(), {a, b, c, a + s * (b - a) + t * (c - a)});
    }

    // Triangles: random in the unit cube, small and nearby (a mix), pairs
    // sharing an edge or a vertex, and tets with nearby triangles (advancing-front-like).
    std::vector<Vec3> points;
    std::vector<std::array<int, 3>> far1, far2, near1, near2, edge1, edge2, vertex1, vertex2;
    std::vector<std::array<int, 4>> tets;
    auto add = [&points](const Vec3& p) {
        points.push_back(p);
        return static_cast<int>(points.size()) - 1;
    };
    for (int i = 0; i < kCases; ++i)
    {
        far1.push_back({add(random.point()), add(random.point()), add(random.point())});
        far2.push_back({add(random.point()), add(random.point()), add(random.point())});
        const Vec3 centre = random.point();
        auto nearby = [&]() { return add(centre + 0.2 * (random.point() - Vec3(0.5, 0.5, 0.5))); };
        near1.push_back({nearby(), nearby(), nearby()});
        near2.push_back({nearby(), nearby(), nearby()});
        const int a = nearby(), b = nearby();
        edge1.push_back({a, b, nearby()});
        edge2.push_back({b, a, nearby()});
        vertex1.push_back({a, nearby(), nearby()});
        vertex2.push_back({a, nearby(), nearby()});
        std::array<int, 4> tet = {a, b, nearby(), nearby()};
        if (volume::orient3d(points[tet[0]], points[tet[1]], points[tet[2]], points[tet[3]]) < 0)
            std::swap(tet[2], tet[3]);
        tets.push_back(tet);
    }

    std::printf("%-40s %12s %10s\n", "predicate / input", "ns per call", "+1 or true");
    // The fastest of several rounds: the machine may be shared, and interference only adds.
    auto run = [repeats](const char* name, const auto& call) {
        double best = 1e300, share = 0.0;
        for (int round = 0; round < 7; ++round)
        {
            const auto [ns, positive] = time_calls(repeats / 5 + 1, call);
            best = std::min(best, ns);
            share = positive;
        }
        std::printf("%-40s %12.1f %9.1f%%\n", name, best, 100.0 * share);
    };
    const auto& rp = random_points;
    const auto& cp = coplanar_points;
    run("signed_volume6 (rounded, reference)", [&](int i) {
        const double v =
            volume::signed_volume6(rp[4 * i], rp[4 * i + 1], rp[4 * i + 2], rp[4 * i + 3]);
        return v > 0 ? 1 : (v < 0 ? -1 : 0);
    });
    run("orient3d random", [&](int i) {
        return volume::orient3d(rp[4 * i], rp[4 * i + 1], rp[4 * i + 2], rp[4 * i + 3]);
    });
    run("orient3d near-coplanar", [&](int i) {
        return volume::orient3d(cp[4 * i], cp[4 * i + 1], cp[4 * i + 2], cp[4 * i + 3]);
    });
    run("orient3d exact stage alone, random", [&](int i) {
        return volume::detail::orient3d_exact(rp[4 * i], rp[4 * i + 1], rp[4 * i + 2],
                                              rp[4 * i + 3]);
    });
    run("orient2d random",
        [&](int i) { return volume::orient2d(rp[4 * i], rp[4 * i + 1], rp[4 * i + 2], i % 3); });
    const auto& ep = exact_coplanar_points;
    run("orient3d exactly coplanar (exact stage)", [&](int i) {
        return volume::orient3d(ep[4 * i], ep[4 * i + 1], ep[4 * i + 2], ep[4 * i + 3]);
    });
    run("orient2d collinear (exact stage)",
        [&](int i) { return volume::orient2d(ep[4 * i], ep[4 * i + 1], ep[4 * i + 2], 2); });
    run("triangles_intersect random in unit cube",
        [&](int i) { return int(volume::triangles_intersect(points, far1[i], far2[i])); });
    run("triangles_intersect nearby",
        [&](int i) { return int(volume::triangles_intersect(points, near1[i], near2[i])); });
    run("triangles_intersect shared edge",
        [&](int i) { return int(volume::triangles_intersect(points, edge1[i], edge2[i])); });
    run("triangles_intersect shared vertex",
        [&](int i) { return int(volume::triangles_intersect(points, vertex1[i], vertex2[i])); });
    run("segment_triangle_intersect nearby", [&](int i) {
        return int(
            volume::segment_triangle_intersect(points, {near1[i][0], near1[i][1]}, near2[i]));
    });
    run("tet_triangle_intersect nearby",
        [&](int i) { return int(volume::tet_triangle_intersect(points, tets[i], near2[i])); });
    run("tet_triangle_intersect shared vertex",
        [&](int i) { return int(volume::tet_triangle_intersect(points, tets[i], vertex2[i])); });
    run("tet_triangle_intersect shared edge",
        [&](int i) { return int(volume::tet_triangle_intersect(points, tets[i], edge2[i])); });
    return 0;
}
