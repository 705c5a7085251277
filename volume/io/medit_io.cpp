// Medit .mesh (ASCII) and .meshb (libMeshb binary) tet meshes; the layout shared with the
// solution files (keyword codes, versions, the keyword loop) is in common/medit_reader.h.

#include <climits>
#include <cstdint>
#include <string>

#include "volume/io/detail/io.h"

namespace hdimesh::volume::io_detail
{

namespace
{

// --- ASCII

/// Keywords whose content we skip, with the tokens per item: derived data (normals and
/// tangents) that the HDI surface model recomputes from the mesh itself.
int skipped_tokens_per_item(std::string_view keyword)
{
    if (keyword == "Normals" || keyword == "Tangents") return 3;
    if (keyword == "NormalAtVertices" || keyword == "TangentAtVertices") return 2;
    if (keyword == "TangentAtEdgeVertices") return 3;
    return 0;
}

/// Element kinds a tet mesh cannot hold: an empty section is harmless (some writers emit
/// them), a non-empty one is an error, since dropping it would lose part of the domain.
bool is_unsupported_element_keyword(std::string_view keyword)
{
    return keyword == "Quadrilaterals" || keyword == "Hexahedra" || keyword == "Prisms" ||
           keyword == "Pyramids" || keyword == "RequiredQuadrilaterals";
}

/// The sections that list indices into another array, in both encodings.
enum class IndexTarget
{
    Vertices,
    Edges,
    Triangles,
    Tetrahedra,
};

struct IndexSection
{
    std::string_view keyword;
    int code;  ///< libMeshb
    std::vector<int> TetMesh::*list;
    IndexTarget target;
};

constexpr IndexSection kIndexSections[] = {
    {"Ridges", gmf::kRidges, &TetMesh::ridges, IndexTarget::Edges},
    {"Corners", gmf::kCorners, &TetMesh::corners, IndexTarget::Vertices},
    {"RequiredVertices", gmf::kRequiredVertices, &TetMesh::required_vertices,
     IndexTarget::Vertices},
    {"RequiredEdges", gmf::kRequiredEdges, &TetMesh::required_edges, IndexTarget::Edges},
    {"RequiredTriangles", gmf::kRequiredTriangles, &TetMesh::required_triangles,
     IndexTarget::Triangles},
    {"RequiredTetrahedra", gmf::kRequiredTetrahedra, &TetMesh::required_tets,
     IndexTarget::Tetrahedra},
};

const IndexSection* find_index_section(std::string_view keyword)
{
    for (const IndexSection& section : kIndexSections)
        if (section.keyword == keyword) return &section;
    return nullptr;
}

const IndexSection* find_index_section(int code)
{
    for (const IndexSection& section : kIndexSections)
        if (section.code == code) return &section;
    return nullptr;
}

class MeditAsciiReader
{
public:
    MeditAsciiReader(const std::string& path, const std::string& data) : in_(path, data, '#') {}

    TetMesh read()
    {
        medit::read_ascii_keywords(
            in_, medit::EndKeyword::Required, nullptr,
            [this](std::string_view keyword) { return read_section(keyword); });
        return std::move(mesh_);
    }

private:
    bool read_section(std::string_view keyword)
    {
        if (keyword == "Vertices")
            read_vertices();
        else if (keyword == "Edges")
            read_elements(mesh_.edges, mesh_.edge_refs, "Edges");
        else if (keyword == "Triangles")
            read_elements(mesh_.triangles, mesh_.triangle_refs, "Triangles");
        else if (keyword == "Tetrahedra")
            read_elements(mesh_.tets, mesh_.tet_refs, "Tetrahedra");
        else if (const IndexSection* section = find_index_section(keyword))
            read_index_list(*section);
        else if (const int per_item = skipped_tokens_per_item(keyword))
        {
            const std::size_t n = in_.count("item count", 2 * per_item);
            for (std::size_t i = 0; i < n * per_item; ++i) in_.token(std::string(keyword).c_str());
        }
        else if (is_unsupported_element_keyword(keyword))
        {
            const std::size_t n = in_.count("item count", 2);
            if (n > 0)
                in_.fail(std::string(keyword) + " are not supported (" + std::to_string(n) +
                         " in the file): only tetrahedra, triangles and edges");
        }
        else
            return false;
        return true;
    }

