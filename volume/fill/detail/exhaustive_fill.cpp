// Stage 3 of the cavity cascade: small polyhedron reconnection, a branch and bound over the
// tetrahedralizations of a cavity's points (plus optional Steiner candidates) that keeps the
// one with the best worst Qe. The search is an advancing front that backtracks: the open faces
// bound the part not yet filled; a tet is put on the open face with the fewest apexes left.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "volume/fill/detail/cavity_stages.h"
#include "volume/fill/detail/kernel.h"
#include "volume/mesh/predicates.h"
#include "volume/mesh/tet_tables.h"

namespace hdimesh::volume::detail
{

namespace
{

/// The point bitmasks are 32 bits wide.
constexpr int kMaxPoints = 32;
constexpr std::uint16_t kNoFace = 0xffff;
/// Optional Steiner points offered to one search: each one widens every branching.
constexpr int kMaxCandidates = 4;

struct Box
{
    Vec3 lo, hi;
    bool apart(const Box& other) const
    {
        return (hi.array() < other.lo.array()).any() || (other.hi.array() < lo.array()).any();
    }
};

template <std::size_t N>
Box box_of(const std::vector<Vec3>& points, const std::array<int, N>& ids)
{
    Box box{points[ids[0]], points[ids[0]]};
    for (std::size_t k = 1; k < N; ++k)
    {
        box.lo = box.lo.cwiseMin(points[ids[k]]);
        box.hi = box.hi.cwiseMax(points[ids[k]]);
    }
    return box;
}

/// binomial(n, k) for n < kMaxPoints, k <= 4.
struct BinomialTable
{
    std::array<std::array<int, 5>, kMaxPoints> value{};
    BinomialTable()
    {
        for (int n = 0; n < kMaxPoints; ++n)
        {
            value[n][0] = 1;
            for (int k = 1; k <= 4; ++k)
                value[n][k] = n == 0 ? 0 : value[n - 1][k - 1] + value[n - 1][k];
        }
    }
};

/// The rank of the sorted quadruple in the combinatorial number system: one slot per tet
/// whatever the order of its vertices.
int quadruple_rank(std::array<int, 4> v)
{
    static const BinomialTable binomial;
    auto order = [&v](int i, int j) {
        if (v[i] > v[j]) std::swap(v[i], v[j]);
    };
    order(0, 1);
    order(2, 3);
    order(0, 2);
    order(1, 3);
    order(1, 2);
    const auto& c = binomial.value;
    return c[v[0]][1] + c[v[1]][2] + c[v[2]][3] + c[v[3]][4];
}

/// The best tetrahedralization found: local tets and their worst Qe.
struct SearchResult
{
    bool found = false;
    double quality = 0;
    std::vector<std::array<int, 4>> tets;
};

/// One search over fixed points: 0 .. num_required-1 are the cavity's vertices (all must be
/// used), the rest optional Steiner candidates strictly inside. It can pause when its node
/// budget runs out and go on later from where it was.
class ReconnectionSearch
{
public:
    ReconnectionSearch(const std::vector<Vec3>& points, int num_required,
                       const std::vector<Triangle>& faces, double floor)
        : points_(points), num_points_(static_cast<int>(points.size())),
          num_required_(num_required), floor_(floor)
    {
        const int n = num_points_;
        const int quadruples = n < 4 ? 1 : n * (n - 1) * (n - 2) * (n - 3) / 24;
        orientation_.assign(static_cast<std::size_t>(n) * n * n * n, kUnknown);
        quality_.assign(quadruples, -1.0);
        face_of_.assign(static_cast<std::size_t>(n) * n * n, kNoFace);
        valence_.assign(n, 0);
        for (const auto& f : faces) add_front_face(f);
    }

    long nodes() const { return nodes_; }
    const SearchResult& best() const { return best_; }

