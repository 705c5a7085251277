// Gmsh .msh meshes, versions 2.2 and 4.1, ASCII and binary.
//
// Mapping (both directions):
//   Gmsh element type   TetMesh              ref
//   15 point            corners              vertex_refs[corner] (physical of the point)
//    1 2-node line      edges                edge_refs
//    2 3-node triangle  triangles            triangle_refs
//    4 4-node tet       tets                 tet_refs
// The ref is the element's physical tag (2.2: first tag; 4.1: first physical tag of its
// entity; 0 = none). On writing, each (dimension, ref) becomes one elementary entity carrying
// that physical tag, and each corner its own point entity.
//
// Gmsh's reference tetrahedron is (0,0,0) (1,0,0) (0,1,0) (0,0,1): the same numbering and
// positive orientation as volume/mesh/tet_tables.h, so nodes are taken in order (read_mesh then
// rejects any non-positive tet, so a file with another convention cannot slip through).

#include <algorithm>
#include <cctype>
#include <climits>
#include <cstdint>
#include <limits>
#include <map>
#include <string>
#include <unordered_map>

#include "volume/io/detail/io.h"

namespace hdimesh::volume::io_detail
{

namespace
{

int nodes_of_type(int type)
{
    switch (type)
    {
        case 15: return 1;
        case 1: return 2;
        case 2: return 3;
        case 4: return 4;
        default: return 0;
    }
}

const char* type_name(int type)
{
    switch (type)
    {
        case 3: return "4-node quadrangle";
        case 5: return "8-node hexahedron";
        case 6: return "6-node prism";
        case 7: return "5-node pyramid";
        case 8: return "3-node line";
        case 9: return "6-node triangle";
        case 11: return "10-node tetrahedron";
        default: return "unsupported type";
    }
}

class GmshReader
{
public:
    GmshReader(const std::string& path, const std::string& data)
        : path_(path), data_(data), text_(path, data, 0), bin_(path, data, 0, false)
    {
    }

    TetMesh read()
    {
        read_sections();
        return std::move(mesh_);
    }

    /// The $NodeData sections as fields at target's vertices ($Elements skipped).
    std::vector<PointField> read_fields(const TetMesh& target)
    {
        target_ = &target;
        read_sections();
        if (fields_.empty()) text_.fail("no $NodeData section: no fields to read");
        return std::move(fields_);
    }

private:
    void read_sections()
    {
        if (text_.token("$MeshFormat") != "$MeshFormat")
            text_.fail("not a Gmsh file: expected $MeshFormat");
        read_format();
        bool seen_nodes = false, seen_elements = false;
        while (!text_.at_end())
        {
            const std::string_view section = text_.token("section");
            if (section.empty() || section[0] != '$')
                text_.fail("expected a $Section, got '" + std::string(section.substr(0, 40)) + "'");
            if (section == "$Entities" && v4_)
                read_entities();
            else if (section == "$Nodes")
            {
                if (seen_nodes) text_.fail("second $Nodes section");
                if (!fields_.empty()) text_.fail("$Nodes after $NodeData");
                seen_nodes = true;
                v4_ ? read_nodes_v4() : read_nodes_v2();
                if (target_) check_target_nodes();
                index_nodes();
            }
            else if (section == "$NodeData" && target_)
                read_node_data(seen_nodes);
            else if (section == "$Elements" && !target_)
            {
                if (!seen_nodes) text_.fail("$Elements before $Nodes");
                if (seen_elements) text_.fail("second $Elements section");
                seen_elements = true;
                v4_ ? read_elements_v4() : read_elements_v2();
            }
            else
            {
                // the format says: sections with an unknown name are ignored
                skip_section(section);
                continue;
            }
            expect_end(section);
        }
        // Gmsh always writes both; requiring $Elements catches a file cut after $EndNodes
        if (!target_ && (!seen_nodes || !seen_elements))
            text_.fail(seen_nodes ? "no $Elements section (truncated file?)" : "no $Nodes section");
    }

    // --- structure

