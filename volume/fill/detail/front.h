#pragma once
// The advancing front's private machinery (volume/fill/advancing_front.cpp): the front faces in
// flat arrays with a hash from the sorted vertex triple, the base-face heap with lazy deletion and
// the uniform bucket grid of front vertices and front-face boxes.

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <cstdint>
#include <vector>

#include "volume/mesh/geometry.h"
#include "volume/mesh/tet_mesh.h"

namespace hdimesh::volume::detail
{

/// Open addressing with linear probing and backward-shift deletion: no tombstones, so a long
/// run of inserts and erases keeps the probe sequences short.
class FaceHash
{
public:
    void reserve(std::size_t faces)
    {
        std::size_t capacity = 16;
        while (capacity < 2 * faces) capacity *= 2;
        if (capacity > slots_.size()) rehash(capacity);
    }

    /// The front id of the face with these (sorted) vertices, or -1.
    int find(const Triangle& key) const
    {
        if (slots_.empty()) return -1;
        for (std::size_t i = home(key);; i = (i + 1) & mask_)
        {
            const Slot& s = slots_[i];
            if (s.id < 0) return -1;
            if (s.key == key) return s.id;
        }
    }

    void insert(const Triangle& key, int id)
    {
        if (2 * (count_ + 1) > slots_.size()) rehash(std::max<std::size_t>(16, 2 * slots_.size()));
        std::size_t i = home(key);
        while (slots_[i].id >= 0)
        {
            assert(slots_[i].key != key);
            i = (i + 1) & mask_;
        }
        slots_[i] = {key, id};
        ++count_;
    }

    void erase(const Triangle& key)
    {
        std::size_t i = home(key);
        while (slots_[i].key != key || slots_[i].id < 0)
        {
            assert(slots_[i].id >= 0);
            i = (i + 1) & mask_;
        }
        // Shift the following run back over the hole so every key stays reachable from home.
        std::size_t hole = i;
        for (std::size_t j = (i + 1) & mask_; slots_[j].id >= 0; j = (j + 1) & mask_)
        {
            const std::size_t h = home(slots_[j].key);
            const bool movable = hole <= j ? (h <= hole || h > j) : (h <= hole && h > j);
            if (movable)
            {
                slots_[hole] = slots_[j];
                hole = j;
            }
        }
        slots_[hole].id = -1;
        --count_;
    }

    std::size_t size() const { return count_; }
    std::size_t memory_bytes() const { return slots_.capacity() * sizeof(Slot); }

private:
    struct Slot
    {
        Triangle key{};
        int id = -1;
    };

    std::size_t home(const Triangle& key) const
    {
        std::uint64_t h = static_cast<std::uint32_t>(key[0]) * 0x9E3779B97F4A7C15ull;
        h ^= static_cast<std::uint32_t>(key[1]) * 0xC2B2AE3D27D4EB4Full + (h >> 29);
        h ^= static_cast<std::uint32_t>(key[2]) * 0x165667B19E3779F9ull + (h >> 31);
        h ^= h >> 33;
        return static_cast<std::size_t>(h) & mask_;
    }

    void rehash(std::size_t capacity)
    {
        std::vector<Slot> old;
        old.swap(slots_);
        slots_.assign(capacity, Slot{});
        mask_ = capacity - 1;
        count_ = 0;
        for (const Slot& s : old)
            if (s.id >= 0) insert(s.key, s.id);
    }

    std::vector<Slot> slots_;
    std::size_t mask_ = 0;
    std::size_t count_ = 0;
};

/// The order of base faces: fewest failures first, then the oldest generation, then the
/// smallest (by size classes a factor 2^(1/4) wide, in Z-order inside a class, so that
/// consecutive faces are near each other), then the smaller id (determinism). `version` tells
/// a stale entry (lazy deletion).
struct HeapEntry
{
    int fail;
    int generation;
    std::uint64_t order;
    int face;
    int version;
};

/// std::push_heap keeps the largest on top: "larger" here is the face to take later.
struct TakenLater
{
    bool operator()(const HeapEntry& x, const HeapEntry& y) const
    {
        if (x.fail != y.fail) return x.fail > y.fail;
        if (x.generation != y.generation) return x.generation > y.generation;
        if (x.order != y.order) return x.order > y.order;
        return x.face > y.face;
    }
};

/// The front: faces oriented with the unmeshed region on their positive side (orient3d of
/// (v0, v1, v2, p) > 0 for p there), so the tet on face f with apex p is (v0, v1, v2, p).
struct Front
{
    std::vector<Triangle> vertices;
    std::vector<int> fail;
    std::vector<int> generation;
    std::vector<float> size;
    std::vector<std::uint64_t> order;  ///< size class, then Z-order key
    std::vector<int> version;          ///< bumped on each heap push: tells stale heap entries
    std::vector<std::uint8_t> alive;
    std::vector<int> free_ids;
    int alive_count = 0;
    FaceHash hash;
    std::vector<int> valence;  ///< per point: alive front faces using it
    std::vector<HeapEntry> heap;

    int find(const Triangle& t) const { return hash.find(sorted_triple(t)); }