    /// Searches on for at most `more_nodes` nodes. true when the whole tree has been searched
    /// (best() is then the max-min fill above the floor, or proven absent).
    bool search(long more_nodes)
    {
        const long budget = nodes_ + std::max(more_nodes, 0L);
        if (finished_) return true;
        if (!started_)
        {
            started_ = true;
            if (!open_step()) return finished_ = true;
        }
        while (!steps_.empty())
        {
            Step& step = steps_.back();
            if (step.placed) unplace(step);
            bool placed = false;
            if (step.worst_before > floor_)
                while (step.next < step.num_candidates)
                {
                    if (nodes_ >= budget) return false;  // paused: this step goes on next time
                    if (try_place(step, step.candidates[step.next++]))
                    {
                        placed = true;
                        break;
                    }
                }
            if (!placed)
            {
                add_front_face(step.base);
                steps_.pop_back();
                continue;
            }
            if (front_.empty())
                record();
            else
                open_step();  // when none is pushed (a dead end), this step's next apex comes
        }
        return finished_ = true;
    }

private:
    static constexpr std::int8_t kUnknown = 2;

    struct Step
    {
        Triangle base{};
        std::array<std::uint8_t, kMaxPoints> candidates{};
        int num_candidates = 0;
        int next = 0;
        double worst_before = 0;  // worst Qe of the tets below this step
        bool placed = false;
        int apex = -1;
        double quality = 0;
        std::uint32_t newly_covered = 0;
        bool newly_used = false;
    };

    std::size_t quadruple_slot(int a, int b, int c, int d) const
    {
        return ((static_cast<std::size_t>(a) * num_points_ + b) * num_points_ + c) * num_points_ +
               d;
    }

    /// orient3d of four points by id, each quadruple computed once and stored for its 24
    /// orders (0 for a repeated id).
    int orientation(int a, int b, int c, int d)
    {
        if (a == b || a == c || a == d || b == c || b == d || c == d) return 0;
        const std::int8_t cached = orientation_[quadruple_slot(a, b, c, d)];
        if (cached != kUnknown) return cached;
        const int sign = orient3d(points_[a], points_[b], points_[c], points_[d]);
        std::array<int, 4> v = {a, b, c, d};
        std::array<int, 4> order = {0, 1, 2, 3};
        do
        {
            // the parity of the permutation `order`, by counting inversions
            int inversions = 0;
            for (int i = 0; i < 4; ++i)
                for (int j = i + 1; j < 4; ++j) inversions += order[i] > order[j];
            orientation_[quadruple_slot(v[order[0]], v[order[1]], v[order[2]], v[order[3]])] =
                static_cast<std::int8_t>(inversions % 2 == 0 ? sign : -sign);
        } while (std::next_permutation(order.begin(), order.end()));
        return sign;
    }

    /// Qe of the tet on outward face f with apex p, or -1 when not positive.
    double cone_quality(const Triangle& f, int p)
    {
        const std::array<int, 4> tet = cone_tet(f, p);
        if (orientation(tet[0], tet[1], tet[2], tet[3]) <= 0) return -1.0;
        double& cached = quality_[quadruple_rank(tet)];
        if (cached < 0.0)
            cached = std::max(
                tet_quality(points_[tet[0]], points_[tet[1]], points_[tet[2]], points_[tet[3]]),
                std::numeric_limits<double>::min());
        return cached;
    }

    /// v in the closed positive tet, from the cached signs.
    bool contains(const std::array<int, 4>& t, int v)
    {
        return orientation(v, t[1], t[2], t[3]) >= 0 && orientation(t[0], v, t[2], t[3]) >= 0 &&
               orientation(t[0], t[1], v, t[3]) >= 0 && orientation(t[0], t[1], t[2], v) >= 0;
    }

    /// A plane that shows, from the cached signs, that the closed tet and the closed triangle
    /// meet at most in their shared vertices: a face plane of the tet with every vertex of the
    /// triangle outside or shared, or the triangle's plane with every unshared vertex of the
    /// tet strictly on one side. false means: ask the exact intersection test.
    bool separated(const std::array<int, 4>& t, const Triangle& g)
    {
        auto in_tet = [&](int v) { return v == t[0] || v == t[1] || v == t[2] || v == t[3]; };
        for (const auto& fv : tet::kFaceVertices)
        {
            bool outside = true;
            for (int k = 0; k < 3 && outside; ++k)
            {
                const int side = orientation(t[fv[0]], t[fv[1]], t[fv[2]], g[k]);
                outside = side > 0 || (side == 0 && in_tet(g[k]));
            }
            if (outside) return true;
        }
        int above = 0, below = 0;
        for (int v : t)
        {
            if (v == g[0] || v == g[1] || v == g[2]) continue;
            const int side = orientation(g[0], g[1], g[2], v);
            if (side > 0)
                ++above;
            else if (side < 0)
                ++below;
            else
                return false;
        }
        return above == 0 || below == 0;
    }