    void read_format()
    {
        const std::string_view version = text_.token("format version");
        if (version == "4.1")
            v4_ = true;
        else if (version == "2.2" || version == "2.1" || version == "2" || version == "2.0")
            v4_ = false;
        else
            text_.fail("unsupported Gmsh format version '" + std::string(version.substr(0, 20)) +
                       "' (2.2 and 4.1 are read)");
        binary_ = text_.integer_in("file type", 0, 1) == 1;
        const long long data_size = text_.integer("data size");
        if (binary_)
        {
            if (data_size != 8) text_.fail("binary files need data size 8");
            text_.skip_line();
            bin_.seek(text_.position(), "format header");
            const std::int32_t one = bin_.get<std::int32_t>("endianness marker");
            if (one != 1)
            {
                if (BinaryReader::byte_swapped(one) != 1) bin_.fail("bad endianness marker");
                bin_.set_swap(true);
            }
            resume_text();
        }
        expect_end("$MeshFormat");
    }

    void expect_end(std::string_view section)
    {
        const std::string end = "$End" + std::string(section.substr(1));
        const std::string_view got = text_.token(end.c_str());
        if (got != end)
            text_.fail("expected " + end + ", got '" + std::string(got.substr(0, 40)) +
                       "' (wrong count or truncated file?)");
    }

    void skip_section(std::string_view section)
    {
        const std::string end = "$End" + std::string(section.substr(1));
        const std::size_t from = text_.position();
        const std::size_t at = data_.find(end, from);
        if (at == std::string::npos)
            text_.fail("section " + std::string(section) + " has no " + end);
        const int lines =
            static_cast<int>(std::count(data_.begin() + from, data_.begin() + at, '\n'));
        text_.set_position(at + end.size(), text_.current_line() + lines);
    }

    /// Binary data starts on the line after the text just read.
    void start_binary()
    {
        text_.skip_line();
        bin_.seek(text_.position(), "binary block");
    }
    void resume_text() { text_.set_position(bin_.position(), text_.current_line()); }

    // --- numbers in either encoding

    long long text_or_size(const char* what, long long lo, long long hi)
    {
        return binary_ ? bin_.integer_in<std::uint64_t>(what, lo, hi)
                       : text_.integer_in(what, lo, hi);
    }
    long long text_or_int(const char* what, long long lo, long long hi)
    {
        return binary_ ? bin_.integer_in<std::int32_t>(what, lo, hi)
                       : text_.integer_in(what, lo, hi);
    }
    double text_or_real(const char* what)
    {
        return binary_ ? bin_.real<double>(what) : text_.real(what);
    }
    /// A count bounded by the bytes left (each item needs at least `min_bytes`).
    std::size_t bounded_count(const char* what, std::size_t min_bytes, bool as_size_t)
    {
        if (!binary_) return text_.count(what, min_bytes);
        const long long n = as_size_t ? bin_.integer_in<std::uint64_t>(what, 0, LLONG_MAX)
                                      : bin_.integer_in<std::int32_t>(what, 0, INT_MAX);
        bin_.require(static_cast<unsigned long long>(n), min_bytes, what);
        return static_cast<std::size_t>(n);
    }
    [[noreturn]] void fail(const std::string& message)
    {
        if (binary_) bin_.fail(message);
        text_.fail(message);
    }

    // --- 4.1 entities: physical tag of each (dimension, entity tag)

    void read_entities()
    {
        if (binary_) start_binary();
        std::size_t counts[4];
        for (int d = 0; d < 4; ++d)
            counts[d] = bounded_count("entity count", binary_ ? 20 : 8, true);
        for (int d = 0; d < 4; ++d)
            for (std::size_t i = 0; i < counts[d]; ++i)
            {
                const int tag = static_cast<int>(text_or_int("entity tag", INT_MIN, INT_MAX));
                for (int k = 0; k < (d == 0 ? 3 : 6); ++k) text_or_real("entity bounding box");
                const std::size_t nphys =
                    bounded_count("physical tag count", binary_ ? 4 : 2, true);
                int physical = 0;
                for (std::size_t k = 0; k < nphys; ++k)
                {
                    const int p = static_cast<int>(text_or_int("physical tag", INT_MIN, INT_MAX));
                    if (k == 0) physical = p;
                }
                entity_physical_[{d, tag}] = physical;
                if (d > 0)
                {
                    const std::size_t nbound =
                        bounded_count("bounding entity count", binary_ ? 4 : 2, true);
                    for (std::size_t k = 0; k < nbound; ++k)
                        text_or_int("bounding entity tag", INT_MIN, INT_MAX);
                }
            }
        if (binary_) resume_text();
    }

    // --- nodes