    int add(const Triangle& t, int gen, float face_size, std::uint64_t order_key)
    {
        int id;
        if (!free_ids.empty())
        {
            id = free_ids.back();
            free_ids.pop_back();
            vertices[id] = t;
            fail[id] = 0;
            generation[id] = gen;
            size[id] = face_size;
            order[id] = order_key;
            alive[id] = 1;
        }
        else
        {
            id = static_cast<int>(vertices.size());
            vertices.push_back(t);
            fail.push_back(0);
            generation.push_back(gen);
            size.push_back(face_size);
            order.push_back(order_key);
            version.push_back(0);
            alive.push_back(1);
        }
        hash.insert(sorted_triple(t), id);
        for (int v : t) ++valence[v];
        ++alive_count;
        return id;
    }

    void remove(int id)
    {
        assert(alive[id]);
        alive[id] = 0;
        hash.erase(sorted_triple(vertices[id]));
        for (int v : vertices[id]) --valence[v];
        free_ids.push_back(id);
        --alive_count;
    }

    void push(int id)
    {
        ++version[id];
        heap.push_back({fail[id], generation[id], order[id], id, version[id]});
        std::push_heap(heap.begin(), heap.end(), TakenLater());
    }

    /// The next base face (skipping stale entries), or -1 when the heap is empty.
    int top()
    {
        while (!heap.empty())
        {
            const HeapEntry& e = heap.front();
            if (alive[e.face] && version[e.face] == e.version) return e.face;
            std::pop_heap(heap.begin(), heap.end(), TakenLater());
            heap.pop_back();
        }
        return -1;
    }

    void pop()
    {
        std::pop_heap(heap.begin(), heap.end(), TakenLater());
        heap.pop_back();
    }

    std::size_t memory_bytes() const
    {
        return vertices.capacity() * sizeof(Triangle) +
               (fail.capacity() + generation.capacity() + version.capacity() + free_ids.capacity() +
                valence.capacity()) *
                   sizeof(int) +
               size.capacity() * sizeof(float) + order.capacity() * sizeof(std::uint64_t) +
               alive.capacity() + hash.memory_bytes() + heap.capacity() * sizeof(HeapEntry);
    }
};

/// A uniform grid over the domain's box: front vertices (in the cell they fall in) and front
/// faces (in the cell of their box's centre). Each entry carries its position or box, so a query
/// filters without touching the per-face arrays (those random reads dominated the front's time);
/// the caller removes an entry when its vertex or face leaves the front.
class BucketGrid
{
public:
    /// The box in floats rounded outwards: still never misses an overlap, at 40 bytes.
    struct FaceEntry
    {
        std::array<float, 3> lo, hi;
        Triangle vertices;
        int face;
    };

    void init(const Vec3& lo, const Vec3& hi, double cell, long max_cells)
    {
        origin_ = lo;
        const Vec3 extent = (hi - lo).cwiseMax(Vec3::Constant(1e-300));
        double c = std::max(cell, 1e-300);
        for (;;)
        {
            // in double, each side capped: a tiny cell must not overflow the count
            double total = 1;
            for (int k = 0; k < 3; ++k)
            {
                const double cells = std::ceil(extent[k] / c);
                dims_[k] = cells >= 1 && cells < 1e6 ? static_cast<int>(cells)
                           : cells >= 1e6            ? 1000000
                                                     : 1;
                total *= dims_[k];
            }
            if (total <= static_cast<double>(std::max(1L, max_cells))) break;
            c *= 1.25;
        }
        inverse_cell_ = 1.0 / c;
        const std::size_t n = static_cast<std::size_t>(dims_[0]) * dims_[1] * dims_[2];
        vertex_cells_.assign(n, {});
        face_cells_.assign(n, {});
        face_cell_boxes_.assign(n, CellBox{});
        face_margin_ = 0;
    }

    void add_vertex(int v, const Vec3& p) { vertex_cells_[index(cell_of(p))].push_back({p, v}); }

    void remove_vertex(int v, const Vec3& p)
    {
        erase_one(vertex_cells_[index(cell_of(p))],
                  [v](const VertexEntry& e) { return e.vertex == v; });
    }

    /// A face is listed once, in the cell of its box's centre; queries widen by the largest
    /// half extent listed so far.
    void add_face(int f, const Triangle& t, const Vec3& lo, const Vec3& hi)
    {
        const Vec3 half = 0.5 * (hi - lo);
        face_margin_ = std::max(face_margin_, half.maxCoeff());
        FaceEntry e{{}, {}, t, f};
        for (int k = 0; k < 3; ++k)
        {
            e.lo[k] = std::nextafter(static_cast<float>(lo[k]), -HUGE_VALF);
            e.hi[k] = std::nextafter(static_cast<float>(hi[k]), HUGE_VALF);
        }
        const std::size_t cell = index(cell_of(0.5 * (lo + hi)));
        face_cells_[cell].push_back(e);
        CellBox& box = face_cell_boxes_[cell];
        for (int k = 0; k < 3; ++k)
        {
            box.lo[k] = std::min(box.lo[k], e.lo[k]);
            box.hi[k] = std::max(box.hi[k], e.hi[k]);
        }
    }