    void once(bool& seen, const char* keyword)
    {
        if (seen) in_.fail(std::string("second ") + keyword + " section");
        seen = true;
    }

    void read_vertices()
    {
        once(seen_vertices_, "Vertices");
        const std::size_t n = in_.count("Vertices count", 8);
        if (n > static_cast<std::size_t>(INT_MAX)) in_.fail("too many vertices");
        mesh_.points.resize(n);
        mesh_.vertex_refs.resize(n);
        for (std::size_t i = 0; i < n; ++i)
        {
            Vec3& p = mesh_.points[i];
            p.x() = in_.real("vertex x");
            p.y() = in_.real("vertex y");
            p.z() = in_.real("vertex z");
            mesh_.vertex_refs[i] = static_cast<int>(in_.integer_in("vertex ref", INT_MIN, INT_MAX));
        }
    }

    bool& seen_flag(const char* keyword)
    {
        const std::string_view k = keyword;
        return k == "Edges" ? seen_edges_ : k == "Triangles" ? seen_triangles_ : seen_tets_;
    }

    template <std::size_t N>
    void read_elements(std::vector<std::array<int, N>>& items, std::vector<int>& refs,
                       const char* keyword)
    {
        once(seen_flag(keyword), keyword);
        const std::size_t n = in_.count(keyword, 2 * (N + 1));
        if (n > static_cast<std::size_t>(INT_MAX)) in_.fail(std::string("too many ") + keyword);
        const long long max_vertex =
            seen_vertices_ ? static_cast<long long>(mesh_.points.size()) : INT_MAX;
        items.resize(n);
        refs.resize(n);
        for (std::size_t i = 0; i < n; ++i)
        {
            for (std::size_t k = 0; k < N; ++k)
                items[i][k] = static_cast<int>(in_.integer_in("vertex index", 1, max_vertex)) - 1;
            refs[i] = static_cast<int>(in_.integer_in("ref", INT_MIN, INT_MAX));
        }
    }

    void read_index_list(const IndexSection& section)
    {
        const std::string keyword(section.keyword);
        const std::size_t n = in_.count(keyword.c_str(), 2);
        if (n > static_cast<std::size_t>(INT_MAX)) in_.fail("too many " + keyword);
        const long long max_index = target_known(section.target)
                                        ? static_cast<long long>(target_size(section.target))
                                        : INT_MAX;
        std::vector<int>& items = mesh_.*section.list;
        items.reserve(items.size() + n);
        for (std::size_t i = 0; i < n; ++i)
            items.push_back(static_cast<int>(in_.integer_in("index", 1, max_index)) - 1);
    }

    bool target_known(IndexTarget target) const
    {
        switch (target)
        {
            case IndexTarget::Vertices: return seen_vertices_;
            case IndexTarget::Edges: return seen_edges_;
            case IndexTarget::Triangles: return seen_triangles_;
            case IndexTarget::Tetrahedra: return seen_tets_;
        }
        return false;
    }

    std::size_t target_size(IndexTarget target) const
    {
        switch (target)
        {
            case IndexTarget::Vertices: return mesh_.points.size();
            case IndexTarget::Edges: return mesh_.edges.size();
            case IndexTarget::Triangles: return mesh_.triangles.size();
            case IndexTarget::Tetrahedra: return mesh_.tets.size();
        }
        return 0;
    }

    TextReader in_;
    TetMesh mesh_;
    bool seen_vertices_ = false, seen_edges_ = false, seen_triangles_ = false, seen_tets_ = false;
};

// --- binary

class MeshbReader
{
public:
    MeshbReader(const std::string& path, const std::string& data)
        : in_(path, data, 0, false), file_(in_)
    {
    }

