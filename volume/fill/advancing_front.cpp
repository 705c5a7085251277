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
#include "volume/fill/cavity.h"
#include "volume/fill/detail/cavity_stages.h"
#include "volume/fill/detail/front.h"
#include "volume/mesh/predicates.h"
#include "volume/mesh/tet_tables.h"

namespace hdimesh::volume
{
namespace
{
using detail::Front;

constexpr double kTwoThirdsRoot = 0.816496580927726;  // sqrt(2/3): a regular tet's height / edge
constexpr double kMinSizeFactor = 0.6;                // d never below this times the face's edge
constexpr double kMaxSizeFactor = 1.6;                // ... nor above this
constexpr double kPreferExisting = 0.8;       // an existing vertex wins at this fraction of P*'s Qe
constexpr double kSearchRadius = 0.7;         // vertex candidates within this times d of P* ...
constexpr double kRadiusGrowth = 0.5;         // ... plus this times d per failure
constexpr double kVolumeFloor = 1e-6;         // 6 V >= this times the face's mean edge cubed
constexpr double kCrowdingRelax = 0.8;        // the new-point distance shrinks so per failure
constexpr int kExtraAttempts = 2;             // attempts at the last floor before a face is stuck
constexpr double kGridCellFactor = 1.5;       // grid cell = this times the typical size
constexpr int kBruteForceFaces = 256;         // a front this small is searched in one cell
constexpr double kRetreatPreferFactor = 0.6;  // existing vertices win more easily per retreat
constexpr int kRetreatRings = 1;    // tet layers a retreat clears beyond the open faces, at most
constexpr double kFoldSine = 1e-7;  // a new face this flat against a front face folds

struct Box
{
    Vec3 lo, hi;
    bool overlaps(const Box& o) const
    {
        return lo[0] <= o.hi[0] && o.lo[0] <= hi[0] && lo[1] <= o.hi[1] && o.lo[1] <= hi[1] &&
               lo[2] <= o.hi[2] && o.lo[2] <= hi[2];
    }
};

Box box_of(const Vec3& a, const Vec3& b, const Vec3& c)
{
    return {a.cwiseMin(b).cwiseMin(c), a.cwiseMax(b).cwiseMax(c)};
}

/// p strictly on the positive side of the plane through a with normal n (n = (b-a)x(c-a)
/// computed in doubles), decided in floating point only when the margin covers the round-off
/// of the products; false means "not sure or not outside", the exact test decides then.
bool surely_positive(const Vec3& a, const Vec3& n, double n_scale, const Vec3& p)
{
    const Vec3 d = p - a;
    const double value = n.dot(d);
    const double bound = 1e-13 * n_scale * (std::abs(d[0]) + std::abs(d[1]) + std::abs(d[2]));
    return value > bound;
}

/// The sizes a cavity's own faces ask for, when no field is given: each input vertex's mean
/// incident edge length, blended by inverse distance, so that sizes cannot drift down as the
/// front's faces shrink (the front would then never close).
class InputSizeField final : public SizeField
{
public:
    void build(const std::vector<Vec3>& points, const std::vector<Triangle>& faces)
    {
        const int n = static_cast<int>(points.size());
        std::vector<double> sum(n, 0.0);
        std::vector<int> count(n, 0);
        for (const Triangle& t : faces)
            for (int k = 0; k < 3; ++k)
            {
                const double length = (points[t[k]] - points[t[(k + 1) % 3]]).norm();
                sum[t[k]] += length;
                sum[t[(k + 1) % 3]] += length;
                count[t[k]] += 1;
                count[t[(k + 1) % 3]] += 1;
            }
        // a large input is sampled evenly: the blend is smooth and the query stays cheap
        const int step = std::max(1, n / kMaxSamples);
        samples_.clear();
        sizes_.clear();
        for (int v = 0; v < n; v += step)
            if (count[v] > 0)
            {
                samples_.push_back(points[v]);
                sizes_.push_back(sum[v] / count[v]);
            }
    }