    std::size_t face_slot(int a, int b, int c) const
    {
        return (static_cast<std::size_t>(a) * num_points_ + b) * num_points_ + c;
    }
    int find_face(int a, int b, int c) const { return face_of_[face_slot(a, b, c)]; }
    void set_face(const Triangle& f, std::uint16_t index)
    {
        face_of_[face_slot(f[0], f[1], f[2])] = index;
        face_of_[face_slot(f[1], f[2], f[0])] = index;
        face_of_[face_slot(f[2], f[0], f[1])] = index;
    }
    void add_front_face(const Triangle& f)
    {
        set_face(f, static_cast<std::uint16_t>(front_.size()));
        front_.push_back(f);
        for (int v : f) ++valence_[v];
    }
    void remove_front_face(int index)
    {
        const Triangle f = front_[index];
        set_face(f, kNoFace);
        for (int v : f) --valence_[v];
        if (index + 1 != static_cast<int>(front_.size()))
        {
            front_[index] = front_.back();
            set_face(front_[index], static_cast<std::uint16_t>(index));
        }
        front_.pop_back();
    }

    bool available_apex(int v) const
    {
        if (valence_[v] > 0) return true;
        const std::uint32_t bit = 1u << v;
        return v >= num_required_ && !(used_ & bit) && !(covered_ & bit);
    }

    /// Picks the open face with the fewest apexes that could still beat the floor (ties: the
    /// first in the front), takes it off the front and pushes its step with the apexes by
    /// decreasing Qe. false (nothing pushed) when some face has no apex left.
    bool open_step()
    {
        int best_face = -1, best_count = kMaxPoints + 1;
        for (int i = 0; i < static_cast<int>(front_.size()); ++i)
        {
            const Triangle& f = front_[i];
            int count = 0;
            for (int v = 0; v < num_points_ && count < best_count; ++v)
            {
                if (v == f[0] || v == f[1] || v == f[2] || !available_apex(v)) continue;
                if (cone_quality(f, v) > floor_) ++count;
            }
            if (count == 0) return false;
            if (count < best_count)
            {
                best_count = count;
                best_face = i;
            }
            if (best_count == 1) break;  // a forced move: no face can be better
        }
        Step step;
        step.base = front_[best_face];
        step.worst_before = steps_.empty()
                                ? std::numeric_limits<double>::max()
                                : std::min(steps_.back().worst_before, steps_.back().quality);
        std::array<double, kMaxPoints> quality{};
        for (int v = 0; v < num_points_; ++v)
        {
            if (v == step.base[0] || v == step.base[1] || v == step.base[2] || !available_apex(v))
                continue;
            const double q = cone_quality(step.base, v);
            if (q <= floor_) continue;
            quality[v] = q;
            step.candidates[step.num_candidates++] = static_cast<std::uint8_t>(v);
        }
        std::stable_sort(step.candidates.begin(), step.candidates.begin() + step.num_candidates,
                         [&](std::uint8_t u, std::uint8_t v) { return quality[u] > quality[v]; });
        remove_front_face(best_face);
        steps_.push_back(step);
        return true;
    }

    /// The tet on the step's base with this apex is put in when it is positive, beats the
    /// floor, holds no open vertex and meets no open face but the ones it closes.
    bool try_place(Step& step, int apex)
    {
        const Triangle& f = step.base;
        const double q = cone_quality(f, apex);
        if (q <= floor_) return false;
        ++nodes_;
        const std::array<int, 4> tet = cone_tet(f, apex);
        // the three new faces, outward from the tet
        const std::array<Triangle, 3> sides = {Triangle{tet[1], tet[2], tet[3]},
                                               Triangle{tet[0], tet[3], tet[2]},
                                               Triangle{tet[0], tet[1], tet[3]}};
        for (const auto& s : sides)
            if (find_face(s[0], s[2], s[1]) != kNoFace) return false;  // the front folds here
        const Box tet_box = box_of(points_, tet);
        for (int v = 0; v < num_points_; ++v)
        {
            if (valence_[v] == 0 || v == tet[0] || v == tet[1] || v == tet[2] || v == tet[3])
                continue;
            if (tet_box.apart(Box{points_[v], points_[v]})) continue;
            if (contains(tet, v)) return false;
        }
        for (const auto& g : front_)
        {
            if (tet_box.apart(box_of(points_, g)) || separated(tet, g)) continue;
            if (tet_triangle_intersect(points_, tet, g)) return false;
        }
        place(step, apex, q, sides);
        return true;
    }