    TetMesh read()
    {
        for (;;)
        {
            const medit::BinaryFile::Keyword keyword = file_.keyword();
            if (keyword.code == gmf::kEnd) break;
            read_block(keyword);
        }
        return std::move(mesh_);
    }

private:
    void read_block(const medit::BinaryFile::Keyword& keyword)
    {
        switch (keyword.code)
        {
            case gmf::kDimension: file_.dimension(); break;
            case gmf::kVertices: read_vertices(); break;
            case gmf::kEdges: read_elements(mesh_.edges, mesh_.edge_refs, "Edges"); break;
            case gmf::kTriangles:
                read_elements(mesh_.triangles, mesh_.triangle_refs, "Triangles");
                break;
            case gmf::kTetrahedra: read_elements(mesh_.tets, mesh_.tet_refs, "Tetrahedra"); break;
            case gmf::kNormals:
            case gmf::kTangents:
            case gmf::kNormalAtVertices:
            case gmf::kTangentAtVertices:
            case gmf::kTangentAtEdgeVertices:
                // derived data the HDI model recomputes: jump over the block
                if (keyword.next <= static_cast<long long>(in_.position()))
                    in_.fail("keyword " + std::to_string(keyword.code) +
                             ": bad next-keyword position");
                in_.seek(static_cast<std::size_t>(keyword.next), "next-keyword position");
                break;
            case gmf::kQuadrilaterals:
            case gmf::kPrisms:
            case gmf::kHexahedra:
            case gmf::kPyramids:
            case gmf::kRequiredQuadrilaterals:
                // element kinds a tet mesh cannot hold: harmless only when empty
                if (const long long n = file_.count("element count", 4); n > 0)
                    in_.fail("keyword " + std::to_string(keyword.code) + ": " + std::to_string(n) +
                             " quadrilaterals/prisms/pyramids/hexahedra are not supported");
                break;
            default:
                if (const IndexSection* section = find_index_section(keyword.code))
                    read_index_list(*section);
                else
                    in_.fail("unsupported keyword code " + std::to_string(keyword.code) +
                             " (libMeshb numbering)");
        }
    }

    void read_vertices()
    {
        const long long n =
            file_.count("Vertices count", 3 * file_.real_bytes() + file_.int_bytes());
        mesh_.points.resize(n);
        mesh_.vertex_refs.resize(n);
        for (long long i = 0; i < n; ++i)
        {
            for (int k = 0; k < 3; ++k) mesh_.points[i][k] = file_.real("vertex coordinate");
            mesh_.vertex_refs[i] = static_cast<int>(file_.integer("vertex ref", INT_MIN, INT_MAX));
        }
    }

    template <std::size_t N>
    void read_elements(std::vector<std::array<int, N>>& items, std::vector<int>& refs,
                       const char* keyword)
    {
        const long long n = file_.count(keyword, (N + 1) * file_.int_bytes());
        items.resize(n);
        refs.resize(n);
        for (long long i = 0; i < n; ++i)
        {
            for (std::size_t k = 0; k < N; ++k)
                items[i][k] = static_cast<int>(file_.integer("vertex index", 1, INT_MAX)) - 1;
            refs[i] = static_cast<int>(file_.integer("ref", INT_MIN, INT_MAX));
        }
    }

    void read_index_list(const IndexSection& section)
    {
        const std::string keyword(section.keyword);
        const long long n = file_.count(keyword.c_str(), file_.int_bytes());
        std::vector<int>& items = mesh_.*section.list;
        items.reserve(items.size() + n);
        for (long long i = 0; i < n; ++i)
            items.push_back(static_cast<int>(file_.integer("index", 1, INT_MAX)) - 1);
    }

