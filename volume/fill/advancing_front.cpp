#include "volume/fill/advancing_front.h"

#include <algorithm>
#include <array>
#include <cassert>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <sstream>

#include "common/morton.h"
#include "volume/fill/detail/front_mesher.h"
#include "volume/mesh/predicates.h"
#include "volume/mesh/tet_tables.h"

namespace hdimesh::volume
{
namespace detail::front_mesher
{

float FrontMesher::face_size(const Triangle& t) const
{
    const Vec3 &a = points_[t[0]], &b = points_[t[1]], &c = points_[t[2]];
    return static_cast<float>(((b - a).norm() + (c - b).norm() + (a - c).norm()) / 3.0);
}

/// Size class (a factor 2^(1/4) per class) above a 45-bit Z-order key of the centroid.
std::uint64_t FrontMesher::order_key(const Triangle& t) const
{
    const Vec3 &a = points_[t[0]], &b = points_[t[1]], &c = points_[t[2]];
    const double size = ((b - a).norm() + (c - b).norm() + (a - c).norm()) / 3.0;
    const double size_class = std::floor(4.0 * std::log2(std::max(size, 1e-300) / order_scale_));
    const std::uint64_t cls =
        static_cast<std::uint64_t>(std::clamp(size_class + 2048.0, 0.0, 4095.0));
    const Vec3 u = (((a + b + c) / 3.0 - order_origin_) * order_inverse_extent_)
                       .cwiseMax(Vec3::Zero())
                       .cwiseMin(Vec3::Constant(1.0));
    constexpr double kCells = 32767.0;
    const std::uint64_t z = morton_key(static_cast<std::uint64_t>(u[0] * kCells),
                                       static_cast<std::uint64_t>(u[1] * kCells),
                                       static_cast<std::uint64_t>(u[2] * kCells));
    return cls << 45 | z;
}

bool FrontMesher::setup(std::string& failure)
{
    const int n = static_cast<int>(input_points_.size());
    local_to_global_.reserve(3 * input_faces_.size());
    for (std::size_t f = 0; f < input_faces_.size(); ++f)
        for (int v : input_faces_[f])
        {
            if (v < 0 || v >= n)
            {
                failure = "face " + std::to_string(f) + ": vertex id " + std::to_string(v) +
                          " out of range";
                return false;
            }
            local_to_global_.push_back(v);
        }
    std::sort(local_to_global_.begin(), local_to_global_.end());
    local_to_global_.erase(std::unique(local_to_global_.begin(), local_to_global_.end()),
                           local_to_global_.end());
    num_input_vertices_ = static_cast<int>(local_to_global_.size());
    points_.reserve(num_input_vertices_ * 2 + 16);
    for (int g : local_to_global_) points_.push_back(input_points_[g]);
    auto local_of = [&](int g) {
        return static_cast<int>(
            std::lower_bound(local_to_global_.begin(), local_to_global_.end(), g) -
            local_to_global_.begin());
    };

    // Closed and consistently oriented: every directed edge once, and its reverse once.
    std::vector<std::array<int, 3>> directed;  // (from, to, face)
    directed.reserve(3 * input_faces_.size());
    std::vector<Triangle> local_faces(input_faces_.size());
    for (std::size_t f = 0; f < input_faces_.size(); ++f)
    {
        const Triangle& t = input_faces_[f];
        if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2])
        {
            failure = "face " + std::to_string(f) + " repeats a vertex";
            return false;
        }
        for (int k = 0; k < 3; ++k) local_faces[f][k] = local_of(t[k]);
        for (int k = 0; k < 3; ++k)
            directed.push_back(
                {local_faces[f][k], local_faces[f][(k + 1) % 3], static_cast<int>(f)});
    }
    std::sort(directed.begin(), directed.end());
    for (std::size_t i = 0; i < directed.size(); ++i)
    {
        const auto& e = directed[i];
        if (i + 1 < directed.size() && directed[i + 1][0] == e[0] && directed[i + 1][1] == e[1])
        {
            failure = "faces " + std::to_string(e[2]) + " and " +
                      std::to_string(directed[i + 1][2]) + " run along edge " +
                      std::to_string(local_to_global_[e[0]]) + "-" +
                      std::to_string(local_to_global_[e[1]]) + " the same way";
            return false;
        }
        const std::array<int, 3> reverse{e[1], e[0], -1};
        const auto it = std::lower_bound(directed.begin(), directed.end(), reverse);
        if (it == directed.end() || (*it)[0] != e[1] || (*it)[1] != e[0])
        {
            failure = "face " + std::to_string(e[2]) + ": edge " +
                      std::to_string(local_to_global_[e[0]]) + "-" +
                      std::to_string(local_to_global_[e[1]]) + " is open";
            return false;
        }
    }