    void read_nodes_v2()
    {
        const std::size_t n = text_.count("node count", 8);
        if (n > static_cast<std::size_t>(INT_MAX)) text_.fail("too many nodes");
        node_tags_.resize(n);
        mesh_.points.resize(n);
        if (binary_)
        {
            start_binary();
            bin_.require(n, 28, "nodes");
        }
        for (std::size_t i = 0; i < n; ++i)
        {
            node_tags_[i] = text_or_int("node tag", 1, INT_MAX);
            for (int k = 0; k < 3; ++k) mesh_.points[i][k] = text_or_real("node coordinate");
        }
        if (binary_) resume_text();
    }

    void read_nodes_v4()
    {
        if (binary_) start_binary();
        const std::size_t blocks = bounded_count("node block count", binary_ ? 20 : 8, true);
        const std::size_t n = bounded_count("node count", binary_ ? 32 : 8, true);
        if (n > static_cast<std::size_t>(INT_MAX)) fail("too many nodes");
        text_or_size("minimum node tag", 0, LLONG_MAX);
        text_or_size("maximum node tag", 0, LLONG_MAX);
        node_tags_.reserve(n);
        mesh_.points.reserve(n);
        for (std::size_t b = 0; b < blocks; ++b)
        {
            const int dim = static_cast<int>(text_or_int("entity dimension", 0, 3));
            text_or_int("entity tag", INT_MIN, INT_MAX);
            const int parametric = static_cast<int>(text_or_int("parametric flag", 0, 1));
            const std::size_t in_block = bounded_count("nodes in block", binary_ ? 32 : 8, true);
            if (node_tags_.size() + in_block > n)
                fail("node blocks hold more nodes than announced");
            for (std::size_t i = 0; i < in_block; ++i)
                node_tags_.push_back(text_or_size("node tag", 1, LLONG_MAX));
            for (std::size_t i = 0; i < in_block; ++i)
            {
                Vec3 p;
                for (int k = 0; k < 3; ++k) p[k] = text_or_real("node coordinate");
                for (int k = 0; k < parametric * dim; ++k) text_or_real("parametric coordinate");
                mesh_.points.push_back(p);
            }
        }
        if (node_tags_.size() != n)
            fail("node blocks hold " + std::to_string(node_tags_.size()) + " nodes, header says " +
                 std::to_string(n));
        if (binary_) resume_text();
    }

    /// Node tag -> index: a dense table when tags are compact (the usual 1..n), else a hash.
    void index_nodes()
    {
        long long max_tag = 0;
        for (long long t : node_tags_) max_tag = std::max(max_tag, t);
        const std::size_t n = node_tags_.size();
        dense_ = static_cast<unsigned long long>(max_tag) <= 2 * n + 1024;
        if (dense_) tag_to_index_.assign(static_cast<std::size_t>(max_tag) + 1, -1);
        for (std::size_t i = 0; i < n; ++i)
        {
            const long long tag = node_tags_[i];
            int& slot = dense_ ? tag_to_index_[tag] : sparse_[tag];
            if (dense_ ? slot != -1 : slot != 0)
                fail("node tag " + std::to_string(tag) + " defined twice");
            slot = dense_ ? static_cast<int>(i) : static_cast<int>(i) + 1;  // sparse: +1, 0 = unset
        }
        mesh_.vertex_refs.assign(n, 0);
        std::vector<long long>().swap(node_tags_);
    }

    int node_index(long long tag, long long element_tag)
    {
        int index = -1;
        if (dense_)
        {
            if (tag >= 0 && tag < static_cast<long long>(tag_to_index_.size()))
                index = tag_to_index_[tag];
        }
        else
        {
            const auto it = sparse_.find(tag);
            if (it != sparse_.end()) index = it->second - 1;
        }
        if (index < 0)
            fail("element " + std::to_string(element_tag) + ": node " + std::to_string(tag) +
                 " is not in $Nodes");
        return index;
    }

    // --- $NodeData (read_fields only)

    /// The nodes must be the target's vertices, in order: the fields are taken by index.
    void check_target_nodes()
    {
        const std::vector<Vec3>& points = target_->points;
        if (mesh_.points.size() != points.size())
            text_.fail("$Nodes holds " + std::to_string(mesh_.points.size()) + " nodes, the mesh " +
                       std::to_string(points.size()) + " vertices");
        for (std::size_t i = 0; i < points.size(); ++i)
            if ((mesh_.points[i] - points[i]).norm() > 1e-9 * (1.0 + points[i].norm()))
                text_.fail("node " + std::to_string(node_tags_[i]) +
                           " is not at the mesh's vertex " + std::to_string(i + 1) +
                           ": the fields' nodes must be the mesh's");
    }

