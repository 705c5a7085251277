#pragma once
// The Medit file layout shared by the meshes (.mesh/.meshb) and the solutions (.sol/.solb):
// the libMeshb keyword codes, the ASCII keyword loop and the binary header and block cursor.
// Each reader keeps its own sections; this is the frame around them.
//
// ASCII: "Keyword [count] items..." with '#' comments, indices 1-based.
// Binary (libMeshb): int32 magic 1 (byte-swapped when written on the other endianness),
// int32 version, then keyword blocks: int32 code, next-block position, [count], items.
//
//   version  reals    integers  positions
//      1     float32  int32     int32
//      2     float64  int32     int32      <- what we write (version 3 past 2 GiB)
//      3     float64  int32     int64
//      4     float64  int64     int64

#include <cstddef>
#include <functional>
#include <string_view>

#include "common/buffer_io.h"

namespace hdimesh::medit
{

/// libMeshb keyword codes (libmeshb7.h order).
namespace gmf
{
inline constexpr int kDimension = 3, kVertices = 4, kEdges = 5, kTriangles = 6, kQuadrilaterals = 7,
                     kTetrahedra = 8, kPrisms = 9, kHexahedra = 10,
                     // libMeshb reserves 12; Mmg stores RequiredTetrahedra there, so do we.
    kRequiredTetrahedra = 12, kCorners = 13, kRidges = 14, kRequiredVertices = 15,
                     kRequiredEdges = 16, kRequiredTriangles = 17, kRequiredQuadrilaterals = 18,
                     kPyramids = 49, kTangentAtEdgeVertices = 19, kNormalAtVertices = 20,
                     kNormalAtTriangleVertices = 21, kEnd = 54, kTangents = 59, kNormals = 60,
                     kTangentAtVertices = 61, kSolAtVertices = 62;
}

enum class EndKeyword
{
    Required,  ///< a file without End is an error: truncation at a section boundary shows
    Optional,  ///< reading stops at End or at the end of the text
};

/// Reads an ASCII Medit file's keywords in order. MeshVersionFormatted (1-4) and Dimension
/// (3 only) are read here; any other keyword before End goes to read_section, which reads its
/// content and returns false when it does not know the keyword: that fails "unknown keyword
/// 'K'" (+ " in a " + file_kind when given) at its line. Returns how many keywords came before
/// End. With EndKeyword::Required, a text without End fails at its last line.
int read_ascii_keywords(io::TextReader& in, EndKeyword end, const char* file_kind,
                        const std::function<bool(std::string_view keyword)>& read_section);

/// A cursor over a libMeshb binary file: reads the magic number (and with it the byte order)
/// and the version at construction, then keyword blocks and the version's integers and reals.
/// Failures throw InputError "path: byte N: message".
class BinaryFile
{
public:
    explicit BinaryFile(io::BinaryReader& in);

    struct Keyword
    {
        int code;
        long long next;  ///< absolute position of the next block (0 on End)
    };
    /// The next block's code and next-block position; fails at the end of the data (no End).
    Keyword keyword();
    /// An item count of the version's integer width, checked against the bytes left.
    long long count(const char* what, std::size_t bytes_per_item);
    long long integer(const char* what, long long lo, long long hi);
    double real(const char* what);
    /// Reads a Dimension block's value; fails unless it is 3.
    void dimension();

    int version() const { return version_; }
    int int_bytes() const { return int_bytes_; }
    int real_bytes() const { return real_bytes_; }
    io::BinaryReader& reader() { return in_; }

private:
    io::BinaryReader& in_;
    int version_ = 2, int_bytes_ = 4, real_bytes_ = 8, position_bytes_ = 4;
};

}  // namespace hdimesh::medit