    double size(const Vec3& p) const override
    {
        double weighted = 0, total = 0;
        for (std::size_t k = 0; k < samples_.size(); ++k)
        {
            const double d2 = (samples_[k] - p).squaredNorm();
            const double w = 1.0 / (d2 * d2 + 1e-300);
            weighted += w * sizes_[k];
            total += w;
        }
        return weighted / total;
    }

private:
    static constexpr int kMaxSamples = 1024;
    std::vector<Vec3> samples_;
    std::vector<double> sizes_;
};

class FrontMesher
{
public:
    FrontMesher(const std::vector<Vec3>& points, const std::vector<Triangle>& faces,
                const SizeField* field, const AdvancingFrontOptions& options)
        : input_points_(points), input_faces_(faces), field_(field), options_(options)
    {
    }

    bool run(std::vector<TetVertices>& tets_out, std::vector<Vec3>& new_points_out,
             std::string& failure, FrontReport* report);

private:
    bool setup(std::string& failure);
    void build_grid();
    void compute_components();
    /// Per vertex, the smallest vertex id of its group: the live front faces joined through
    /// shared vertices (a vertex on no live face is its own group).
    std::vector<int> front_vertex_groups() const;
    bool advance();  // true when the front is empty
    bool attempt(int face);
    void gather_vertices(const Box& region);
    void gather_faces(int face, const Box& region);
    bool valid_tet(int face, int p, bool is_new);
    bool folds_onto(const TetVertices& tet, int shared_mask, const Triangle& t) const;
    void commit(int face, int p);
    void add_face(const Triangle& t);
    void remove_face(int id);
    int close_leftovers();
    bool retreat();
    float face_size(const Triangle& t) const;
    std::uint64_t order_key(const Triangle& t) const;

    // input
    const std::vector<Vec3>& input_points_;
    const std::vector<Triangle>& input_faces_;
    const SizeField* field_;
    const AdvancingFrontOptions& options_;
    InputSizeField input_sizes_;  // the field when none is given

    // local numbering: input vertices first (global id in local_to_global_), then new points
    std::vector<int> local_to_global_;
    int num_input_vertices_ = 0;
    std::vector<Vec3> points_;
    std::vector<int> component_;  // per point
    std::vector<int> layer_;      // per point: 0 on the input, a new point one above its base
    std::vector<std::uint8_t> in_grid_;
    std::vector<TetVertices> tets_;
    Vec3 order_origin_ = Vec3::Zero();  // the input's box, for the Z-order keys
    double order_inverse_extent_ = 1.0;
    double order_scale_ = 1.0;

    Front front_;
    detail::BucketGrid grid_;
    bool use_grid_ = false;

    // scratch of one attempt, reused so the inner loop does not allocate
    std::vector<int> local_vertices_;
    std::vector<detail::BucketGrid::FaceEntry> local_faces_;
    struct Candidate
    {
        double quality;
        int vertex;  // -1: the new point new_positions_[slot]
        int slot;
    };
    std::vector<Candidate> candidates_;
    std::vector<std::uint32_t> vertex_stamp_;  // valid_tet's per-vertex masks, by call
    std::vector<std::uint8_t> vertex_mask_;
    std::uint32_t stamp_ = 0;
    int last_blocker_ = -1;  // index in local_faces_ of the face that refused the last candidate
    std::array<Vec3, 3> new_positions_;