    /// A string tag: "quoted" (spaces allowed) or one token.
    std::string string_tag()
    {
        std::size_t at = text_.position();
        int line = text_.current_line();
        while (at < data_.size() && std::isspace(static_cast<unsigned char>(data_[at])))
            line += data_[at++] == '\n' ? 1 : 0;
        if (at >= data_.size() || data_[at] != '"') return std::string(text_.token("string tag"));
        const std::size_t close = data_.find_first_of("\"\n", at + 1);
        if (close == std::string::npos || data_[close] != '"')
            text_.fail("string tag without its closing quote");
        text_.set_position(close + 1, line);
        return data_.substr(at + 1, close - at - 1);
    }

    /// Vertex index of a $NodeData node tag: through $Nodes, else tag k is vertex k - 1.
    int data_vertex(long long tag, bool through_nodes, const std::string& name)
    {
        const int nv = target_->num_vertices();
        int index = -1;
        if (!through_nodes)
            index = tag >= 1 && tag <= nv ? static_cast<int>(tag - 1) : -1;
        else if (dense_)
            index = tag >= 0 && tag < static_cast<long long>(tag_to_index_.size())
                        ? tag_to_index_[tag]
                        : -1;
        else if (const auto it = sparse_.find(tag); it != sparse_.end())
            index = it->second - 1;
        if (index < 0)
            fail("$NodeData '" + name + "': node " + std::to_string(tag) +
                 (through_nodes ? " is not in $Nodes"
                                : " is not a vertex (1 to " + std::to_string(nv) + ")"));
        return index;
    }

    void read_node_data(bool through_nodes)
    {
        PointField field;
        const long long strings = text_.integer_in("string tag count", 0, INT_MAX);
        for (long long k = 0; k < strings; ++k)
        {
            std::string tag = string_tag();
            if (k == 0) field.name = std::move(tag);
        }
        if (field.name.empty()) field.name = "field" + std::to_string(fields_.size() + 1);
        for (const PointField& f : fields_)
            if (f.name == field.name)
                text_.fail("a second $NodeData '" + field.name +
                           "' (several time steps or partitions are not read)");
        const long long reals = text_.integer_in("real tag count", 0, INT_MAX);
        for (long long k = 0; k < reals; ++k) text_.real("real tag");
        const long long ints = text_.integer_in("integer tag count", 3, INT_MAX);
        long long header[3] = {};  // time step, components, values
        for (long long k = 0; k < ints; ++k)
        {
            const long long v = text_.integer("integer tag");
            if (k < 3) header[k] = v;
        }
        field.components = static_cast<int>(header[1]);
        if (header[1] != 1 && header[1] != 3 && header[1] != 9)
            text_.fail("$NodeData '" + field.name + "' has " + std::to_string(header[1]) +
                       " components (1, 3 or 9 are read)");
        const int nv = target_->num_vertices();
        if (header[2] != nv)
            text_.fail("$NodeData '" + field.name + "' has " + std::to_string(header[2]) +
                       " values, the mesh " + std::to_string(nv) + " vertices");
        field.values.assign(static_cast<std::size_t>(nv) * field.components, 0.0);
        std::vector<char> seen(nv, 0);
        if (binary_)
        {
            start_binary();
            bin_.require(static_cast<unsigned long long>(nv), 4 + 8 * field.components,
                         "$NodeData values");
        }
        for (int i = 0; i < nv; ++i)
        {
            // a binary tag is an int in 4.1 too, as Gmsh writes and reads it (size_t from 4.2)
            const long long tag = binary_ ? bin_.integer_in<std::int32_t>("node tag", 0, INT_MAX)
                                          : text_.integer("node tag");
            const int v = data_vertex(tag, through_nodes, field.name);
            if (seen[v])
                fail("$NodeData '" + field.name + "': node " + std::to_string(tag) +
                     " given twice");
            seen[v] = 1;
            for (int c = 0; c < field.components; ++c)
                field.values[static_cast<std::size_t>(v) * field.components + c] =
                    text_or_real("$NodeData value");
        }
        if (binary_) resume_text();
        fields_.push_back(std::move(field));
    }

    // --- elements

