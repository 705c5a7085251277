// The PLY reader: ASCII or binary of either byte order (surface_io.cpp's read_triangle_soup).

#include "surface/detail/ply_reader.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "common/buffer_io.h"
#include "common/errors.h"

namespace hdimesh::surface::detail
{
namespace
{

// PLY, ASCII or binary of either byte order: the vertex element's x, y, z and the face
// element's vertex_indices list; every other element and property is read and skipped. Our
// own reader: OpenMesh's loops forever on some corrupted headers.
struct PlyProperty
{
    std::string name;
    std::string type;        // the scalar's, or the list items'
    std::string count_type;  // a list's count; empty for a scalar
};

struct PlyElement
{
    std::string name;
    std::size_t count = 0;
    std::vector<PlyProperty> properties;
};

/// Bytes of a PLY scalar type, 0 for an unknown name.
int ply_type_size(const std::string& type)
{
    if (type == "char" || type == "uchar" || type == "int8" || type == "uint8") return 1;
    if (type == "short" || type == "ushort" || type == "int16" || type == "uint16") return 2;
    if (type == "int" || type == "uint" || type == "int32" || type == "uint32" || type == "float" ||
        type == "float32")
        return 4;
    if (type == "double" || type == "float64") return 8;
    return 0;
}

/// The header's elements (from after "ply" up to "end_header"), and its format in `format`.
std::vector<PlyElement> read_ply_header(const std::string& path, const std::string& data,
                                        std::size_t header_end, std::size_t body,
                                        std::string& format)
{
    io::TextReader header(path, std::string_view(data).substr(0, header_end), 0);
    header.token("ply");
    std::vector<PlyElement> elements;
    while (!header.at_end())
    {
        const std::string_view key = header.token("header keyword");
        if (key == "comment" || key == "obj_info")
        {
            header.skip_line();
        }
        else if (key == "format")
        {
            format = header.token("format");
            header.token("format version");
        }
        else if (key == "element")
        {
            PlyElement element;
            element.name = header.token("element name");
            const long long count = header.integer("element count");
            if (count < 0 || static_cast<unsigned long long>(count) > data.size() - body)
                header.fail("element count " + std::to_string(count) +
                            " exceeds what the file can hold");  // an item takes a byte at least
            element.count = static_cast<std::size_t>(count);
            elements.push_back(element);
        }
        else if (key == "property")
        {
            if (elements.empty()) header.fail("a property before any element");
            PlyProperty property;
            property.type = header.token("property type");
            if (property.type == "list")
            {
                property.count_type = header.token("list count type");
                property.type = header.token("list item type");
                if (ply_type_size(property.count_type) == 0)
                    header.fail("unknown list count type '" + property.count_type + "'");
            }
            if (ply_type_size(property.type) == 0)
                header.fail("unknown property type '" + property.type + "'");
            property.name = header.token("property name");
            elements.back().properties.push_back(property);
        }
        else
        {
            header.fail("unknown header keyword '" + std::string(key) + "'");
        }
    }
    return elements;
}

/// The body's numbers, from text or binary by the header's format.
class PlyBody
{
public:
    PlyBody(const std::string& path, const std::string& data, std::size_t body,
            const std::string& format)
        : ascii_(format == "ascii"),
          text_(path, ascii_ ? std::string_view(data) : std::string_view(), 0),
          binary_(path, data, body, format == "binary_big_endian")
    {
        if (ascii_)
            text_.set_position(
                body, 1 + static_cast<int>(std::count(data.begin(), data.begin() + body, '\n')));
    }

    // One number of the given type, as a double (integers exactly up to 2^53).
    double number(const std::string& type, const char* what)
    {
        if (ascii_) return text_.real(what);
        if (type == "char" || type == "int8") return binary_.get<std::int8_t>(what);
        if (type == "uchar" || type == "uint8") return binary_.get<std::uint8_t>(what);
        if (type == "short" || type == "int16") return binary_.get<std::int16_t>(what);
        if (type == "ushort" || type == "uint16") return binary_.get<std::uint16_t>(what);
        if (type == "int" || type == "int32") return binary_.get<std::int32_t>(what);
        if (type == "uint" || type == "uint32") return binary_.get<std::uint32_t>(what);
        if (type == "float" || type == "float32") return binary_.real<float>(what);
        return binary_.real<double>(what);
    }