    long iteration_budget_ = 0;
    long iterations_ = 0;
    int retreat_rounds_ = 0;
    int leftover_groups_ = 0;
};

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

/// True when front face t, sharing an edge with a new side face of `tet`, lies flat against it
/// on the same side of the edge: the pocket between them would need a tet flat in doubles.
bool FrontMesher::folds_onto(const TetVertices& tet, int shared_mask, const Triangle& t) const
{
    int edge[2], n = 0, w = -1;
    for (int j = 0; j < 4; ++j)
        if (shared_mask & (1 << j)) edge[n++] = tet[j];
    for (int v : t)
        if (v != edge[0] && v != edge[1]) w = v;
    const Vec3 &X = points_[edge[0]], &Y = points_[edge[1]], &W = points_[w];
    const Vec3 e = Y - X;
    const double e2 = e.squaredNorm();
    if (!(e2 > 0)) return false;
    const Vec3 uw = (W - X) - e * ((W - X).dot(e) / e2);
    // the tet's faces through the edge other than the base (which leaves the front)
    for (int j = 0; j < 4; ++j)
    {
        const int q = tet[j];
        if (q == edge[0] || q == edge[1]) continue;
        int other = -1;
        for (int k = 0; k < 4; ++k)
            if (tet[k] != edge[0] && tet[k] != edge[1] && tet[k] != q) other = tet[k];
        // the face (edge, q) is the base when the fourth vertex is the apex
        if (other == tet[3]) continue;
        const Vec3& Q = points_[q];
        const Vec3 uq = (Q - X) - e * ((Q - X).dot(e) / e2);
        if (!(uq.dot(uw) > 0)) continue;
        const double sine = uq.cross(uw).norm() / (uq.norm() * uw.norm());
        if (sine < kFoldSine && front_.find({edge[0], edge[1], q}) < 0) return true;
    }
    return false;
}

bool FrontMesher::valid_tet(int face, int p, bool is_new)
{
    const Triangle& base = front_.vertices[face];
    const int a = base[0], b = base[1], c = base[2];
    const Vec3 &A = points_[a], &B = points_[b], &C = points_[c], &P = points_[p];
    if (orient3d(A, B, C, P) <= 0) return false;

    // A new face that is already on the front the same way would overlap the tets behind it.
    const std::array<Triangle, 3> sides{{{a, b, p}, {b, c, p}, {c, a, p}}};
    if (!is_new)
        for (const Triangle& s : sides)
        {
            const int g = front_.find(s);
            if (g >= 0 && same_orientation(s, front_.vertices[g])) return false;
        }

    const TetVertices tet{a, b, c, p};
    const Box tet_box{A.cwiseMin(B).cwiseMin(C).cwiseMin(P), A.cwiseMax(B).cwiseMax(C).cwiseMax(P)};
    // the four face planes of the tet, outward normals, for the floating-point quick rejects
    std::array<Vec3, 4> normal, origin;
    std::array<double, 4> scale;
    for (int i = 0; i < 4; ++i)
    {
        const auto& fv = tet::kFaceVertices[i];
        const Vec3 &u = points_[tet[fv[0]]], &v = points_[tet[fv[1]]], &w = points_[tet[fv[2]]];
        const Vec3 e1 = v - u, e2 = w - u;
        normal[i] = e1.cross(e2);
        origin[i] = u;
        scale[i] = (e1.cwiseAbs().sum()) * (e2.cwiseAbs().sum());
    }
    auto surely_outside = [&](int i, int v) {
        return surely_positive(origin[i], normal[i], scale[i], points_[v]);
    };
    // Per vertex, once per call (a front vertex is in about six of the local faces): bit i when
    // it is surely outside face plane i or a vertex of face i; bit 4 + j when it is tet[j].
    if (vertex_stamp_.size() < points_.size())
    {
        vertex_stamp_.resize(points_.size() + points_.size() / 2 + 16, 0);
        vertex_mask_.resize(vertex_stamp_.size(), 0);
    }
    if (++stamp_ == 0)
    {
        std::fill(vertex_stamp_.begin(), vertex_stamp_.end(), 0);
        stamp_ = 1;
    }
    for (int j = 0; j < 4; ++j)
    {
        vertex_stamp_[tet[j]] = stamp_;
        vertex_mask_[tet[j]] = static_cast<std::uint8_t>((0xF & ~(1 << j)) | (1 << (4 + j)));
    }
    auto mask_of = [&](int v) {
        if (vertex_stamp_[v] != stamp_)
        {
            vertex_stamp_[v] = stamp_;
            std::uint8_t m = 0;
            for (int i = 0; i < 4; ++i)
                if (surely_outside(i, v)) m |= static_cast<std::uint8_t>(1 << i);
            vertex_mask_[v] = m;
        }
        return vertex_mask_[v];
    };

    // true when front face `entry` forbids the tet
    auto blocks = [&](const detail::BucketGrid::FaceEntry& entry) {
        const Triangle& t = entry.vertices;
        if (!tet_box.overlaps({Vec3(entry.lo[0], entry.lo[1], entry.lo[2]),
                               Vec3(entry.hi[0], entry.hi[1], entry.hi[2])}))
            return false;
        const std::uint8_t m0 = mask_of(t[0]), m1 = mask_of(t[1]), m2 = mask_of(t[2]);
        const int shared_mask = (m0 | m1 | m2) >> 4;
        const int shared = ((m0 >> 4) != 0) + ((m1 >> 4) != 0) + ((m2 >> 4) != 0);
        if (shared == 3) return false;  // the face the new tet closes against
        if (shared == 2 && folds_onto(tet, shared_mask, t)) return true;
        // quick reject: every vertex of t strictly outside one face plane or on it as a vertex
        if (m0 & m1 & m2 & 0xF) return false;
        // quick reject: the tet's other vertices strictly on one side of t's plane
        {
            const Vec3 &u = points_[t[0]], e1 = points_[t[1]] - u, e2 = points_[t[2]] - u;
            const Vec3 n = e1.cross(e2);
            const double n_scale = e1.cwiseAbs().sum() * e2.cwiseAbs().sum();
            int above = 0, below = 0, others = 0;
            for (int j = 0; j < 4; ++j)
            {
                if (shared_mask & (1 << j)) continue;
                ++others;
                const Vec3& X = points_[tet[j]];
                above += surely_positive(u, n, n_scale, X);
                below += surely_positive(u, -n, n_scale, X);
            }
            if (above == others || below == others) return false;
        }
        return tet_triangle_intersect(points_, tet, t);
    };
    // The face that refused the attempt's last candidate is tried first: the same obstacle
    // usually stands in the way of the next ones.
    if (last_blocker_ >= 0 && blocks(local_faces_[last_blocker_])) return false;
    for (std::size_t k = 0; k < local_faces_.size(); ++k)
        if (static_cast<int>(k) != last_blocker_ && blocks(local_faces_[k]))
        {
            last_blocker_ = static_cast<int>(k);
            return false;
        }

    for (int v : local_vertices_)
    {
        if (v == a || v == b || v == c || v == p) continue;
        const Vec3& X = points_[v];
        if (X[0] < tet_box.lo[0] || X[0] > tet_box.hi[0] || X[1] < tet_box.lo[1] ||
            X[1] > tet_box.hi[1] || X[2] < tet_box.lo[2] || X[2] > tet_box.hi[2])
            continue;
        bool outside = false;
        for (int i = 0; i < 4 && !outside; ++i) outside = surely_outside(i, v);
        if (outside) continue;
        if (point_in_tet(points_, v, tet)) return false;
    }
    return true;
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
    // Existing vertices scoring >= 0.8 of the best new point first, then new points, then the
    // other vertices; by quality inside each class, ties by vertex id.
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

/// Closes the small groups of the front left over by the small-cavity stages; returns how many.
int FrontMesher::close_leftovers()
{
    const int n = static_cast<int>(points_.size());
    const std::vector<int> group = front_vertex_groups();
    auto root = [&group](int v) { return group[v]; };
    std::vector<int> open;
    for (int f = 0; f < static_cast<int>(front_.vertices.size()); ++f)
        if (front_.alive[f]) open.push_back(f);
    // groups in the order of their smallest face id
    std::vector<std::pair<int, int>> by_group;  // (root, face)
    for (int f : open) by_group.push_back({root(front_.vertices[f][0]), f});
    std::stable_sort(by_group.begin(), by_group.end(),
                     [](const auto& x, const auto& y) { return x.first < y.first; });
    CavityOptions cavity_options;
    cavity_options.max_exhaustive_points = options_.max_leftover_points;
    int closed = 0;
    std::vector<int> group_faces, group_vertices;
    for (std::size_t i = 0; i < by_group.size();)
    {
        std::size_t j = i;
        group_faces.clear();
        while (j < by_group.size() && by_group[j].first == by_group[i].first)
            group_faces.push_back(by_group[j++].second);
        i = j;
        group_vertices.clear();
        for (int f : group_faces)
            for (int v : front_.vertices[f]) group_vertices.push_back(v);
        std::sort(group_vertices.begin(), group_vertices.end());
        group_vertices.erase(std::unique(group_vertices.begin(), group_vertices.end()),
                             group_vertices.end());
        if (static_cast<int>(group_vertices.size()) > options_.max_leftover_points) continue;
        std::vector<Vec3> group_points;
        for (int v : group_vertices) group_points.push_back(points_[v]);
        auto local = [&](int v) {
            return static_cast<int>(
                std::lower_bound(group_vertices.begin(), group_vertices.end(), v) -
                group_vertices.begin());
        };
        std::vector<Triangle> outward;
        for (int f : group_faces)
        {
            const Triangle& t = front_.vertices[f];
            outward.push_back({local(t[0]), local(t[2]), local(t[1])});
        }
        CavityFill fill;
        if (!detail::fill_small_cavity(group_points, outward, cavity_options, fill)) continue;
        // The group is closed, but another part of the front might lie inside it; and a tet
        // flat in doubles would fail the checker's volume test (a sliver is kept: a flat pocket
        // has no other fill, the optimizer takes it apart).
        const int m = static_cast<int>(group_vertices.size());
        std::vector<Vec3> fill_points = group_points;
        fill_points.insert(fill_points.end(), fill.new_points.begin(), fill.new_points.end());
        bool clear = true;
        for (const TetVertices& t : fill.tets)
            if (!(signed_volume(fill_points[t[0]], fill_points[t[1]], fill_points[t[2]],
                                fill_points[t[3]]) > 0))
                clear = false;
        for (int v = 0; v < n && clear; ++v)
        {
            if (front_.valence[v] == 0 ||
                std::binary_search(group_vertices.begin(), group_vertices.end(), v))
                continue;
            fill_points.push_back(points_[v]);
            const int probe = static_cast<int>(fill_points.size()) - 1;
            for (const TetVertices& t : fill.tets)
                if (point_in_tet(fill_points, probe, t))
                {
                    clear = false;
                    break;
                }
            fill_points.pop_back();
        }
        if (!clear) continue;
        std::vector<int> global(m + fill.new_points.size());
        for (int k = 0; k < m; ++k) global[k] = group_vertices[k];
        for (std::size_t k = 0; k < fill.new_points.size(); ++k)
        {
            global[m + k] = static_cast<int>(points_.size());
            points_.push_back(fill.new_points[k]);
            front_.valence.push_back(0);
            component_.push_back(0);
            in_grid_.push_back(0);
            layer_.push_back(0);
        }
        for (const TetVertices& t : fill.tets)
            tets_.push_back({global[t[0]], global[t[1]], global[t[2]], global[t[3]]});
        for (int f : group_faces) remove_face(f);
        ++closed;
    }
    return closed;
}

/// Netgen's RemoveProblem: removes every tet with a vertex on an open face and the new points
/// nothing uses any more; the freed faces rejoin the front with their failures forgotten.
bool FrontMesher::retreat()
{
    const int n = static_cast<int>(points_.size());
    std::vector<std::uint8_t> on_front(n, 0);
    for (int v = 0; v < n; ++v) on_front[v] = front_.valence[v] > 0;
    // later rounds also clear the tets one layer beyond: a wider region re-advances more
    // volume and strands more faces than it frees
    const int rings = std::min(retreat_rounds_, kRetreatRings);
    for (int ring = 0; ring < rings; ++ring)
    {
        std::vector<std::uint8_t> grown = on_front;
        for (const TetVertices& t : tets_)
            if (on_front[t[0]] || on_front[t[1]] || on_front[t[2]] || on_front[t[3]])
                for (int v : t) grown[v] = 1;
        on_front.swap(grown);
    }
    std::vector<TetVertices> kept;
    kept.reserve(tets_.size());
    std::vector<TetVertices> removed;
    for (const TetVertices& t : tets_)
    {
        if (on_front[t[0]] || on_front[t[1]] || on_front[t[2]] || on_front[t[3]])
            removed.push_back(t);
        else
            kept.push_back(t);
    }
    if (removed.empty()) return false;
    tets_.swap(kept);
    for (const TetVertices& t : removed)
        for (int i = 0; i < 4; ++i)
        {
            const auto& fv = tet::kFaceVertices[i];
            const Triangle outward{t[fv[0]], t[fv[1]], t[fv[2]]};
            const int g = front_.find(outward);
            if (g >= 0)
            {
                assert(same_orientation(outward, front_.vertices[g]));
                front_.remove(g);
            }
            else
            {
                const Triangle inward{outward[0], outward[2], outward[1]};
                const int lowest =
                    std::min({layer_[inward[0]], layer_[inward[1]], layer_[inward[2]]});
                front_.add(inward, lowest, face_size(inward), order_key(inward));
            }
        }
    // every surviving face starts over: heap, grid and components rebuilt from the front
    front_.heap.clear();
    for (int f = 0; f < static_cast<int>(front_.vertices.size()); ++f)
        if (front_.alive[f])
        {
            front_.fail[f] = 0;
            front_.push(f);
        }
    compute_components();
    build_grid();
    return true;
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

}  // namespace

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
    FrontMesher mesher(points, faces, field, options);
    return mesher.run(tets, new_points, failure, report);
}

}  // namespace hdimesh::volume