    void add_element(int type, const long long* nodes, int ref, long long element_tag)
    {
        int v[4];
        for (int k = 0; k < nodes_of_type(type); ++k) v[k] = node_index(nodes[k], element_tag);
        switch (type)
        {
            case 15:
                mesh_.corners.push_back(v[0]);
                if (ref != 0) mesh_.vertex_refs[v[0]] = ref;
                break;
            case 1:
                mesh_.edges.push_back({v[0], v[1]});
                mesh_.edge_refs.push_back(ref);
                break;
            case 2:
                mesh_.triangles.push_back({v[0], v[1], v[2]});
                mesh_.triangle_refs.push_back(ref);
                break;
            case 4:
                mesh_.tets.push_back({v[0], v[1], v[2], v[3]});
                mesh_.tet_refs.push_back(ref);
                break;
        }
    }

    int supported_nodes(int type)
    {
        const int nn = nodes_of_type(type);
        if (nn == 0)
            fail("element type " + std::to_string(type) + " (" + type_name(type) +
                 ") is not supported: only points, lines, triangles and tetrahedra");
        return nn;
    }

    void read_elements_v2()
    {
        const std::size_t n = text_.count("element count", 8);
        if (!binary_)
        {
            for (std::size_t i = 0; i < n; ++i)
            {
                const long long tag = text_.integer("element tag");
                const int type = static_cast<int>(text_.integer_in("element type", 0, INT_MAX));
                const int nn = supported_nodes(type);
                const std::size_t ntags = text_.count("tag count", 2);
                int physical = 0;
                for (std::size_t k = 0; k < ntags; ++k)
                {
                    const int t =
                        static_cast<int>(text_.integer_in("element tag", INT_MIN, INT_MAX));
                    if (k == 0) physical = t;
                }
                long long nodes[4];
                for (int k = 0; k < nn; ++k) nodes[k] = text_.integer("node tag");
                add_element(type, nodes, physical, tag);
            }
            return;
        }
        start_binary();
        std::size_t done = 0;
        while (done < n)
        {
            const int type =
                static_cast<int>(bin_.integer_in<std::int32_t>("element type", 0, INT_MAX));
            const int nn = supported_nodes(type);
            const long long count = bin_.integer_in<std::int32_t>("elements in block", 1,
                                                                  static_cast<long long>(n - done));
            const int ntags = static_cast<int>(bin_.integer_in<std::int32_t>("tag count", 0, 64));
            bin_.require(static_cast<unsigned long long>(count), 4 * (1 + ntags + nn),
                         "element block");
            for (long long i = 0; i < count; ++i)
            {
                const long long tag = bin_.get<std::int32_t>("element tag");
                int physical = 0;
                for (int k = 0; k < ntags; ++k)
                {
                    const int t = bin_.get<std::int32_t>("element tag");
                    if (k == 0) physical = t;
                }
                long long nodes[4];
                for (int k = 0; k < nn; ++k) nodes[k] = bin_.get<std::int32_t>("node tag");
                add_element(type, nodes, physical, tag);
            }
            done += static_cast<std::size_t>(count);
        }
        resume_text();
    }

    void read_elements_v4()
    {
        if (binary_) start_binary();
        const std::size_t blocks = bounded_count("element block count", binary_ ? 20 : 8, true);
        const std::size_t n = bounded_count("element count", binary_ ? 16 : 4, true);
        text_or_size("minimum element tag", 0, LLONG_MAX);
        text_or_size("maximum element tag", 0, LLONG_MAX);
        std::size_t done = 0;
        for (std::size_t b = 0; b < blocks; ++b)
        {
            const int dim = static_cast<int>(text_or_int("entity dimension", 0, 3));
            const int entity = static_cast<int>(text_or_int("entity tag", INT_MIN, INT_MAX));
            const int type = static_cast<int>(text_or_int("element type", 0, INT_MAX));
            const int nn = supported_nodes(type);
            const std::size_t count =
                bounded_count("elements in block", binary_ ? 8 * (1 + nn) : 2 * (1 + nn), true);
            if (done + count > n) fail("element blocks hold more elements than announced");
            const auto it = entity_physical_.find({dim, entity});
            const int physical = it == entity_physical_.end() ? 0 : it->second;
            for (std::size_t i = 0; i < count; ++i)
            {
                const long long tag = text_or_size("element tag", 0, LLONG_MAX);
                long long nodes[4];
                for (int k = 0; k < nn; ++k) nodes[k] = text_or_size("node tag", 0, LLONG_MAX);
                add_element(type, nodes, physical, tag);
            }
            done += count;
        }
        if (done != n)
            fail("element blocks hold " + std::to_string(done) + " elements, header says " +
                 std::to_string(n));
        if (binary_) resume_text();
    }