    void place(Step& step, int apex, double quality, const std::array<Triangle, 3>& sides)
    {
        step.placed = true;
        step.apex = apex;
        step.quality = quality;
        step.newly_used = false;
        if (apex >= num_required_ && !(used_ & (1u << apex)))
        {
            used_ |= 1u << apex;
            step.newly_used = true;
        }
        for (const auto& s : sides)
        {
            const int index = find_face(s[0], s[1], s[2]);
            if (index != kNoFace)
                remove_front_face(index);
            else
                add_front_face({s[0], s[2], s[1]});
        }
        step.newly_covered = 0;
        const std::array<int, 4> tet = cone_tet(step.base, apex);
        for (int v = num_required_; v < num_points_; ++v)
        {
            const std::uint32_t bit = 1u << v;
            if ((used_ & bit) || (covered_ & bit)) continue;
            if (contains(tet, v)) step.newly_covered |= bit;
        }
        covered_ |= step.newly_covered;
    }

    void unplace(Step& step)
    {
        const std::array<int, 4> tet = cone_tet(step.base, step.apex);
        const std::array<Triangle, 3> sides = {Triangle{tet[1], tet[2], tet[3]},
                                               Triangle{tet[0], tet[3], tet[2]},
                                               Triangle{tet[0], tet[1], tet[3]}};
        for (auto it = sides.rbegin(); it != sides.rend(); ++it)
        {
            const Triangle& s = *it;
            const int index = find_face(s[0], s[2], s[1]);
            if (index != kNoFace)
                remove_front_face(index);
            else
                add_front_face(s);
        }
        covered_ &= ~step.newly_covered;
        if (step.newly_used) used_ &= ~(1u << step.apex);
        step.placed = false;
    }

    void record()
    {
        double worst = std::numeric_limits<double>::max();
        for (const auto& s : steps_) worst = std::min(worst, s.quality);
        if (worst <= floor_) return;
        floor_ = worst;
        best_.found = true;
        best_.quality = worst;
        best_.tets.clear();
        for (const auto& s : steps_) best_.tets.push_back(cone_tet(s.base, s.apex));
    }