    BinaryReader in_;
    medit::BinaryFile file_;
    TetMesh mesh_;
};

// --- writers

/// The sections both writers emit, in order, with what each item holds.
struct MeditSections
{
    LiveTets live;
    std::vector<int> required_tets_in_file;  // 1-based file indices
};

MeditSections prepare(const TetMesh& mesh)
{
    MeditSections s;
    s.live = live_tets(mesh);
    for (int t : mesh.required_tets)
        if (t >= 0 && t < mesh.num_tet_slots() && !mesh.is_dead(t))
            s.required_tets_in_file.push_back(s.live.file_index[t]);
    return s;
}

void write_index_section(TextWriter& w, const char* keyword, const std::vector<int>& ids,
                         int offset)
{
    if (ids.empty()) return;
    w.text(keyword).character('\n').integer(static_cast<long long>(ids.size())).character('\n');
    for (int id : ids) w.integer(id + offset).character('\n');
    w.character('\n');
}

template <std::size_t N>
void write_element_section(TextWriter& w, const char* keyword,
                           const std::vector<std::array<int, N>>& items,
                           const std::vector<int>& refs)
{
    if (items.empty()) return;
    w.text(keyword).character('\n').integer(static_cast<long long>(items.size())).character('\n');
    for (std::size_t i = 0; i < items.size(); ++i)
    {
        for (int v : items[i]) w.integer(v + 1).character(' ');
        w.integer(refs[i]).character('\n');
    }
    w.character('\n');
}

/// Binary block writer: keyword code, the absolute position of the next keyword, the count.
class MeshbWriter
{
public:
    MeshbWriter(TextWriter& w, bool wide_positions) : w_(w), wide_(wide_positions) {}

    void header(int code, std::size_t payload_bytes, bool counted, std::size_t count)
    {
        const std::size_t header_bytes = 4 + (wide_ ? 8 : 4) + (counted ? 4 : 0);
        // libMeshb ends the chain with a zero position on End
        const std::size_t next = code == gmf::kEnd ? 0 : w_.offset() + header_bytes + payload_bytes;
        w_.raw(static_cast<std::int32_t>(code));
        if (wide_)
            w_.raw(static_cast<std::int64_t>(next));
        else
            w_.raw(static_cast<std::int32_t>(next));
        if (counted) w_.raw(static_cast<std::int32_t>(count));
    }

    void index_section(int code, const std::vector<int>& ids, int offset)
    {
        if (ids.empty()) return;
        header(code, 4 * ids.size(), true, ids.size());
        for (int id : ids) w_.raw(static_cast<std::int32_t>(id + offset));
    }