    void remove_face(int f, const Vec3& lo, const Vec3& hi)
    {
        const std::size_t cell = index(cell_of(0.5 * (lo + hi)));
        erase_one(face_cells_[cell], [f](const FaceEntry& e) { return e.face == f; });
        if (face_cells_[cell].empty()) face_cell_boxes_[cell] = CellBox{};
    }

    /// Calls on_vertex(v) for the vertices inside [lo, hi].
    template <class OnVertex>
    void query_vertices(const Vec3& lo, const Vec3& hi, OnVertex&& on_vertex) const
    {
        const auto a = cell_of(lo), b = cell_of(hi);
        for (int z = a[2]; z <= b[2]; ++z)
            for (int y = a[1]; y <= b[1]; ++y)
                for (int x = a[0]; x <= b[0]; ++x)
                    for (const VertexEntry& e : vertex_cells_[index({x, y, z})])
                        if (e.position[0] >= lo[0] && e.position[0] <= hi[0] &&
                            e.position[1] >= lo[1] && e.position[1] <= hi[1] &&
                            e.position[2] >= lo[2] && e.position[2] <= hi[2])
                            on_vertex(e.vertex);
    }

    /// Calls on_face(entry) once for every face whose box overlaps [lo, hi].
    template <class OnFace>
    void query_faces(const Vec3& lo, const Vec3& hi, OnFace&& on_face) const
    {
        const Vec3 margin = Vec3::Constant(face_margin_);
        const auto a = cell_of(lo - margin), b = cell_of(hi + margin);
        for (int z = a[2]; z <= b[2]; ++z)
            for (int y = a[1]; y <= b[1]; ++y)
                for (int x = a[0]; x <= b[0]; ++x)
                {
                    const std::size_t cell = index({x, y, z});
                    // the margin is the largest face's: most cells it adds hold none that reach
                    const CellBox& box = face_cell_boxes_[cell];
                    if (!overlaps(box.lo, box.hi, lo, hi)) continue;
                    for (const FaceEntry& e : face_cells_[cell])
                        if (overlaps(e.lo, e.hi, lo, hi)) on_face(e);
                }
    }

    std::size_t memory_bytes() const
    {
        std::size_t bytes = vertex_cells_.capacity() * sizeof(vertex_cells_[0]) +
                            face_cells_.capacity() * sizeof(face_cells_[0]);
        for (const auto& c : vertex_cells_) bytes += c.capacity() * sizeof(VertexEntry);
        for (const auto& c : face_cells_) bytes += c.capacity() * sizeof(FaceEntry);
        bytes += face_cell_boxes_.capacity() * sizeof(CellBox);
        return bytes;
    }

private:
    /// The union of the boxes of a cell's faces (empty: none); it grows only until the cell
    /// empties, so it always holds them.
    struct CellBox
    {
        std::array<float, 3> lo{HUGE_VALF, HUGE_VALF, HUGE_VALF},
            hi{-HUGE_VALF, -HUGE_VALF, -HUGE_VALF};
    };

    /// Float box [lo, hi] (a face's or a cell's) against the query box [qlo, qhi].
    static bool overlaps(const std::array<float, 3>& lo, const std::array<float, 3>& hi,
                         const Vec3& qlo, const Vec3& qhi)
    {
        return lo[0] <= qhi[0] && qlo[0] <= hi[0] && lo[1] <= qhi[1] && qlo[1] <= hi[1] &&
               lo[2] <= qhi[2] && qlo[2] <= hi[2];
    }

    struct VertexEntry
    {
        Vec3 position;
        int vertex;
    };

    /// Removes the cell's entry that matches (there is one), not keeping the order.
    template <class Entries, class Match>
    static void erase_one(Entries& entries, Match&& match)
    {
        for (std::size_t k = 0; k < entries.size(); ++k)
            if (match(entries[k]))
            {
                entries[k] = entries.back();
                entries.pop_back();
                return;
            }
        assert(false && "the entry is not in the grid");
    }

    std::array<int, 3> cell_of(const Vec3& p) const
    {
        std::array<int, 3> c{};
        for (int k = 0; k < 3; ++k)
        {
            const double x = (p[k] - origin_[k]) * inverse_cell_;
            c[k] = x <= 0 ? 0 : std::min(dims_[k] - 1, static_cast<int>(x));
        }
        return c;
    }

    std::size_t index(const std::array<int, 3>& c) const
    {
        return static_cast<std::size_t>(c[0]) +
               static_cast<std::size_t>(dims_[0]) *
                   (static_cast<std::size_t>(c[1]) + static_cast<std::size_t>(dims_[1]) * c[2]);
    }

    Vec3 origin_ = Vec3::Zero();
    double inverse_cell_ = 1.0;
    double face_margin_ = 0;
    std::array<int, 3> dims_{1, 1, 1};
    std::vector<std::vector<VertexEntry>> vertex_cells_;
    std::vector<std::vector<FaceEntry>> face_cells_;
    std::vector<CellBox> face_cell_boxes_;  // per cell
};

}  // namespace hdimesh::volume::detail