    {
        Vec3 lo = points_[0], hi = points_[0];
        for (const Vec3& p : points_) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
        order_origin_ = lo;
        order_inverse_extent_ = 1.0 / std::max((hi - lo).maxCoeff(), 1e-300);
        order_scale_ = std::max((hi - lo).maxCoeff(), 1e-300);
    }
    if (!field_)
    {
        input_sizes_.build(points_, local_faces);
        field_ = &input_sizes_;
    }
    front_.valence.assign(num_input_vertices_, 0);
    front_.hash.reserve(input_faces_.size() * 2);
    for (std::size_t f = 0; f < input_faces_.size(); ++f)
    {
        const Triangle& t = local_faces[f];
        const Triangle inward{t[0], t[2], t[1]};
        if (front_.find(inward) >= 0)
        {
            failure = "face " + std::to_string(f) + " is listed twice";
            return false;
        }
        front_.add(inward, 0, face_size(inward), order_key(inward));
    }
    component_.assign(num_input_vertices_, 0);
    layer_.assign(num_input_vertices_, 0);
    in_grid_.assign(num_input_vertices_, 0);

    // Budget: enough iterations for every tet the sizes can ask for, many times over.
    Vec3 lo = points_[0], hi = points_[0];
    for (const Vec3& p : points_) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
    double volume = 0, min_size = std::numeric_limits<double>::infinity();
    for (std::size_t f = 0; f < local_faces.size(); ++f)
    {
        const Triangle& t = local_faces[f];
        volume += signed_volume(Vec3::Zero(), points_[t[0]], points_[t[1]], points_[t[2]]);
        double s = front_.size[f];
        if (field_)
            s = std::min<double>(
                s, field_->size((points_[t[0]] + points_[t[1]] + points_[t[2]]) / 3.0));
        min_size = std::min(min_size, s);
    }
    const double regular_volume = min_size * min_size * min_size / (6.0 * std::sqrt(2.0));
    const double expected = std::abs(volume) / std::max(regular_volume, 1e-300);
    iteration_budget_ = static_cast<long>(
        std::min(4e9, 20.0 * std::min(expected, 1e8) + 200.0 * input_faces_.size() + 10000));
    if (options_.max_attempts > 0)
        iteration_budget_ = std::min(iteration_budget_, options_.max_attempts);
    return true;
}

void FrontMesher::build_grid()
{
    use_grid_ = front_.alive_count > kBruteForceFaces;
    Vec3 lo = points_[0], hi = points_[0];
    for (int v = 0; v < num_input_vertices_; ++v)
        lo = lo.cwiseMin(points_[v]), hi = hi.cwiseMax(points_[v]);
    double mean = 0;
    for (int f = 0; f < static_cast<int>(front_.vertices.size()); ++f)
        if (front_.alive[f]) mean += front_.size[f];
    mean /= std::max(1, front_.alive_count);
    double typical = mean;
    if (field_)
    {
        // the geometric mean of the field at the face centroids: a uniform grid's compromise
        double log_sum = 0;
        int count = 0;
        for (int f = 0; f < static_cast<int>(front_.vertices.size()); f += 7)
            if (front_.alive[f])
            {
                const Triangle& t = front_.vertices[f];
                const double s =
                    field_->size((points_[t[0]] + points_[t[1]] + points_[t[2]]) / 3.0);
                log_sum += std::log(std::clamp(s, kMinSizeFactor * front_.size[f],
                                               kMaxSizeFactor * front_.size[f]));
                ++count;
            }
        if (count > 0) typical = std::exp(log_sum / count);
    }
    const long max_cells = use_grid_ ? 8L * front_.alive_count + 4096 : 1;
    grid_.init(lo, hi, kGridCellFactor * typical, max_cells);
    std::fill(in_grid_.begin(), in_grid_.end(), 0);
    for (int v = 0; v < static_cast<int>(points_.size()); ++v)
        if (front_.valence[v] > 0)
        {
            grid_.add_vertex(v, points_[v]);
            in_grid_[v] = 1;
        }
    for (int f = 0; f < static_cast<int>(front_.vertices.size()); ++f)
        if (front_.alive[f])
        {
            const Triangle& t = front_.vertices[f];
            const Box b = box_of(points_[t[0]], points_[t[1]], points_[t[2]]);
            grid_.add_face(f, t, b.lo, b.hi);
        }
}

