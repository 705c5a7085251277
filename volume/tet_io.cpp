// read_mesh / write_mesh dispatch by extension, and the machinery every format shares
// (io_detail.h): file loading, the tokenizer, the binary cursor, the buffered writer and the
// validation that ends every read.

#include "volume/tet_io.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <sstream>

#include "common/atomic_file.h"
#include "common/errors.h"
#include "volume/io_detail.h"
#include "volume/tet_tables.h"

namespace hdimesh::volume
{

namespace io_detail
{

std::string load_file(const std::string& path)
{
    std::ifstream in(path, std::ios::binary);
    if (!in) throw IoError(path + ": cannot open: " + std::strerror(errno));
    in.seekg(0, std::ios::end);
    const std::streamoff size = in.tellg();
    if (size < 0) throw IoError(path + ": cannot read (not a regular file?)");
    in.seekg(0, std::ios::beg);
    std::string data(static_cast<std::size_t>(size), '\0');
    if (size > 0 && !in.read(data.data(), size)) throw IoError(path + ": read failed");
    return data;
}

std::string lower_extension(const std::string& path)
{
    const auto slash = path.find_last_of("/\\");
    const auto dot = path.find_last_of('.');
    if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
    std::string ext = path.substr(dot);
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return ext;
}

void throw_input(const std::string& path, const std::string& message)
{
    throw InputError(path + ": " + message);
}

// --- TextReader

TextReader::TextReader(const std::string& path, std::string_view text, char comment)
    : path_(path), text_(text), comment_(comment)
{
    std::memset(kind_, 0, sizeof(kind_));
    for (unsigned char c : {' ', '\t', '\r', '\f', '\v'}) kind_[c] = 1;
    kind_[static_cast<unsigned char>('\n')] = 2;
    if (comment_ != 0) kind_[static_cast<unsigned char>(comment_)] = 3;
}

void TextReader::skip_blanks()
{
    const std::size_t n = text_.size();
    const char* text = text_.data();
    while (pos_ < n)
    {
        const unsigned char kind = kind_[static_cast<unsigned char>(text[pos_])];
        if (kind == 0) break;
        if (kind == 2) ++line_;
        if (kind == 3)
            while (pos_ < n && text[pos_] != '\n') ++pos_;
        else
            ++pos_;
    }
}

bool TextReader::at_end()
{
    skip_blanks();
    return pos_ >= text_.size();
}

std::string_view TextReader::token(const char* what)
{
    skip_blanks();
    token_line_ = line_;
    if (pos_ >= text_.size()) fail(std::string("unexpected end of file while reading ") + what);
    const std::size_t start = pos_;
    const std::size_t n = text_.size();
    const char* text = text_.data();
    while (pos_ < n && kind_[static_cast<unsigned char>(text[pos_])] == 0) ++pos_;
    return text_.substr(start, pos_ - start);
}

namespace
{

std::string printable(std::string_view token)
{
    std::string s(token.substr(0, 40));
    for (char& c : s)
        if (!std::isprint(static_cast<unsigned char>(c))) c = '?';
    return token.size() > 40 ? s + "..." : s;
}

}  // namespace

long long TextReader::integer(const char* what)
{
    std::string_view t = token(what);
    if (!t.empty() && t[0] == '+') t.remove_prefix(1);
    // fast path: up to 18 plain digits cannot overflow (the common case by far)
    if (!t.empty() && t.size() <= 18)
    {
        long long value = 0;
        std::size_t i = t[0] == '-' ? 1 : 0;
        bool digits = i < t.size();
        for (; i < t.size() && digits; ++i)
        {
            const unsigned d = static_cast<unsigned>(t[i] - '0');
            digits = d <= 9;
            value = 10 * value + d;
        }
        if (digits) return t[0] == '-' ? -value : value;
    }
    long long value = 0;
    const auto r = std::from_chars(t.data(), t.data() + t.size(), value);
    if (r.ec != std::errc() || r.ptr != t.data() + t.size() || t.empty())
        fail(std::string("expected an integer (") + what + "), got '" + printable(t) + "'");
    return value;
}

long long TextReader::integer_in(const char* what, long long lo, long long hi)
{
    const long long v = integer(what);
    if (v < lo || v > hi)
        fail(std::string(what) + " " + std::to_string(v) + " out of range [" + std::to_string(lo) +
             ", " + std::to_string(hi) + "]");
    return v;
}

double TextReader::real(const char* what)
{
    std::string_view t = token(what);
    if (!t.empty() && t[0] == '+') t.remove_prefix(1);
    double value = 0;
    const auto r = std::from_chars(t.data(), t.data() + t.size(), value);
    if (r.ec == std::errc::result_out_of_range)
        fail(std::string(what) + " '" + printable(t) + "' is out of the double range");
    if (r.ec != std::errc() || r.ptr != t.data() + t.size() || t.empty())
        fail(std::string("expected a number (") + what + "), got '" + printable(t) + "'");
    if (!std::isfinite(value)) fail(std::string(what) + " is not finite: '" + printable(t) + "'");
    return value;
}

std::size_t TextReader::count(const char* what, std::size_t min_bytes_per_item)
{
    const long long n = integer(what);
    if (n < 0) fail(std::string("negative count for ") + what + ": " + std::to_string(n));
    const std::size_t left = text_.size() - std::min(pos_, text_.size());
    if (static_cast<unsigned long long>(n) > left / std::max<std::size_t>(min_bytes_per_item, 1))
        fail(std::string("count ") + std::to_string(n) + " for " + what +
             " exceeds what the rest of the file can hold (truncated or corrupted file)");
    return static_cast<std::size_t>(n);
}

void TextReader::skip_line()
{
    while (pos_ < text_.size() && text_[pos_] != '\n') ++pos_;
    if (pos_ < text_.size())
    {
        ++pos_;
        ++line_;
    }
}

void TextReader::set_position(std::size_t pos, int line)
{
    pos_ = std::min(pos, text_.size());
    line_ = line;
    token_line_ = line;
}

void TextReader::fail(const std::string& message) const
{
    throw InputError(path_ + ":" + std::to_string(token_line_) + ": " + message);
}

// --- BinaryReader

void BinaryReader::require(unsigned long long items, std::size_t bytes_per_item, const char* what) const
{
    const std::size_t left = pos_ <= data_.size() ? data_.size() - pos_ : 0;
    if (items > left / std::max<std::size_t>(bytes_per_item, 1))
        fail("count " + std::to_string(items) + " for " + what +
             " exceeds what the rest of the file can hold (truncated or corrupted file)");
}

void BinaryReader::seek(std::size_t pos, const char* what)
{
    if (pos > data_.size()) fail(std::string(what) + " points past the end of the file");
    pos_ = pos;
}

void BinaryReader::fail(const std::string& message) const
{
    throw InputError(path_ + ": byte " + std::to_string(pos_) + ": " + message);
}

// --- TextWriter

void TextWriter::flush()
{
    // a failed stream is reported with the file name by write_file_atomically
    out_.write(buffer_.data(), static_cast<std::streamsize>(buffer_.size()));
    flushed_ += buffer_.size();
    buffer_.clear();
}

// --- validation

namespace
{

std::string entity_error(const char* entity, std::size_t index, const std::string& message)
{
    return std::string(entity) + " " + std::to_string(index + 1) + ": " + message;
}

/// Checks 0-based ids against [0, n), naming the 1-based entity and id on failure.
template <class Array>
void check_ids(const std::string& path, const std::vector<Array>& items, int n, const char* entity,
               const char* target)
{
    for (std::size_t i = 0; i < items.size(); ++i)
        for (int id : items[i])
            if (id < 0 || id >= n)
                throw_input(path, entity_error(entity, i,
                                               std::string(target) + " " + std::to_string(id + 1) +
                                                   " out of range [1, " + std::to_string(n) + "]"));
}

void check_index_list(const std::string& path, const std::vector<int>& items, int n,
                      const char* entity, const char* target)
{
    for (std::size_t i = 0; i < items.size(); ++i)
        if (items[i] < 0 || items[i] >= n)
            throw_input(path, entity_error(entity, i,
                                           std::string(target) + " " + std::to_string(items[i] + 1) +
                                               " out of range [1, " + std::to_string(n) + "]"));
}

}  // namespace

void finish_read(TetMesh& mesh, const std::string& path)
{
    const int nv = mesh.num_vertices();
    mesh.vertex_refs.resize(mesh.points.size(), 0);
    mesh.tet_refs.resize(mesh.tets.size(), 0);
    mesh.triangle_refs.resize(mesh.triangles.size(), 0);
    mesh.edge_refs.resize(mesh.edges.size(), 0);
    for (int v = 0; v < nv; ++v)
        if (!mesh.points[v].allFinite())
            throw_input(path, entity_error("vertex", v, "coordinate is not finite"));

    check_ids(path, mesh.tets, nv, "tetrahedron", "vertex");
    check_ids(path, mesh.triangles, nv, "triangle", "vertex");
    check_ids(path, mesh.edges, nv, "edge", "vertex");
    const int ne = static_cast<int>(mesh.edges.size());
    const int ntri = static_cast<int>(mesh.triangles.size());
    check_index_list(path, mesh.ridges, ne, "ridge", "edge");
    check_index_list(path, mesh.required_edges, ne, "required edge", "edge");
    check_index_list(path, mesh.corners, nv, "corner", "vertex");
    check_index_list(path, mesh.required_vertices, nv, "required vertex", "vertex");
    check_index_list(path, mesh.required_triangles, ntri, "required triangle", "triangle");
    check_index_list(path, mesh.required_tets, mesh.num_tet_slots(), "required tetrahedron",
                     "tetrahedron");

    for (int t = 0; t < mesh.num_tet_slots(); ++t)
    {
        const double volume = mesh.volume(t);
        if (!(volume > 0.0))
        {
            const auto& v = mesh.tets[t];
            std::ostringstream message;
            message.precision(6);
            message << (volume == 0.0 ? "zero" : "negative") << " volume " << volume
                    << " (vertices " << v[0] + 1 << " " << v[1] + 1 << " " << v[2] + 1 << " "
                    << v[3] + 1 << "); tets must be positive: det(v1-v0, v2-v0, v3-v0) > 0";
            throw_input(path, entity_error("tetrahedron", t, message.str()));
        }
    }

    // readers grow some arrays by push_back: give the slack back (the container's bytes per
    // tet is a benchmarked figure, and a read mesh is usually kept for a whole run)
    mesh.points.shrink_to_fit();
    mesh.vertex_refs.shrink_to_fit();
    mesh.tets.shrink_to_fit();
    mesh.tet_refs.shrink_to_fit();
    mesh.triangles.shrink_to_fit();
    mesh.triangle_refs.shrink_to_fit();
    mesh.edges.shrink_to_fit();
    mesh.edge_refs.shrink_to_fit();

    const int overshared = mesh.build_adjacency();
    if (overshared > 0)
        throw_input(path, std::to_string(overshared) +
                              " face(s) shared by more than two tetrahedra (not a valid tet mesh)");
    mesh.classify_vertices();
}

LiveTets live_tets(const TetMesh& mesh)
{
    LiveTets live;
    live.file_index.assign(mesh.tets.size(), 0);
    live.ids.reserve(mesh.tets.size());
    for (int t = 0; t < mesh.num_tet_slots(); ++t)
    {
        if (mesh.is_dead(t)) continue;
        live.ids.push_back(t);
        live.file_index[t] = static_cast<int>(live.ids.size());
    }
    return live;
}

}  // namespace io_detail

MeshFormat mesh_format_from_path(const std::string& path)
{
    const std::string ext = io_detail::lower_extension(path);
    if (ext == ".mesh") return MeshFormat::Medit;
    if (ext == ".meshb") return MeshFormat::MeditBinary;
    if (ext == ".msh") return MeshFormat::Gmsh;
    if (ext == ".vtu") return MeshFormat::Vtu;
    throw InputError(path + ": unknown mesh format '" + ext +
                     "' (expected .mesh, .meshb, .msh or .vtu)");
}

TetMesh read_mesh(const std::string& path)
{
    const MeshFormat format = mesh_format_from_path(path);
    if (format == MeshFormat::Vtu)
        throw InputError(path + ": reading .vtu is not supported (write-only, for viewing)");
    const std::string data = io_detail::load_file(path);
    if (data.empty()) throw InputError(path + ": empty file");
    TetMesh mesh = format == MeshFormat::Gmsh ? io_detail::read_gmsh(path, data)
                                              : io_detail::read_medit(path, data);
    io_detail::finish_read(mesh, path);
    return mesh;
}

void write_mesh(const TetMesh& mesh, const std::string& path, const WriteOptions& options)
{
    const MeshFormat format = mesh_format_from_path(path);
    if (format == MeshFormat::Gmsh && options.gmsh_version != "2.2" && options.gmsh_version != "4.1")
        throw InputError(path + ": unsupported Gmsh version '" + options.gmsh_version +
                         "' (2.2 or 4.1)");
    if (!options.vertex_sizes.empty() &&
        options.vertex_sizes.size() != static_cast<std::size_t>(mesh.num_vertices()))
        throw InputError(path + ": " + std::to_string(options.vertex_sizes.size()) +
                         " vertex sizes for " + std::to_string(mesh.num_vertices()) + " vertices");
    write_file_atomically(path, [&](std::ostream& out) {
        switch (format)
        {
            case MeshFormat::Medit: io_detail::write_medit_ascii(mesh, out); break;
            case MeshFormat::MeditBinary: io_detail::write_medit_binary(mesh, out); break;
            case MeshFormat::Gmsh: io_detail::write_gmsh(mesh, out, options); break;
            case MeshFormat::Vtu: io_detail::write_vtu(mesh, out, options); break;
        }
    });
}

}  // namespace hdimesh::volume