    const std::string& path_;
    const std::string& data_;
    TextReader text_;
    BinaryReader bin_;
    bool v4_ = false, binary_ = false;
    std::map<std::pair<int, int>, int> entity_physical_;
    std::vector<long long> node_tags_;
    bool dense_ = true;
    std::vector<int> tag_to_index_;
    std::unordered_map<long long, int> sparse_;
    TetMesh mesh_;
    const TetMesh* target_ = nullptr;  ///< read_fields: the mesh the fields are at
    std::vector<PointField> fields_;
};

// --- writing

/// One elementary entity per (dimension, ref); corners get one point entity each.
struct Entity
{
    Entity(int dim_, int tag_, int physical_) : dim(dim_), tag(tag_), physical(physical_) {}
    int dim;
    int tag;
    int physical;  // 0: none
    Vec3 low = Vec3::Constant(std::numeric_limits<double>::infinity());
    Vec3 high = -Vec3::Constant(std::numeric_limits<double>::infinity());
    std::vector<int> elements;  // indices into the mesh array of that dimension (live tet ids)
};

struct EntityPlan
{
    std::vector<Entity> entities[4];
    std::vector<int> entity_of[4];  // per element id (tet slot for tets): index into entities[d]
    int node_dim = 3, node_entity = 1;
    std::size_t element_count = 0;
};

EntityPlan plan_entities(const TetMesh& mesh, const LiveTets& live)
{
    EntityPlan plan;
    for (std::size_t c = 0; c < mesh.corners.size(); ++c)
    {
        const int v = mesh.corners[c];
        Entity e(0, static_cast<int>(c) + 1, mesh.vertex_refs[v]);
        e.low = e.high = mesh.points[v];
        e.elements.push_back(static_cast<int>(c));
        plan.entities[0].push_back(std::move(e));
        plan.entity_of[0].push_back(static_cast<int>(c));
    }
    auto group = [&](int dim, const std::vector<int>& ids, const std::vector<int>& refs,
                     auto vertices_of) {
        std::map<int, int> entity_of_ref;
        plan.entity_of[dim].assign(dim == 3 ? mesh.tets.size() : ids.size(), -1);
        for (int i : ids)
        {
            const int ref = refs[i];
            auto [it, added] =
                entity_of_ref.emplace(ref, static_cast<int>(plan.entities[dim].size()));
            if (added)
                plan.entities[dim].emplace_back(
                    dim, static_cast<int>(plan.entities[dim].size()) + 1, ref);
            Entity& e = plan.entities[dim][it->second];
            e.elements.push_back(i);
            plan.entity_of[dim][i] = it->second;
            for (int v : vertices_of(i))
            {
                e.low = e.low.cwiseMin(mesh.points[v]);
                e.high = e.high.cwiseMax(mesh.points[v]);
            }
        }
    };
    auto iota = [](std::size_t n) {
        std::vector<int> ids(n);
        for (std::size_t i = 0; i < n; ++i) ids[i] = static_cast<int>(i);
        return ids;
    };
    group(1, iota(mesh.edges.size()), mesh.edge_refs, [&](int i) { return mesh.edges[i]; });
    group(2, iota(mesh.triangles.size()), mesh.triangle_refs,
          [&](int i) { return mesh.triangles[i]; });
    group(3, live.ids, mesh.tet_refs, [&](int i) { return mesh.tets[i]; });
    plan.element_count =
        mesh.corners.size() + mesh.edges.size() + mesh.triangles.size() + live.ids.size();

    // nodes are all listed in one block, on the first entity of the highest dimension
    plan.node_dim = -1;
    for (int d = 3; d >= 0 && plan.node_dim < 0; --d)
        if (!plan.entities[d].empty()) plan.node_dim = d;
    if (plan.node_dim < 0)
    {
        // vertices but no element: an empty volume entity still holds them
        Entity e(3, 1, 0);
        for (const Vec3& p : mesh.points)
        {
            e.low = e.low.cwiseMin(p);
            e.high = e.high.cwiseMax(p);
        }
        if (mesh.points.empty()) e.low = e.high = Vec3::Zero();
        plan.entities[3].push_back(std::move(e));
        plan.node_dim = 3;
    }
    plan.node_entity = 1;
    return plan;
}

constexpr int kGmshType[4] = {15, 1, 2, 4};

class GmshWriter
{
public:
    GmshWriter(const TetMesh& mesh, std::ostream& out, bool binary)
        : mesh_(mesh), w_(out), binary_(binary), live_(live_tets(mesh)),
          plan_(plan_entities(mesh, live_))
    {
    }