    template <std::size_t N>
    void element_section(int code, const std::vector<std::array<int, N>>& items,
                         const std::vector<int>& refs)
    {
        if (items.empty()) return;
        header(code, 4 * (N + 1) * items.size(), true, items.size());
        for (std::size_t i = 0; i < items.size(); ++i)
        {
            std::int32_t record[N + 1];
            for (std::size_t k = 0; k < N; ++k) record[k] = items[i][k] + 1;
            record[N] = refs[i];
            w_.bytes(record, sizeof(record));
        }
    }

private:
    TextWriter& w_;
    bool wide_;
};

}  // namespace

TetMesh read_medit(const std::string& path, const std::string& data)
{
    if (lower_extension(path) == ".meshb") return MeshbReader(path, data).read();
    return MeditAsciiReader(path, data).read();
}

void write_medit_ascii(const TetMesh& mesh, std::ostream& out)
{
    const MeditSections s = prepare(mesh);
    TextWriter w(out);
    w.text("MeshVersionFormatted 2\n\nDimension 3\n\n");
    if (!mesh.points.empty())
    {
        w.text("Vertices\n").integer(mesh.num_vertices()).character('\n');
        for (int v = 0; v < mesh.num_vertices(); ++v)
        {
            const Vec3& p = mesh.points[v];
            w.real(p.x()).character(' ').real(p.y()).character(' ').real(p.z()).character(' ');
            w.integer(v < static_cast<int>(mesh.vertex_refs.size()) ? mesh.vertex_refs[v] : 0)
                .character('\n');
        }
        w.character('\n');
    }
    write_element_section(w, "Edges", mesh.edges, mesh.edge_refs);
    write_element_section(w, "Triangles", mesh.triangles, mesh.triangle_refs);
    if (!s.live.ids.empty())
    {
        w.text("Tetrahedra\n").integer(static_cast<long long>(s.live.ids.size())).character('\n');
        for (int t : s.live.ids)
        {
            for (int v : mesh.tets[t]) w.integer(v + 1).character(' ');
            w.integer(mesh.tet_refs[t]).character('\n');
        }
        w.character('\n');
    }
    write_index_section(w, "Corners", mesh.corners, 1);
    write_index_section(w, "Ridges", mesh.ridges, 1);
    write_index_section(w, "RequiredVertices", mesh.required_vertices, 1);
    write_index_section(w, "RequiredEdges", mesh.required_edges, 1);
    write_index_section(w, "RequiredTriangles", mesh.required_triangles, 1);
    write_index_section(w, "RequiredTetrahedra", s.required_tets_in_file, 0);
    w.text("End\n");
    w.flush();
}

void write_medit_binary(const TetMesh& mesh, std::ostream& out)
{
    const MeditSections s = prepare(mesh);
    const std::size_t nv = mesh.points.size();
    const std::size_t nt = s.live.ids.size();
    // 32-bit positions (version 2) unless the file would pass 2 GiB (then version 3)
    const std::size_t estimate =
        nv * 28 + nt * 20 + mesh.triangles.size() * 16 + mesh.edges.size() * 12 +
        4 * (mesh.corners.size() + mesh.ridges.size() + mesh.required_vertices.size() +
             mesh.required_edges.size() + mesh.required_triangles.size() + nt) +
        4096;
    const bool wide = estimate > static_cast<std::size_t>(INT_MAX);
    TextWriter w(out);
    MeshbWriter b(w, wide);
    w.raw(std::int32_t{1}).raw(std::int32_t{wide ? 3 : 2});
    b.header(gmf::kDimension, 4, false, 0);
    w.raw(std::int32_t{3});
    if (nv > 0)
    {
        b.header(gmf::kVertices, nv * 28, true, nv);
        for (std::size_t v = 0; v < nv; ++v)
        {
            const Vec3& p = mesh.points[v];
            const double xyz[3] = {p.x(), p.y(), p.z()};
            w.bytes(xyz, sizeof(xyz));
            w.raw(static_cast<std::int32_t>(v < mesh.vertex_refs.size() ? mesh.vertex_refs[v] : 0));
        }
    }
    b.element_section(gmf::kEdges, mesh.edges, mesh.edge_refs);
    b.element_section(gmf::kTriangles, mesh.triangles, mesh.triangle_refs);
    if (nt > 0)
    {
        b.header(gmf::kTetrahedra, 20 * nt, true, nt);
        for (int t : s.live.ids)
        {
            std::int32_t record[5];
            for (int k = 0; k < 4; ++k) record[k] = mesh.tets[t][k] + 1;
            record[4] = mesh.tet_refs[t];
            w.bytes(record, sizeof(record));
        }
    }
    b.index_section(gmf::kCorners, mesh.corners, 1);
    b.index_section(gmf::kRidges, mesh.ridges, 1);
    b.index_section(gmf::kRequiredVertices, mesh.required_vertices, 1);
    b.index_section(gmf::kRequiredEdges, mesh.required_edges, 1);
    b.index_section(gmf::kRequiredTriangles, mesh.required_triangles, 1);
    b.index_section(gmf::kRequiredTetrahedra, s.required_tets_in_file, 0);
    b.header(gmf::kEnd, 0, false, 0);
    w.flush();
}

}  // namespace hdimesh::volume::io_detail