/// Components of the front through shared vertices. When one encloses a negative volume (a
/// void's shell) it is part of a component around it: then all share one label (as Netgen).
std::vector<int> FrontMesher::front_vertex_groups() const
{
    const int n = static_cast<int>(points_.size());
    std::vector<int> parent(n);
    std::iota(parent.begin(), parent.end(), 0);
    auto root = [&](int v) {
        while (parent[v] != v) v = parent[v] = parent[parent[v]];
        return v;
    };
    for (int f = 0; f < static_cast<int>(front_.vertices.size()); ++f)
        if (front_.alive[f])
        {
            const Triangle& t = front_.vertices[f];
            for (int k = 1; k < 3; ++k)
            {
                const int a = root(t[0]), b = root(t[k]);
                if (a != b) parent[std::max(a, b)] = std::min(a, b);
            }
        }
    for (int v = 0; v < n; ++v) parent[v] = root(v);
    return parent;
}

void FrontMesher::compute_components()
{
    const int n = static_cast<int>(points_.size());
    const std::vector<int> group = front_vertex_groups();
    auto root = [&group](int v) { return group[v]; };
    std::vector<double> volume(n, 0.0);
    for (int f = 0; f < static_cast<int>(front_.vertices.size()); ++f)
        if (front_.alive[f])
        {
            const Triangle& t = front_.vertices[f];
            // stored inward: the enclosed volume is minus the sum
            volume[root(t[0])] -=
                signed_volume(points_[t[0]], points_[t[1]], points_[t[2]], Vec3::Zero());
        }
    bool negative = false;
    for (int v = 0; v < n; ++v)
        if (group[v] == v && front_.valence[v] > 0 && volume[v] < 0) negative = true;
    component_.resize(n);
    for (int v = 0; v < n; ++v) component_[v] = negative ? 0 : root(v);
}

void FrontMesher::gather_vertices(const Box& region)
{
    local_vertices_.clear();
    grid_.query_vertices(region.lo, region.hi, [&](int v) { local_vertices_.push_back(v); });
}

void FrontMesher::gather_faces(int face, const Box& region)
{
    local_faces_.clear();
    last_blocker_ = -1;
    grid_.query_faces(region.lo, region.hi, [&](const detail::BucketGrid::FaceEntry& e) {
        if (e.face != face) local_faces_.push_back(e);
    });
}

/// A face's generation is its vertices' lowest layer (Netgen's FrontNr): the faces a tet raises
/// beside the boundary stay in the boundary's layer, so valleys close before the next layer.
void FrontMesher::add_face(const Triangle& t)
{
    const int lowest = std::min({layer_[t[0]], layer_[t[1]], layer_[t[2]]});
    for (int v : t) layer_[v] = std::min(layer_[v], lowest + 1);
    const int id = front_.add(t, lowest, face_size(t), order_key(t));
    for (int v : t)
        if (!in_grid_[v])
        {
            grid_.add_vertex(v, points_[v]);
            in_grid_[v] = 1;
        }
    const Box b = box_of(points_[t[0]], points_[t[1]], points_[t[2]]);
    grid_.add_face(id, t, b.lo, b.hi);
    front_.push(id);
}

void FrontMesher::remove_face(int id)
{
    // the points never move, so the box is the one the face was listed with
    const Triangle& t = front_.vertices[id];
    const Box b = box_of(points_[t[0]], points_[t[1]], points_[t[2]]);
    grid_.remove_face(id, b.lo, b.hi);
    front_.remove(id);
    for (int v : t)
        if (front_.valence[v] == 0 && in_grid_[v])
        {
            grid_.remove_vertex(v, points_[v]);
            in_grid_[v] = 0;
        }
}

void FrontMesher::commit(int face, int p)
{
    const Triangle base = front_.vertices[face];
    const int a = base[0], b = base[1], c = base[2];
    tets_.push_back({a, b, c, p});
    remove_face(face);
    const std::array<Triangle, 3> sides{{{a, b, p}, {b, c, p}, {c, a, p}}};
    for (const Triangle& s : sides)
    {
        const int g = front_.find(s);
        if (g >= 0)
        {
            // closing: the face on the front must run the other way (a same-way one is a bug)
            assert(!same_orientation(s, front_.vertices[g]));
            remove_face(g);
        }
        else
            add_face(s);
    }
}

