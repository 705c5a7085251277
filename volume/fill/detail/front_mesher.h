#pragma once
// The advancing-front mesher's machinery (volume/fill/advancing_front.h): its tuning constants,
// the fallback size field and the FrontMesher itself, whose methods are spread over
// advancing_front.cpp (setup, the loop, commits), fill/detail/front_validity.cpp (the tests a
// candidate tet must pass) and fill/detail/front_recovery.cpp (leftovers and retreat).

#include <algorithm>
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "volume/fill/advancing_front.h"
#include "volume/fill/detail/front.h"
#include "volume/size/size_fields.h"

namespace hdimesh::volume::detail::front_mesher
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

inline Box box_of(const Vec3& a, const Vec3& b, const Vec3& c)
{
    return {a.cwiseMin(b).cwiseMin(c), a.cwiseMax(b).cwiseMax(c)};
}

/// p strictly on the positive side of the plane through a with normal n (n = (b-a)x(c-a)
/// computed in doubles), decided in floating point only when the margin covers the round-off
/// of the products; false means "not sure or not outside", the exact test decides then.
inline bool surely_positive(const Vec3& a, const Vec3& n, double n_scale, const Vec3& p)
{
    const Vec3 d = p - a;
    const double value = n.dot(d);
    const double bound = 1e-13 * n_scale * (std::abs(d[0]) + std::abs(d[1]) + std::abs(d[2]));
    return value > bound;
}

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
    void sort_candidates(double ideal_quality);
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

}  // namespace hdimesh::volume::detail::front_mesher