    void fail(const std::string& message) const
    {
        if (ascii_) text_.fail(message);
        binary_.fail(message);
    }

private:
    const bool ascii_;
    io::TextReader text_;
    io::BinaryReader binary_;
};

/// One element's items: a vertex element's points and a face element's triangles (fanned)
/// into `soup`; any other element read and skipped.
void read_ply_element(const std::string& path, const PlyElement& element, PlyBody& in,
                      TriangleSoup& soup)
{
    const bool vertex = element.name == "vertex", face = element.name == "face";
    int axis[3] = {-1, -1, -1}, indices = -1;
    for (std::size_t k = 0; k < element.properties.size(); ++k)
    {
        const PlyProperty& property = element.properties[k];
        for (int c = 0; c < 3 && vertex; ++c)
            if (property.name == std::string(1, static_cast<char>('x' + c)) &&
                property.count_type.empty())
                axis[c] = static_cast<int>(k);
        if (face && !property.count_type.empty() &&
            (property.name == "vertex_indices" || property.name == "vertex_index"))
            indices = static_cast<int>(k);
    }
    if (vertex && (axis[0] < 0 || axis[1] < 0 || axis[2] < 0))
        throw InputError(path + ": the vertex element has no x, y and z properties");
    if (face && indices < 0)
        throw InputError(path + ": the face element has no vertex_indices list");
    if (vertex) soup.points.reserve(element.count);
    for (std::size_t item = 0; item < element.count; ++item)
    {
        Vec3d p(0, 0, 0);
        std::vector<int> poly;
        for (std::size_t k = 0; k < element.properties.size(); ++k)
        {
            const PlyProperty& property = element.properties[k];
            if (property.count_type.empty())
            {
                const double value = in.number(property.type, property.name.c_str());
                for (int c = 0; c < 3; ++c)
                    if (axis[c] == static_cast<int>(k)) p[c] = value;
                continue;
            }
            const double n = in.number(property.count_type, "list count");
            if (!(n >= 0 && n <= 1e6)) in.fail("list count " + std::to_string(n) + " out of range");
            const bool wanted = static_cast<int>(k) == indices;
            if (wanted && n < 3) in.fail("a face needs at least three vertices");
            for (int j = 0; j < static_cast<int>(n); ++j)
            {
                const double index = in.number(property.type, "vertex index");
                if (!wanted) continue;
                if (!(index >= 0 && index < static_cast<double>(soup.points.size())) ||
                    index != std::floor(index))
                    in.fail("vertex index " + std::to_string(index) + " out of range (0.." +
                            std::to_string(soup.points.size()) + ")");
                poly.push_back(static_cast<int>(index));
            }
        }
        if (vertex) soup.points.push_back(p);
        for (std::size_t j = 1; j + 1 < poly.size(); ++j)
        {
            soup.triangles.push_back({poly[0], poly[j], poly[j + 1]});
            soup.refs.push_back(0);
        }
    }
}

}  // namespace

TriangleSoup read_ply(const std::string& path)
{
    const std::string data = io::load_file(path);
    const std::size_t header_end = data.find("end_header");
    if (data.compare(0, 3, "ply") != 0 || header_end == std::string::npos)
        throw InputError(path + ": not a PLY file (no 'ply' ... 'end_header' header)");
    std::size_t body = data.find('\n', header_end);
    body = body == std::string::npos ? data.size() : body + 1;

    std::string format;
    const std::vector<PlyElement> elements = read_ply_header(path, data, header_end, body, format);
    const bool ascii = format == "ascii";
    if (!ascii && format != "binary_little_endian" && format != "binary_big_endian")
        throw InputError(path + ": unknown PLY format '" + format + "'");

    PlyBody in(path, data, body, format);
    TriangleSoup soup;
    bool have_faces = false;
    for (const PlyElement& element : elements)
    {
        have_faces = have_faces || element.name == "face";
        read_ply_element(path, element, in, soup);
    }
    if (!have_faces) throw InputError(path + ": no face element");
    return soup;
}

}  // namespace hdimesh::surface::detail