/// Existing vertices scoring >= 0.8 of the best new point first, then new points, then the
/// other vertices; by quality inside each class, ties by vertex id.
void FrontMesher::sort_candidates(double ideal_quality)
{
    // each retreat round leans further towards existing vertices, so a rerun takes another path
    const double prefer =
        kPreferExisting * std::pow(kRetreatPreferFactor, retreat_rounds_) * ideal_quality;
    auto rank = [&](const Candidate& x) {
        if (x.vertex >= 0) return x.quality >= prefer ? 0 : 2;
        return 1;
    };
    std::sort(candidates_.begin(), candidates_.end(), [&](const Candidate& x, const Candidate& y) {
        const int rx = rank(x), ry = rank(y);
        if (rx != ry) return rx < ry;
        if (x.quality != y.quality) return x.quality > y.quality;
        if (x.vertex != y.vertex) return x.vertex < y.vertex;
        return x.slot < y.slot;
    });
}

bool FrontMesher::attempt(int face)
{
    const Triangle& base = front_.vertices[face];
    const int a = base[0], b = base[1], c = base[2];
    const Vec3 A = points_[a], B = points_[b], C = points_[c];
    const Vec3 centroid = (A + B + C) / 3.0;
    Vec3 normal = (B - A).cross(C - A);
    const double twice_area = normal.norm();
    if (!(twice_area > 0)) return false;
    normal /= twice_area;
    const double mean_edge = front_.size[face];
    const double wanted = field_ ? field_->size(centroid) : mean_edge;
    const double d = std::clamp(wanted, kMinSizeFactor * mean_edge, kMaxSizeFactor * mean_edge);
    const int fail = front_.fail[face];
    const int num_floors = static_cast<int>(options_.quality_floors.size());
    const double floor =
        num_floors == 0 ? 0.0 : options_.quality_floors[std::min(fail, num_floors - 1)];
    const double height = kTwoThirdsRoot * d;
    const Vec3 ideal = centroid + normal * height;
    const double radius = d * (kSearchRadius + kRadiusGrowth * fail);
    const double volume_floor = kVolumeFloor * mean_edge * mean_edge * mean_edge;

    Box region{A.cwiseMin(B).cwiseMin(C).cwiseMin(ideal - Vec3::Constant(radius)),
               A.cwiseMax(B).cwiseMax(C).cwiseMax(ideal + Vec3::Constant(radius))};
    gather_vertices(region);

    candidates_.clear();
    auto quality_of = [&](const Vec3& P) {
        if (signed_volume6(A, B, C, P) <= volume_floor) return -1.0;
        return tet_quality(A, B, C, P);
    };
    const int comp = component_[a];
    const double radius2 = radius * radius;
    for (int v : local_vertices_)
    {
        if (v == a || v == b || v == c || component_[v] != comp) continue;
        if ((points_[v] - ideal).squaredNorm() > radius2) continue;
        const double q = quality_of(points_[v]);
        if (q > 0 && q >= floor) candidates_.push_back({q, v, 0});
    }
    // New points: P* and P* pulled back to 0.7 and 0.5 of its height, each dropped when a front
    // vertex is closer than min_point_distance * d (that vertex is a candidate already); the
    // distance relaxes with the failures, as the quality floor does.
    const double too_close = options_.min_point_distance * d * std::pow(kCrowdingRelax, fail);
    double ideal_quality = 0, best_new = 0;  // P*'s, and the best new point's
    const std::array<double, 3> pull{1.0, 0.7, 0.5};
    for (int k = 0; k < 3; ++k)
    {
        const Vec3 P = centroid + normal * (height * pull[k]);
        bool crowded = false;
        for (int v : local_vertices_)
            if ((points_[v] - P).squaredNorm() < too_close * too_close)
            {
                crowded = true;
                break;
            }
        if (crowded) continue;
        const double q = quality_of(P);
        if (q > 0 && q >= floor)
        {
            new_positions_[k] = P;
            candidates_.push_back({q, -1, k});
            if (k == 0) ideal_quality = q;
            best_new = std::max(best_new, q);
        }
    }
    if (ideal_quality == 0) ideal_quality = best_new;
    sort_candidates(ideal_quality);

    if (candidates_.empty()) return false;
    // the faces that may meet any candidate tet: those overlapping the union of their boxes
    Box reach = box_of(A, B, C);
    for (const Candidate& cand : candidates_)
    {
        const Vec3& P = cand.vertex >= 0 ? points_[cand.vertex] : new_positions_[cand.slot];
        reach.lo = reach.lo.cwiseMin(P);
        reach.hi = reach.hi.cwiseMax(P);
    }
    gather_faces(face, reach);

    for (const Candidate& cand : candidates_)
    {
        if (cand.vertex >= 0)
        {
            if (valid_tet(face, cand.vertex, false))
            {
                commit(face, cand.vertex);
                return true;
            }
            continue;
        }
        const int p = static_cast<int>(points_.size());
        points_.push_back(new_positions_[cand.slot]);
        front_.valence.push_back(0);
        component_.push_back(comp);
        in_grid_.push_back(0);
        layer_.push_back(1 + std::min({layer_[a], layer_[b], layer_[c]}));
        if (valid_tet(face, p, true))
        {
            commit(face, p);
            return true;
        }
        points_.pop_back();
        front_.valence.pop_back();
        component_.pop_back();
        in_grid_.pop_back();
        layer_.pop_back();
    }
    return false;
}