    void write_v2()
    {
        format("2.2");
        const int nv = mesh_.num_vertices();
        w_.text("$Nodes\n").integer(nv).character('\n');
        for (int v = 0; v < nv; ++v)
        {
            const Vec3& p = mesh_.points[v];
            if (binary_)
            {
                w_.raw(static_cast<std::int32_t>(v + 1));
                const double xyz[3] = {p.x(), p.y(), p.z()};
                w_.bytes(xyz, sizeof(xyz));
            }
            else
            {
                w_.integer(v + 1)
                    .character(' ')
                    .real(p.x())
                    .character(' ')
                    .real(p.y())
                    .character(' ')
                    .real(p.z())
                    .character('\n');
            }
        }
        if (binary_) w_.character('\n');
        w_.text("$EndNodes\n$Elements\n")
            .integer(static_cast<long long>(plan_.element_count))
            .character('\n');
        // 2.2 elements carry their own tags, so the input order is kept
        long long element_tag = 0;
        for (int d = 0; d < 4; ++d)
        {
            const int type = kGmshType[d];
            const int nn = d + 1;
            std::vector<int> ids;
            if (d == 3)
                ids = live_.ids;
            else
                for (std::size_t i = 0; i < plan_.entity_of[d].size(); ++i)
                    ids.push_back(static_cast<int>(i));
            if (binary_ && !ids.empty())
            {
                const std::int32_t header[3] = {type, static_cast<std::int32_t>(ids.size()), 2};
                w_.bytes(header, sizeof(header));
            }
            for (int i : ids)
            {
                const Entity& e = plan_.entities[d][plan_.entity_of[d][i]];
                int v[4];
                vertices(d, i, v);
                ++element_tag;
                if (binary_)
                {
                    std::int32_t record[3 + 4] = {static_cast<std::int32_t>(element_tag),
                                                  e.physical, e.tag};
                    for (int k = 0; k < nn; ++k) record[3 + k] = v[k] + 1;
                    w_.bytes(record, sizeof(std::int32_t) * (3 + nn));
                }
                else
                {
                    w_.integer(element_tag)
                        .character(' ')
                        .integer(type)
                        .text(" 2 ")
                        .integer(e.physical)
                        .character(' ')
                        .integer(e.tag);
                    for (int k = 0; k < nn; ++k) w_.character(' ').integer(v[k] + 1);
                    w_.character('\n');
                }
            }
        }
        if (binary_) w_.character('\n');
        w_.text("$EndElements\n");
        w_.flush();
    }

    void write_v4()
    {
        format("4.1");
        // $Entities
        w_.text("$Entities\n");
        for (int d = 0; d < 4; ++d) size(plan_.entities[d].size(), d == 3 ? '\n' : ' ');
        for (int d = 0; d < 4; ++d)
            for (const Entity& e : plan_.entities[d])
            {
                integer(e.tag, ' ');
                for (int k = 0; k < 3; ++k) real(e.low[k], ' ');
                if (d > 0)
                    for (int k = 0; k < 3; ++k) real(e.high[k], ' ');
                size(e.physical != 0 ? 1 : 0, d > 0 || e.physical != 0 ? ' ' : '\n');
                if (e.physical != 0) integer(e.physical, d > 0 ? ' ' : '\n');
                if (d > 0) size(0, '\n');  // no bounding entities
            }
        end_binary_line();
        w_.text("$EndEntities\n");

        // $Nodes: one block on the first entity of the highest dimension
        const std::size_t nv = mesh_.points.size();
        w_.text("$Nodes\n");
        size(1, ' ');
        size(nv, ' ');
        size(nv > 0 ? 1 : 0, ' ');
        size(nv, '\n');
        integer(plan_.node_dim, ' ');
        integer(plan_.node_entity, ' ');
        integer(0, ' ');
        size(nv, '\n');
        for (std::size_t v = 0; v < nv; ++v) size(v + 1, '\n');
        for (std::size_t v = 0; v < nv; ++v)
        {
            const Vec3& p = mesh_.points[v];
            real(p.x(), ' ');
            real(p.y(), ' ');
            real(p.z(), '\n');
        }
        end_binary_line();
        w_.text("$EndNodes\n");

        // $Elements: one block per entity
        std::size_t blocks = 0;
        for (int d = 0; d < 4; ++d) blocks += plan_.entities[d].size();
        w_.text("$Elements\n");
        size(blocks, ' ');
        size(plan_.element_count, ' ');
        size(plan_.element_count > 0 ? 1 : 0, ' ');
        size(plan_.element_count, '\n');
        std::size_t element_tag = 0;
        for (int d = 0; d < 4; ++d)
            for (const Entity& e : plan_.entities[d])
            {
                integer(d, ' ');
                integer(e.tag, ' ');
                integer(kGmshType[d], ' ');
                size(e.elements.size(), '\n');
                for (int i : e.elements)
                {
                    int v[4];
                    vertices(d, i, v);
                    size(++element_tag, ' ');
                    for (int k = 0; k <= d; ++k)
                        size(static_cast<std::size_t>(v[k]) + 1, k == d ? '\n' : ' ');
                }
            }
        end_binary_line();
        w_.text("$EndElements\n");
        w_.flush();
    }

