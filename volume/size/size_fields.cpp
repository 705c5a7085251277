#include "volume/size/size_fields.h"

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <functional>
#include <limits>
#include <queue>
#include <sstream>
#include <string>
#include <utility>

#include "common/errors.h"
#include "volume/mesh/boundary.h"
#include "volume/mesh/geometry.h"
#include "volume/size/detail/point_memo.h"

namespace hdimesh::volume
{

namespace
{

bool finite_positive(double x) { return std::isfinite(x) && x > 0.0; }

std::string number(double x)
{
    std::ostringstream out;
    out << x;
    return out.str();
}

/// The vertex sizes a background mesh needs: one per vertex, positive where a tet uses it.
void validate_vertex_sizes(const TetMesh& mesh, const std::vector<double>& sizes)
{
    if (static_cast<int>(sizes.size()) != mesh.num_vertices())
        throw InputError("vertex sizes: " + std::to_string(sizes.size()) + " sizes for " +
                         std::to_string(mesh.num_vertices()) + " vertices");
    for (int t = 0; t < mesh.num_tet_slots(); ++t)
    {
        if (mesh.is_dead(t)) continue;
        for (int v : mesh.tets[t])
            if (v >= 0 && v < mesh.num_vertices() && !finite_positive(sizes[v]))
                throw InputError("vertex sizes: size " + number(sizes[v]) + " at vertex " +
                                 std::to_string(v) + " (sizes must be finite and > 0)");
    }
}

}  // namespace

ConstantSize::ConstantSize(double h) : h_(h)
{
    if (!finite_positive(h))
        throw InputError("constant size " + number(h) + ": must be finite and > 0");
}

BenchmarkFieldParams benchmark_case(char name)
{
    switch (std::toupper(static_cast<unsigned char>(name)))
    {
        case 'A': return {0.03, 0.03};
        case 'B': return {0.01, 0.01};
        case 'C': return {0.03, 0.3};
        case 'D': return {0.01, 0.3};
        case 'E': return {0.01, 0.7};
    }
    throw InputError(std::string("benchmark field case '") + name + "': expected A, B, C, D or E");
}

BenchmarkSize::BenchmarkSize(const BenchmarkFieldParams& params) : params_(params)
{
    const auto& p = params;
    if (!(finite_positive(p.dmin) && finite_positive(p.dmax) && p.dmin <= p.dmax &&
          std::isfinite(p.r) && p.r >= 0.0 && finite_positive(p.R)))
        throw InputError("benchmark field: dmin " + number(p.dmin) + ", r " + number(p.r) +
                         ", dmax " + number(p.dmax) + ", R " + number(p.R) +
                         ": need 0 < dmin <= dmax, r >= 0, R > 0");
}

double BenchmarkSize::size(const Vec3& p) const
{
    const auto& [dmin, r, dmax, R] = params_;
    const double x = p.x(), y = p.y(), z = p.z();
    double h = dmax;
    for (const double rho :
         {std::sqrt(y * y + z * z), std::sqrt(x * x + z * z), std::sqrt(x * x + y * y)})
    {
        const double d = std::abs(rho - r);
        const double cylinder = (1.0 - d / R) * dmin + (d / R) * dmax;
        h = std::min(h, std::min(cylinder, dmax));
    }
    return h;
}

BackgroundMeshSize::BackgroundMeshSize(const TetMesh& mesh, std::vector<double> vertex_sizes)
    : locator_((validate_vertex_sizes(mesh, vertex_sizes), mesh)), sizes_(std::move(vertex_sizes)),
      id_(detail::next_field_id())
{
}

double BackgroundMeshSize::size(const Vec3& p) const
{
    // An edge's midpoint is asked again by every operator that looks at the edge: the answers
    // of late are kept per thread, keyed by this field and the point's exact bits (the same
    // value the location gives, which depends on the point alone).
    struct Remembered
    {
        std::uint64_t field = 0;
        Vec3 point;
        double size = 0.0;
    };
    constexpr std::size_t kSlots = 4096;
    thread_local std::vector<Remembered> remembered(kSlots);
    Remembered& slot = remembered[detail::point_slot(p, kSlots)];
    if (slot.field == id_ && slot.point == p) return slot.size;
    slot.field = id_;
    slot.point = p;
    slot.size = locate_size(p);
    return slot.size;
}

double BackgroundMeshSize::locate_size(const Vec3& p) const
{
    if (const auto inside = locator_.locate(p))
    {
        double h = 0.0;
        for (int k = 0; k < 4; ++k) h += inside->weights[k] * sizes_[inside->vertices[k]];
        return h;
    }
    const BoundaryPoint nearest = locator_.nearest_boundary_point(p);
    double h = 0.0;
    for (int k = 0; k < 3; ++k) h += nearest.weights[k] * sizes_[nearest.vertices[k]];
    return h;
}

ClampedSize::ClampedSize(std::shared_ptr<const SizeField> inner, double hmin, double hmax)
    : inner_(std::move(inner)), hmin_(hmin), hmax_(hmax)
{
    if (!inner_) throw InputError("clamped size: no field to clamp");
    if (!(std::isfinite(hmin) && hmin >= 0.0 && hmax >= hmin))
        throw InputError("clamped size: hmin " + number(hmin) + ", hmax " + number(hmax) +
                         ": need 0 <= hmin <= hmax");
}

double ClampedSize::size(const Vec3& p) const { return std::clamp(inner_->size(p), hmin_, hmax_); }

double expected_tet_count(const TetMesh& mesh, const SizeField& field)
{
    double count = 0.0;
    for (int t = 0; t < static_cast<int>(mesh.tets.size()); ++t)
    {
        if (mesh.is_dead(t)) continue;
        const auto& v = mesh.tets[t];
        const Vec3& a = mesh.points[v[0]];
        const Vec3& b = mesh.points[v[1]];
        const Vec3& c = mesh.points[v[2]];
        const Vec3& d = mesh.points[v[3]];
        const double h = field.size(0.25 * (a + b + c + d));
        count += std::abs(signed_volume(a, b, c, d)) / (h * h * h / (6.0 * std::sqrt(2.0)));
    }
    return count;
}

std::vector<double> sample_vertex_sizes(const TetMesh& mesh, const SizeField& field)
{
    std::vector<double> sizes(mesh.num_vertices());
    for (int v = 0; v < mesh.num_vertices(); ++v) sizes[v] = field.size(mesh.points[v]);
    return sizes;
}

void grade_vertex_sizes(const TetMesh& mesh, std::vector<double>& sizes, double hgrad)
{
    if (!(std::isfinite(hgrad) && hgrad >= 1.0))
        throw InputError("gradation: hgrad " + number(hgrad) + " must be finite and >= 1");
    validate_vertex_sizes(mesh, sizes);

    // h_j <= h_i + slope * L_ij on every edge is a shortest-path condition: the largest sizes
    // satisfying it are min_i (h_i + slope * dist(i, j)), which Dijkstra computes exactly,
    // settling each vertex once (no sweeps to convergence).
    const double slope = hgrad - 1.0;
    const VertexGraph graph = vertex_graph(mesh);
    using Entry = std::pair<double, int>;
    std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> queue;
    for (int v = 0; v < mesh.num_vertices(); ++v)
        if (graph.start[v + 1] > graph.start[v]) queue.push({sizes[v], v});
    std::vector<char> settled(mesh.num_vertices(), 0);
    while (!queue.empty())
    {
        const auto [h, v] = queue.top();
        queue.pop();
        if (settled[v] || h > sizes[v]) continue;
        settled[v] = 1;
        for (int n = graph.start[v]; n < graph.start[v + 1]; ++n)
        {
            const int w = graph.neighbors[n];
            const double bound = h + slope * (mesh.points[w] - mesh.points[v]).norm();
            if (bound < sizes[w])
            {
                sizes[w] = bound;
                queue.push({bound, w});
            }
        }
    }
}

}  // namespace hdimesh::volume