/// Runs the front until it is empty (true) or every face left is stuck (false).
bool FrontMesher::advance()
{
    const int num_floors = static_cast<int>(options_.quality_floors.size());
    const int stuck = std::max(1, num_floors) + kExtraAttempts;
    for (;;)
    {
        const int face = front_.top();
        if (face < 0) return true;
        if (front_.fail[face] >= stuck) return false;
        if (++iterations_ > iteration_budget_) return false;
        front_.pop();
        if (!attempt(face))
        {
            ++front_.fail[face];
            front_.push(face);
        }
    }
}

bool FrontMesher::run(std::vector<TetVertices>& tets_out, std::vector<Vec3>& new_points_out,
                      std::string& failure, FrontReport* report)
{
    const auto start = std::chrono::steady_clock::now();
    if (!setup(failure)) return false;
    compute_components();
    build_grid();
    for (int f = 0; f < static_cast<int>(front_.vertices.size()); ++f)
        if (front_.alive[f]) front_.push(f);

    bool closed = false;
    for (int round = 0;; ++round)
    {
        const bool done = advance();
        if (done)
        {
            closed = true;
            break;
        }
        if (iterations_ > iteration_budget_)
        {
            failure = "advancing front: iteration budget exhausted";
            break;
        }
        leftover_groups_ += close_leftovers();
        if (front_.alive_count == 0)
        {
            closed = true;
            break;
        }
        if (round >= options_.max_retreat_rounds)
        {
            std::ostringstream out;
            out << "advancing front: " << front_.alive_count << " faces still open after " << round
                << " retreat rounds";
            failure = out.str();
            break;
        }
        if (!retreat())
        {
            failure = "advancing front: stuck with nothing to retreat";
            break;
        }
        ++retreat_rounds_;
    }
    if (!closed) return false;

    // new points still used by a tet, in creation order
    const int n = static_cast<int>(points_.size());
    std::vector<int> output_id(n, -1);
    for (int v = 0; v < num_input_vertices_; ++v) output_id[v] = local_to_global_[v];
    std::vector<std::uint8_t> used(n, 0);
    for (const TetVertices& t : tets_)
        for (int v : t) used[v] = 1;
    const int first_new = static_cast<int>(input_points_.size());
    const std::size_t old_points = new_points_out.size();
    int next = first_new + static_cast<int>(old_points);
    for (int v = num_input_vertices_; v < n; ++v)
        if (used[v])
        {
            output_id[v] = next++;
            new_points_out.push_back(points_[v]);
        }
    tets_out.reserve(tets_out.size() + tets_.size());
    for (const TetVertices& t : tets_)
        tets_out.push_back({output_id[t[0]], output_id[t[1]], output_id[t[2]], output_id[t[3]]});
    if (report)
    {
        report->tets = static_cast<long>(tets_.size());
        report->new_points = static_cast<long>(new_points_out.size() - old_points);
        report->retreat_rounds = retreat_rounds_;
        report->leftover_groups = leftover_groups_;
        report->seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    }
    return true;
}

}  // namespace detail::front_mesher

bool advance_front(const std::vector<Vec3>& points, const std::vector<Triangle>& faces,
                   const SizeField* field, const AdvancingFrontOptions& options,
                   std::vector<TetVertices>& tets, std::vector<Vec3>& new_points,
                   std::string& failure, FrontReport* report)
{
    if (faces.empty())
    {
        failure = "advancing front: no faces";
        return false;
    }
    detail::front_mesher::FrontMesher mesher(points, faces, field, options);
    return mesher.run(tets, new_points, failure, report);
}

}  // namespace hdimesh::volume