    /// One $NodeData per field, after the mesh (a 6-component symmetric tensor, in Mmg's
    /// order m11 m12 m13 m22 m23 m33, as Gmsh's 9: Gmsh reads 1, 3 or 9 components).
    void write_node_data(const std::vector<PointField>& fields)
    {
        static constexpr int kFull[9] = {0, 1, 2, 1, 3, 4, 2, 4, 5};
        const int nv = mesh_.num_vertices();
        for (const PointField& field : fields)
        {
            const int in = field.components, out = in == 6 ? 9 : in;
            w_.text("$NodeData\n1\n\"").text(field.name).text("\"\n1\n0\n3\n0\n");
            w_.integer(out).character('\n').integer(nv).character('\n');
            for (int v = 0; v < nv; ++v)
            {
                if (binary_)
                    w_.raw(static_cast<std::int32_t>(v + 1));  // an int in 2.2 and 4.1 alike
                else
                    w_.integer(v + 1);
                const double* values = field.values.data() + static_cast<std::size_t>(v) * in;
                for (int c = 0; c < out; ++c)
                {
                    const double x = values[in == 6 ? kFull[c] : c];
                    binary_ ? (void)w_.raw(x) : (void)w_.character(' ').real(x);
                }
                if (!binary_) w_.character('\n');
            }
            end_binary_line();
            w_.text("$EndNodeData\n");
        }
        w_.flush();
    }

private:
    void format(const char* version)
    {
        w_.text("$MeshFormat\n").text(version).text(binary_ ? " 1 8\n" : " 0 8\n");
        if (binary_) w_.raw(std::int32_t{1}).character('\n');
        w_.text("$EndMeshFormat\n");
    }

    void vertices(int dim, int i, int* v) const
    {
        switch (dim)
        {
            case 0: v[0] = mesh_.corners[i]; break;
            case 1: std::copy(mesh_.edges[i].begin(), mesh_.edges[i].end(), v); break;
            case 2: std::copy(mesh_.triangles[i].begin(), mesh_.triangles[i].end(), v); break;
            default: std::copy(mesh_.tets[i].begin(), mesh_.tets[i].end(), v); break;
        }
    }

    // 4.1 fields: text with a separator, or binary (size_t = uint64, int = int32, double)
    void size(std::size_t v, char separator)
    {
        if (binary_)
            w_.raw(static_cast<std::uint64_t>(v));
        else
            w_.integer(static_cast<long long>(v)).character(separator);
    }
    void integer(int v, char separator)
    {
        if (binary_)
            w_.raw(static_cast<std::int32_t>(v));
        else
            w_.integer(v).character(separator);
    }
    void real(double v, char separator)
    {
        if (binary_)
            w_.raw(v);
        else
            w_.real(v).character(separator);
    }
    void end_binary_line()
    {
        if (binary_) w_.character('\n');
    }

    const TetMesh& mesh_;
    TextWriter w_;
    bool binary_;
    LiveTets live_;
    EntityPlan plan_;
};

}  // namespace

TetMesh read_gmsh(const std::string& path, const std::string& data)
{
    return GmshReader(path, data).read();
}

std::vector<PointField> read_gmsh_fields(const std::string& path, const std::string& data,
                                         const TetMesh& target)
{
    return GmshReader(path, data).read_fields(target);
}

void write_gmsh(const TetMesh& mesh, std::ostream& out, const WriteOptions& options)
{
    GmshWriter writer(mesh, out, options.gmsh_binary);
    if (options.gmsh_version == "2.2")
        writer.write_v2();
    else
        writer.write_v4();
    writer.write_node_data(options.point_fields);
}

}  // namespace hdimesh::volume::io_detail