    const std::vector<Vec3>& points_;
    int num_points_;
    int num_required_;
    double floor_;  // fills must beat it; raised to each one found
    long nodes_ = 0;
    bool started_ = false, finished_ = false;
    SearchResult best_;
    std::vector<std::int8_t> orientation_;
    std::vector<double> quality_;
    std::vector<std::uint16_t> face_of_;
    std::vector<int> valence_;
    std::vector<Triangle> front_;
    std::vector<Step> steps_;
    std::uint32_t used_ = 0;     // optional points that are vertices of placed tets
    std::uint32_t covered_ = 0;  // optional points inside placed tets, lost for good
};

/// The cavity's vertices in increasing id order and the faces over their local numbers.
struct LocalCavity
{
    std::vector<int> global;  // local -> global id
    std::vector<Vec3> points;
    std::vector<Triangle> faces;
};

LocalCavity localize(const std::vector<Vec3>& points, const std::vector<Triangle>& faces)
{
    LocalCavity local;
    for (const auto& f : faces) local.global.insert(local.global.end(), f.begin(), f.end());
    std::sort(local.global.begin(), local.global.end());
    local.global.erase(std::unique(local.global.begin(), local.global.end()), local.global.end());
    for (int g : local.global) local.points.push_back(points[g]);
    for (const auto& f : faces)
    {
        Triangle t;
        for (int k = 0; k < 3; ++k)
            t[k] =
                static_cast<int>(std::lower_bound(local.global.begin(), local.global.end(), f[k]) -
                                 local.global.begin());
        local.faces.push_back(t);
    }
    return local;
}

/// Each Steiner point of the fill moved inside the kernel of its link (the faces opposite it in
/// its tets) to the best point for its own tets, twice round: the search fixed the topology
/// with the candidates where they were. Other tets do not change, so the fill stays valid.
void polish_steiner_points(const std::vector<Vec3>& points, CavityFill& fill)
{
    const int first_new = static_cast<int>(points.size());
    if (fill.new_points.empty()) return;
    // the fill's own vertices, numbered locally: `points` is the whole mesh's, and a copy of it
    // per fill made the mirror's fills quadratic in the mesh (80 MB a fill at 19M tets)
    std::vector<int> ids;
    for (const auto& t : fill.tets) ids.insert(ids.end(), t.begin(), t.end());
    std::sort(ids.begin(), ids.end());
    ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
    auto local = [&](int id) {
        return static_cast<int>(std::lower_bound(ids.begin(), ids.end(), id) - ids.begin());
    };
    std::vector<Vec3> all(ids.size());
    for (std::size_t i = 0; i < ids.size(); ++i)
        all[i] = ids[i] < first_new ? points[ids[i]] : fill.new_points[ids[i] - first_new];
    std::vector<TetVertices> tets;
    tets.reserve(fill.tets.size());
    for (const auto& t : fill.tets)
        tets.push_back({local(t[0]), local(t[1]), local(t[2]), local(t[3])});
    for (int round = 0; round < 2; ++round)
        for (int k = 0; k < static_cast<int>(fill.new_points.size()); ++k)
        {
            if (!std::binary_search(ids.begin(), ids.end(), first_new + k)) continue;
            const int id = local(first_new + k);
            std::vector<Triangle> link;
            double worst_now = std::numeric_limits<double>::max();
            for (const auto& t : tets)
                for (int i = 0; i < 4; ++i)
                    if (t[i] == id)
                    {
                        const auto& fv = tet::kFaceVertices[i];
                        link.push_back({t[fv[0]], t[fv[1]], t[fv[2]]});
                        worst_now = std::min(
                            worst_now, tet_quality(all[t[0]], all[t[1]], all[t[2]], all[t[3]]));
                    }
            Vec3 moved;
            double worst_moved = 0;
            if (best_kernel_point(all, link, moved, worst_moved) && worst_moved > worst_now)
            {
                all[id] = moved;
                fill.new_points[k] = moved;
            }
        }
    double worst = std::numeric_limits<double>::max();
    for (const auto& t : tets)
        worst = std::min(worst, tet_quality(all[t[0]], all[t[1]], all[t[2]], all[t[3]]));
    fill.worst_quality = worst;
}

void write_fill(const LocalCavity& local, const std::vector<Vec3>& search_points,
                const SearchResult& result, const std::vector<Vec3>& points,
                const std::vector<Triangle>& faces, CavityFill& fill)
{
    const int num_required = static_cast<int>(local.global.size());
    std::vector<int> to_global(search_points.size(), -1);
    for (int i = 0; i < num_required; ++i) to_global[i] = local.global[i];
    fill.new_points.clear();
    fill.tets.clear();
    for (const auto& tet : result.tets)
    {
        TetVertices out;
        for (int k = 0; k < 4; ++k)
        {
            int& id = to_global[tet[k]];
            if (id < 0)
            {
                id = static_cast<int>(points.size() + fill.new_points.size());
                fill.new_points.push_back(search_points[tet[k]]);
            }
            out[k] = id;
        }
        fill.tets.push_back(out);
    }
    fill.faces = faces;
    fill.filled = true;
    fill.stage = FillStage::Exhaustive;
    fill.worst_quality = result.quality;
    fill.failure.clear();
    polish_steiner_points(points, fill);
}

struct SteinerCandidates
{
    std::vector<Vec3> points;
    double kernel_cone_quality = -1;  // >= 0 when points is the kernel point alone
};

/// Steiner points the search may use: the kernel point when the kernel is not empty, else one
/// point per group of faces that still has a kernel (groups grown face by face across edges,
/// in face order), at most max_count.
SteinerCandidates steiner_candidates(const std::vector<Vec3>& points,
                                     const std::vector<Triangle>& faces, int max_count)
{
    SteinerCandidates result;
    std::vector<Vec3>& candidates = result.points;
    if (max_count <= 0) return result;
    Vec3 point;
    double quality = 0;
    if (best_kernel_point(points, faces, point, quality))
    {
        candidates.push_back(point);
        result.kernel_cone_quality = quality;
        return result;
    }
    const int num_faces = static_cast<int>(faces.size());
    std::vector<std::vector<int>> neighbours(num_faces);
    {
        std::vector<std::array<int, 3>> edges;  // (lower id, higher id, face)
        for (int f = 0; f < num_faces; ++f)
            for (int k = 0; k < 3; ++k)
            {
                const int a = faces[f][k], b = faces[f][(k + 1) % 3];
                edges.push_back({std::min(a, b), std::max(a, b), f});
            }
        std::sort(edges.begin(), edges.end());
        for (std::size_t i = 0; i + 1 < edges.size(); ++i)
            if (edges[i][0] == edges[i + 1][0] && edges[i][1] == edges[i + 1][1])
            {
                neighbours[edges[i][2]].push_back(edges[i + 1][2]);
                neighbours[edges[i + 1][2]].push_back(edges[i][2]);
            }
        for (auto& list : neighbours) std::sort(list.begin(), list.end());
    }
    std::vector<bool> grouped(num_faces, false);
    for (int seed = 0; seed < num_faces && static_cast<int>(candidates.size()) < max_count; ++seed)
    {
        if (grouped[seed]) continue;
        std::vector<Triangle> group = {faces[seed]};
        std::vector<int> members = {seed}, refused;
        grouped[seed] = true;
        for (std::size_t next = 0; next < members.size(); ++next)
            for (int g : neighbours[members[next]])
            {
                if (grouped[g] || std::find(refused.begin(), refused.end(), g) != refused.end())
                    continue;
                group.push_back(faces[g]);
                Vec3 centre;
                double radius = 0;
                if (kernel_chebyshev_centre(points, group, centre, radius))
                {
                    grouped[g] = true;
                    members.push_back(g);
                }
                else
                {
                    group.pop_back();
                    refused.push_back(g);
                }
            }
        if (members.size() < 4) continue;
        if (best_kernel_point(points, group, point, quality)) candidates.push_back(point);
    }
    return result;
}

}  // namespace

bool fill_exhaustive_above(const std::vector<Vec3>& points, const std::vector<Triangle>& faces,
                           const CavityOptions& options, double quality_floor, CavityFill& fill)
{
    if (faces.size() < 4) return false;
    const int max_points = std::min(options.max_exhaustive_points, kMaxPoints);
    const LocalCavity local = localize(points, faces);
    const int num_required = static_cast<int>(local.points.size());
    if (num_required > max_points) return false;

    const long budget = options.exhaustive_node_budget;
    // the points alone first, so that Steiner points are added only where they pay; half the
    // budget, the rest for the search with candidates if one is needed
    ReconnectionSearch plain(local.points, num_required, local.faces, quality_floor);
    const bool plain_done = plain.search(budget / 2);
    SearchResult best = plain.best();
    std::vector<Vec3> search_points = local.points;
    if (!best.found || best.quality < options.accept_quality)
    {
        const SteinerCandidates candidates =
            steiner_candidates(points, faces, std::min(kMaxCandidates, max_points - num_required));
        if (candidates.points.empty())
        {
            if (!plain_done) plain.search(budget - plain.nodes());
            best = plain.best();
        }
        else
        {
            std::vector<Vec3> with_candidates = local.points;
            with_candidates.insert(with_candidates.end(), candidates.points.begin(),
                                   candidates.points.end());
            double floor = best.found ? best.quality : quality_floor;
            // the kernel point's cone is a fill already: the search looks for better ones
            const bool cone_wins = candidates.kernel_cone_quality > floor;
            if (cone_wins)
            {
                best.found = true;
                best.quality = floor = candidates.kernel_cone_quality;
                best.tets.clear();
                for (const auto& f : local.faces) best.tets.push_back(cone_tet(f, num_required));
            }
            ReconnectionSearch steiner(with_candidates, num_required, local.faces, floor);
            steiner.search(budget - plain.nodes());
            if (steiner.best().found) best = steiner.best();
            if (steiner.best().found || cone_wins) search_points = std::move(with_candidates);
        }
    }
    if (!best.found) return false;
    write_fill(local, search_points, best, points, faces, fill);
    return true;
}

bool fill_exhaustive(const std::vector<Vec3>& points, const std::vector<Triangle>& faces,
                     const CavityOptions& options, CavityFill& fill)
{
    return fill_exhaustive_above(points, faces, options, 0.0, fill);
}

}  // namespace hdimesh::volume::detail
