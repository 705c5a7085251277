// VTK XML unstructured grid (.vtu) for viewing in ParaView: tets (VTK_TETRA = 10) then
// boundary triangles (VTK_TRIANGLE = 5) as cells, cell data "ref" (Int32) and "Qe" (Float64:
// tet_quality / triangle_quality), point data "size" and the carried fields when given. Arrays are
// raw binary in one <AppendedData> block (each preceded by its UInt64 byte count), the most compact
// form ParaView and meshio both read.

#include <cstdint>
#include <string>

#include "volume/io/detail/io.h"
#include "volume/mesh/geometry.h"

namespace hdimesh::volume::io_detail
{

namespace
{

bool little_endian()
{
    const std::uint16_t probe = 1;
    unsigned char first;
    std::memcpy(&first, &probe, 1);
    return first == 1;
}

struct AppendedArray
{
    std::string xml_type;
    std::string name;
    int components;
    std::size_t bytes;
};

}  // namespace

void write_vtu(const TetMesh& mesh, std::ostream& out, const WriteOptions& options)
{
    const LiveTets live = live_tets(mesh);
    const std::size_t nv = mesh.points.size();
    const std::size_t nt = live.ids.size();
    const std::size_t ntri = mesh.triangles.size();
    const std::size_t ncells = nt + ntri;
    const bool with_size = !options.vertex_sizes.empty();

    // the appended block's layout, in writing order
    std::vector<AppendedArray> arrays;
    if (with_size) arrays.push_back({"Float64", "size", 1, 8 * nv});
    for (const PointField& field : options.point_fields)
        arrays.push_back({"Float64", field.name, field.components, 8 * nv * field.components});
    const int point_arrays = (with_size ? 1 : 0) + static_cast<int>(options.point_fields.size());
    arrays.push_back({"Int32", "ref", 1, 4 * ncells});
    arrays.push_back({"Float64", "Qe", 1, 8 * ncells});
    arrays.push_back({"Float64", "Points", 3, 24 * nv});
    arrays.push_back({"Int64", "connectivity", 1, 8 * (4 * nt + 3 * ntri)});
    arrays.push_back({"Int64", "offsets", 1, 8 * ncells});
    arrays.push_back({"UInt8", "types", 1, ncells});
    std::vector<std::size_t> offsets;
    std::size_t offset = 0;
    for (const auto& a : arrays)
    {
        offsets.push_back(offset);
        offset += 8 + a.bytes;
    }
    auto data_array = [&](std::size_t k) {
        const AppendedArray& a = arrays[k];
        std::string s = "        <DataArray type=\"" + a.xml_type + "\" Name=\"" + a.name + "\"";
        if (a.components != 1) s += " NumberOfComponents=\"" + std::to_string(a.components) + "\"";
        return s + " format=\"appended\" offset=\"" + std::to_string(offsets[k]) + "\"/>\n";
    };

    TextWriter w(out);
    w.text(
         "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" "
         "byte_order=\"")
        .text(little_endian() ? "LittleEndian" : "BigEndian")
        .text("\" header_type=\"UInt64\">\n  <UnstructuredGrid>\n    <Piece NumberOfPoints=\"")
        .integer(static_cast<long long>(nv))
        .text("\" NumberOfCells=\"")
        .integer(static_cast<long long>(ncells))
        .text("\">\n");
    std::size_t k = 0;
    auto group = [&](const char* open, int count, const char* close) {
        w.text(open);
        for (int i = 0; i < count; ++i) w.text(data_array(k++));
        w.text(close);
    };
    if (point_arrays > 0)
        group(with_size ? "      <PointData Scalars=\"size\">\n" : "      <PointData>\n",
              point_arrays, "      </PointData>\n");
    group("      <CellData Scalars=\"ref\">\n", 2, "      </CellData>\n");
    group("      <Points>\n", 1, "      </Points>\n");
    group("      <Cells>\n", 3, "      </Cells>\n");
    w.text("    </Piece>\n  </UnstructuredGrid>\n  <AppendedData encoding=\"raw\">\n   _");

    auto block_size = [&](std::size_t index) {
        w.raw(static_cast<std::uint64_t>(arrays[index].bytes));
    };
    k = 0;
    if (with_size)
    {
        block_size(k++);
        w.bytes(options.vertex_sizes.data(), 8 * nv);
    }
    for (const PointField& field : options.point_fields)
    {
        block_size(k++);
        w.bytes(field.values.data(), 8 * field.values.size());
    }
    block_size(k++);
    for (int t : live.ids) w.raw(static_cast<std::int32_t>(mesh.tet_refs[t]));
    for (std::size_t i = 0; i < ntri; ++i) w.raw(static_cast<std::int32_t>(mesh.triangle_refs[i]));
    block_size(k++);
    for (int t : live.ids) w.raw(mesh.quality(t));
    for (const auto& tri : mesh.triangles)
        w.raw(triangle_quality(mesh.points[tri[0]], mesh.points[tri[1]], mesh.points[tri[2]]));
    block_size(k++);
    for (const Vec3& p : mesh.points)
    {
        const double xyz[3] = {p.x(), p.y(), p.z()};
        w.bytes(xyz, sizeof(xyz));
    }
    block_size(k++);
    for (int t : live.ids)
        for (int v : mesh.tets[t]) w.raw(static_cast<std::int64_t>(v));
    for (const auto& tri : mesh.triangles)
        for (int v : tri) w.raw(static_cast<std::int64_t>(v));
    block_size(k++);
    std::int64_t end = 0;
    for (std::size_t i = 0; i < nt; ++i) w.raw(end += 4);
    for (std::size_t i = 0; i < ntri; ++i) w.raw(end += 3);
    block_size(k++);
    for (std::size_t i = 0; i < nt; ++i) w.raw(std::uint8_t{10});
    for (std::size_t i = 0; i < ntri; ++i) w.raw(std::uint8_t{5});
    w.text("\n  </AppendedData>\n</VTKFile>\n");
    w.flush();
}

}  // namespace hdimesh::volume::io_detail
