#pragma once
// Per-vertex marks for the operators' deduplications: cheaper than sorting the repeats (a ball
// lists each vertex about six times); only what is left is sorted.

#include <vector>

namespace hdimesh::volume
{

/// Marks that need no clearing: a vertex is marked when it holds the current round.
class VertexMarks
{
public:
    void next_round(int num_vertices)
    {
        if (static_cast<int>(round_of_.size()) < num_vertices) round_of_.resize(num_vertices, 0);
        ++round_;
    }
    /// Marks v; false when it already was.
    bool mark(int v) { return round_of_[v] == round_ ? false : (round_of_[v] = round_, true); }

private:
    std::vector<unsigned> round_of_;
    unsigned round_ = 0;
};

/// One per thread: the operators of one mesh run on one thread.
inline VertexMarks& vertex_marks()
{
    thread_local VertexMarks marks;
    return marks;
}

}  // namespace hdimesh::volume
