// The Python module's native part (hdimesh._hdimesh): numpy arrays in, the library's calls
// with the GIL released, numpy arrays out. python/hdimesh/__init__.py is the public face: it
// validates arrays, holds them in hdimesh.TetMesh and turns callable size fields into batches.
//
// A mesh crosses as a dict of arrays under TetMesh's attribute names, indices from 0.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "common/errors.h"
#include "coupling/adapt.h"
#include "coupling/adapt_request.h"
#include "coupling/mesh_from_surface.h"
#include "surface/remesh_surface.h"
#include "surface/surface_io.h"
#include "volume/check/boundary_repair.h"
#include "volume/check/check.h"
#include "volume/check/quality_report.h"
#include "volume/io/tet_io.h"
#include "volume/size/metric_fields.h"
#include "volume/size/size_fields.h"
#include "volume/size/size_spec.h"

namespace py = pybind11;
using namespace hdimesh;
using volume::TetMesh;

namespace
{

template <typename T>
using Array = py::array_t<T, py::array::c_style | py::array::forcecast>;

/// A numpy array that owns `values` (moved to the heap; no copy), shaped (n, columns).
template <typename T, typename Element>
py::array owning_array(std::vector<Element>&& values, std::size_t columns)
{
    static_assert(sizeof(Element) % sizeof(T) == 0, "rows of T");
    auto* heap = new std::vector<Element>(std::move(values));
    py::capsule owner(heap, [](void* p) { delete static_cast<std::vector<Element>*>(p); });
    const auto rows = static_cast<py::ssize_t>(heap->size() * sizeof(Element) / sizeof(T) /
                                               std::max<std::size_t>(columns, 1));
    const T* data = reinterpret_cast<const T*>(heap->data());
    const auto item = static_cast<py::ssize_t>(sizeof(T));
    if (columns == 1)
        return py::array_t<T>(std::vector<py::ssize_t>{rows}, std::vector<py::ssize_t>{item}, data,
                              owner);
    const auto width = static_cast<py::ssize_t>(columns);
    return py::array_t<T>(std::vector<py::ssize_t>{rows, width},
                          std::vector<py::ssize_t>{width * item, item}, data, owner);
}

/// `mesh[name]` as rows of `columns` values (an absent or None entry: no rows).
template <typename T>
Array<T> rows_of(const py::dict& mesh, const char* name, py::ssize_t columns)
{
    if (!mesh.contains(name) || mesh[name].is_none()) return Array<T>(std::vector<py::ssize_t>{0});
    Array<T> a = py::cast<Array<T>>(mesh[name]);
    const bool vector = columns == 1 && a.ndim() == 1;
    if (!vector && (a.ndim() != 2 || a.shape(1) != columns))
        throw py::value_error(
            std::string(name) + " must have shape (n, " + std::to_string(columns) + "), got " +
            py::str(py::cast<py::object>(mesh[name].attr("shape"))).cast<std::string>());
    return a;
}

/// Rows of ids into `out` (ids beyond an int are refused here; the range is finish_mesh's).
template <typename Element>
void copy_rows(const Array<long long>& a, std::vector<Element>& out, const char* name)
{
    constexpr std::size_t n = sizeof(Element) / sizeof(int);
    out.resize(static_cast<std::size_t>(a.size()) / n);
    const long long* p = a.data();
    for (std::size_t r = 0; r < out.size(); ++r)
        for (std::size_t k = 0; k < n; ++k)
        {
            const long long id = p[r * n + k];
            if (id != static_cast<int>(id))
                throw py::value_error(std::string(name) + " row " + std::to_string(r) + " holds " +
                                      std::to_string(id) + ", beyond any index");
            out[r][k] = static_cast<int>(id);
        }
}

/// A tet mesh from the dict of arrays, checked as a file read is (ValueError naming the
/// element, numbered from 1 as in the files).
TetMesh to_mesh(const py::dict& m, bool finish = true)
{
    TetMesh mesh;
    const Array<double> points = rows_of<double>(m, "points", 3);
    const std::size_t n = static_cast<std::size_t>(points.size() / 3);
    mesh.points.resize(n);
    for (std::size_t v = 0; v < n; ++v)
        mesh.points[v] =
            volume::Vec3(points.data()[3 * v], points.data()[3 * v + 1], points.data()[3 * v + 2]);
    copy_rows(rows_of<long long>(m, "tets", 4), mesh.tets, "tets");
    copy_rows(rows_of<long long>(m, "triangles", 3), mesh.triangles, "triangles");
    copy_rows(rows_of<long long>(m, "edges", 2), mesh.edges, "edges");

    struct PerRow
    {
        const char* name;
        std::vector<int>* out;
        std::size_t rows;  ///< 0: a list of ids of any length
    };
    for (const PerRow& r : {PerRow{"vertex_refs", &mesh.vertex_refs, n},
                            PerRow{"tet_refs", &mesh.tet_refs, mesh.tets.size()},
                            PerRow{"triangle_refs", &mesh.triangle_refs, mesh.triangles.size()},
                            PerRow{"edge_refs", &mesh.edge_refs, mesh.edges.size()},
                            PerRow{"ridges", &mesh.ridges, 0}, PerRow{"corners", &mesh.corners, 0},
                            PerRow{"required_vertices", &mesh.required_vertices, 0},
                            PerRow{"required_edges", &mesh.required_edges, 0},
                            PerRow{"required_triangles", &mesh.required_triangles, 0},
                            PerRow{"required_tets", &mesh.required_tets, 0}})
    {
        const auto a = rows_of<long long>(m, r.name, 1);
        if (r.rows > 0 && a.size() > 0 && static_cast<std::size_t>(a.size()) != r.rows)
            throw py::value_error(std::string(r.name) + " has " + std::to_string(a.size()) +
                                  " values for " + std::to_string(r.rows) + " rows");
        std::vector<std::array<int, 1>> ids;
        copy_rows(a, ids, r.name);
        r.out->resize(ids.size());
        for (std::size_t i = 0; i < ids.size(); ++i) (*r.out)[i] = ids[i][0];
    }
    if (finish)
        volume::finish_mesh(mesh, "mesh");
    else  // for the checker, which names what finish_mesh would refuse
    {
        mesh.vertex_refs.resize(mesh.points.size(), 0);
        mesh.tet_refs.resize(mesh.tets.size(), 0);
        mesh.triangle_refs.resize(mesh.triangles.size(), 0);
        mesh.edge_refs.resize(mesh.edges.size(), 0);
        const int nv = mesh.num_vertices();
        auto in_range = [nv](const auto& rows) {
            for (const auto& row : rows)
                for (int id : row)
                    if (id < 0 || id >= nv) return false;
            return true;
        };
        if (in_range(mesh.tets) && in_range(mesh.triangles) && in_range(mesh.edges))
            mesh.classify_vertices();
        else
            mesh.vertex_classes.assign(mesh.points.size(), volume::VertexClass::Interior);
    }
    return mesh;
}

/// The dict of arrays of a (compacted) mesh; the vectors move into the arrays.
py::dict from_mesh(TetMesh&& mesh)
{
    mesh.compact();
    py::dict d;
    d["points"] = owning_array<double>(std::move(mesh.points), 3);
    d["tets"] = owning_array<int>(std::move(mesh.tets), 4);
    d["triangles"] = owning_array<int>(std::move(mesh.triangles), 3);
    d["edges"] = owning_array<int>(std::move(mesh.edges), 2);
    d["vertex_refs"] = owning_array<int>(std::move(mesh.vertex_refs), 1);
    d["tet_refs"] = owning_array<int>(std::move(mesh.tet_refs), 1);
    d["triangle_refs"] = owning_array<int>(std::move(mesh.triangle_refs), 1);
    d["edge_refs"] = owning_array<int>(std::move(mesh.edge_refs), 1);
    d["ridges"] = owning_array<int>(std::move(mesh.ridges), 1);
    d["corners"] = owning_array<int>(std::move(mesh.corners), 1);
    d["required_vertices"] = owning_array<int>(std::move(mesh.required_vertices), 1);
    d["required_edges"] = owning_array<int>(std::move(mesh.required_edges), 1);
    d["required_triangles"] = owning_array<int>(std::move(mesh.required_triangles), 1);
    d["required_tets"] = owning_array<int>(std::move(mesh.required_tets), 1);
    return d;
}

/// The surface of a mesh dict (points and triangles) as a soup.
surface::TriangleSoup to_soup(const py::dict& m)
{
    const TetMesh mesh = to_mesh(m);
    return coupling::triangle_soup(mesh);
}

/// A surface (built by the library's reader rules) as vertices, faces and refs.
py::tuple from_surface(const surface::SurfaceMesh& s)
{
    std::vector<std::array<double, 3>> vertices;
    std::vector<std::array<int, 3>> faces;
    std::vector<int> refs;
    std::vector<int> index(s.n_vertices(), -1);
    for (auto v : s.vertices())
    {
        index[v.idx()] = static_cast<int>(vertices.size());
        const auto p = s.point(v);
        vertices.push_back({p[0], p[1], p[2]});
    }
    OpenMesh::FPropHandleT<int> face_ref;
    const bool has_refs = s.get_property_handle(face_ref, surface::property_names::face_ref);
    for (auto f : s.faces())
    {
        std::array<int, 3> t{};
        int k = 0;
        for (auto v : s.fv_range(f)) t[k++] = index[v.idx()];
        faces.push_back(t);
        refs.push_back(has_refs ? s.property(face_ref, f) : 0);
    }
    return py::make_tuple(owning_array<double>(std::move(vertices), 3),
                          owning_array<int>(std::move(faces), 3),
                          owning_array<int>(std::move(refs), 1));
}

std::vector<double> to_vector(const std::optional<Array<double>>& a)
{
    if (!a) return {};
    return std::vector<double>(a->data(), a->data() + a->size());
}

/// Sizes: one of hsiz, a per-vertex array, a benchmark case; bounds and gradation.
volume::SizeSpec size_spec(double hsiz, const std::optional<Array<double>>& sizes,
                           const std::string& bench_field, double hmin, double hmax, double hgrad)
{
    volume::SizeSpec spec;
    spec.hsiz = hsiz;
    spec.vertex_sizes = to_vector(sizes);
    if (bench_field.size() > 1) throw InputError("bench_field is one letter A-E");
    spec.benchmark = bench_field.empty() ? 0 : bench_field[0];
    spec.hmin = hmin;
    spec.hmax = hmax;
    spec.hgrad = hgrad;
    return spec;
}

/// The progress callback, called with the GIL held; the Python object is released with it.
std::function<void(const std::string&, int)> progress_callback(const py::object& callback)
{
    if (callback.is_none()) return {};
    auto held = std::shared_ptr<py::object>(new py::object(callback), [](py::object* o) {
        py::gil_scoped_acquire gil;
        delete o;
    });
    return [held](const std::string& stage, int tets) {
        py::gil_scoped_acquire gil;
        (*held)(stage, tets);
    };
}

/// The library's messages on the C++ streams, as the tools print them; none when silent.
MessageSink print_messages(int verbose)
{
    if (verbose <= 0) return {};
    return [](MessageKind kind, const std::string& text) {
        if (kind == MessageKind::Report)
            std::cout << text << std::flush;
        else if (kind == MessageKind::Trace)
            std::cerr << text << std::flush;
    };
}

/// Fields at the input's vertices, each an (n, k) array (shapes checked in __init__.py).
std::vector<volume::VertexField> to_fields(const std::vector<Array<double>>& arrays)
{
    std::vector<volume::VertexField> fields;
    for (const Array<double>& a : arrays)
        fields.push_back({a.ndim() == 2 ? static_cast<int>(a.shape(1)) : 1,
                          std::vector<double>(a.data(), a.data() + a.size())});
    return fields;
}

/// The carried fields as (n, k) arrays at the vertices the mesh keeps once compacted.
py::list carried_fields(std::vector<volume::VertexField>&& fields, const std::vector<int>& old2new)
{
    py::list out;
    for (volume::VertexField& field : fields)
    {
        const std::size_t k = static_cast<std::size_t>(field.components);
        for (std::size_t v = 0; v < old2new.size(); ++v)  // a vertex only moves down
            if (old2new[v] >= 0)
                std::copy_n(field.values.begin() + v * k, k, field.values.begin() + old2new[v] * k);
        field.values.resize(
            k * std::count_if(old2new.begin(), old2new.end(), [](int v) { return v >= 0; }));
        out.append(owning_array<double>(std::move(field.values), k));
    }
    return out;
}

/// adapt(): the app's two pipelines, a tet mesh adapted or a closed surface filled.
py::dict adapt(const py::dict& m, double hsiz, const std::optional<Array<double>>& sizes,
               const std::string& bench_field, double hmin, double hmax, double hgrad, double hausd,
               int verbose, const py::object& progress, bool nosurf, bool noinsert, bool noswap,
               bool nomove, bool optim, bool no_optimize, bool keep_surface, bool strict,
               int max_passes, double ridge_angle, bool no_ridges, int threads,
               const std::vector<Array<double>>& fields,
               const std::optional<Array<double>>& metrics)
{
    coupling::AdaptInput input = coupling::adapt_input_from_mesh(to_mesh(m));
    coupling::AdaptRequest request;
    request.size = size_spec(hsiz, sizes, bench_field, hmin, hmax, hgrad);
    request.size.vertex_metrics = to_vector(metrics);  // 6 per vertex, Medit's order
    request.surface_hgrad = request.size.hgrad;
    request.hausd = hausd;
    // as the app: a tet mesh given only bounds or hausd keeps its own sizes within them
    request.bounds_given = hausd > 0 || hmin > 0 || hmax > 0 || hgrad > 0;
    request.switches.nosurf = nosurf;
    request.switches.noinsert = noinsert;
    request.switches.noswap = noswap;
    request.switches.nomove = nomove;
    request.switches.optim = optim;
    request.switches.no_optimize = no_optimize;
    request.switches.no_ridges = no_ridges;
    request.switches.ridge_angle = ridge_angle;
    request.keep_surface = keep_surface;
    request.strict = strict;
    request.max_passes = max_passes;
    request.threads = threads;
    request.verbosity = verbose;
    request.messages = print_messages(verbose);
    request.progress = progress_callback(progress);
    request.fields = to_fields(fields);
    coupling::AdaptResult result;
    {
        py::gil_scoped_release release;
        result = coupling::run_adapt(std::move(input), request);
    }
    const std::vector<int> old2new = result.mesh.compact().old2new_verts;
    py::list carried = carried_fields(std::move(result.transfer.fields), old2new);
    // as the app's OUT.sol: the metric at the output's vertices, where the next round starts
    std::optional<Solutions> metric_out;
    if (!request.size.vertex_metrics.empty() && result.field && result.field->anisotropic())
    {
        py::gil_scoped_release release;
        metric_out = volume::field_at_vertices(result.mesh, *result.field);
    }
    py::dict d = from_mesh(std::move(result.mesh));
    d["fields"] = carried;
    if (metric_out)
        d["metric"] = owning_array<double>(std::move(metric_out->solutions.at(0).values), 6);
    return d;
}

}  // namespace

PYBIND11_MODULE(_hdimesh, mod)
{
    mod.doc() = "hdimesh's native part; use the hdimesh package";
    py::register_exception_translator([](std::exception_ptr p) {
        try
        {
            if (p) std::rethrow_exception(p);
        }
        catch (const IoError& e)
        {
            PyErr_SetString(PyExc_OSError, e.what());
        }
        catch (const InputError& e)
        {
            PyErr_SetString(PyExc_ValueError, e.what());
        }
        catch (const TopologyError& e)
        {
            PyErr_SetString(PyExc_ValueError, e.what());
        }
        catch (const Error& e)
        {
            PyErr_SetString(PyExc_RuntimeError, e.what());
        }
    });

    mod.def(
        "read",
        [](const std::string& path, bool fields) {
            TetMesh mesh;
            std::vector<volume::PointField> point_fields;
            {
                py::gil_scoped_release release;
                if (coupling::is_surface_format(path))
                {
                    const surface::TriangleSoup soup = surface::read_triangle_soup(path);
                    for (const auto& p : soup.points)
                        mesh.add_vertex(volume::Vec3(p[0], p[1], p[2]));
                    for (std::size_t f = 0; f < soup.triangles.size(); ++f)
                        mesh.add_triangle(soup.triangles[f], soup.refs.empty() ? 0 : soup.refs[f]);
                    volume::finish_mesh(mesh, path);
                }
                else
                    mesh = volume::read_mesh(path);
                if (fields) point_fields = volume::read_point_fields(path, mesh);
            }
            if (!fields) return from_mesh(std::move(mesh));
            std::vector<std::string> names;
            std::vector<volume::VertexField> values;
            for (volume::PointField& field : point_fields)
            {
                names.push_back(field.name);
                values.push_back({field.components, std::move(field.values)});
            }
            const std::vector<int> old2new = mesh.compact().old2new_verts;
            py::list arrays = carried_fields(std::move(values), old2new);
            py::dict d = from_mesh(std::move(mesh));
            d["fields"] = py::make_tuple(names, arrays);
            return d;
        },
        py::arg("path"), py::arg("fields") = false);

    mod.def(
        "write",
        [](const py::dict& m, const std::string& path, const std::vector<std::string>& names,
           const std::vector<Array<double>>& fields) {
            TetMesh mesh = to_mesh(m);
            volume::WriteOptions options;
            std::vector<volume::VertexField> values = to_fields(fields);
            for (std::size_t k = 0; k < values.size() && k < names.size(); ++k)
                options.point_fields.push_back(
                    {names[k], values[k].components, std::move(values[k].values)});
            py::gil_scoped_release release;
            if (coupling::is_surface_format(path))
                surface::write_surface(surface::build_surface(coupling::triangle_soup(mesh), path),
                                       path);
            else
                volume::write_mesh(mesh, path, options);
        },
        py::arg("mesh"), py::arg("path"), py::arg("names") = std::vector<std::string>{},
        py::arg("fields") = std::vector<Array<double>>{});

    mod.def("adapt", &adapt, py::arg("mesh"), py::arg("hsiz"), py::arg("sizes"),
            py::arg("bench_field"), py::arg("hmin"), py::arg("hmax"), py::arg("hgrad"),
            py::arg("hausd"), py::arg("verbose"), py::arg("progress"), py::arg("nosurf"),
            py::arg("noinsert"), py::arg("noswap"), py::arg("nomove"), py::arg("optim"),
            py::arg("no_optimize"), py::arg("keep_surface"), py::arg("strict"),
            py::arg("max_passes"), py::arg("ridge_angle"), py::arg("no_ridges"),
            py::arg("threads") = 0, py::arg("fields") = std::vector<Array<double>>{},
            py::arg("metrics") = py::none());

    mod.def(
        "remesh_surface",
        [](const py::dict& m, double hsiz, double hausd, double ridge_angle, bool no_ridges,
           double hmin, double hmax, double hgrad, const std::optional<Array<double>>& sizes,
           int iterations, int verbose) {
            surface::TriangleSoup soup = to_soup(m);
            surface::SurfaceRemeshSettings settings;
            settings.features.detect_ridges = !no_ridges;
            settings.features.ridge_angle_deg = ridge_angle;
            settings.sizing.hsiz = hsiz;
            settings.sizing.hausd = hausd;
            settings.sizing.hmin = hmin;
            settings.sizing.hmax = hmax;
            settings.sizing.hgrad = hgrad;
            settings.iterations = iterations;
            settings.verbosity = verbose > 1 ? verbose - 1 : 0;
            settings.messages = print_messages(verbose);
            settings.input_sizes = to_vector(sizes);
            surface::SurfaceMesh mesh;
            {
                py::gil_scoped_release release;
                surface::ReadReport repaired;
                mesh = surface::build_surface(std::move(soup), "surface", &repaired);
                if (!settings.input_sizes.empty())  // the repair renumbers the points
                {
                    std::vector<double> sizes_after;
                    for (int old : repaired.source_point)
                        sizes_after.push_back(settings.input_sizes.at(old));
                    settings.input_sizes = std::move(sizes_after);
                }
                if (!(hsiz > 0) && !(hausd > 0) && settings.input_sizes.empty() && !(hmax > 0))
                    settings.sizing.hmax = 2.0 * surface::mean_edge_length(mesh);
                surface::remesh_surface(mesh, settings);
            }
            return from_surface(mesh);
        },
        py::arg("mesh"), py::arg("hsiz"), py::arg("hausd"), py::arg("ridge_angle"),
        py::arg("no_ridges"), py::arg("hmin"), py::arg("hmax"), py::arg("hgrad"), py::arg("sizes"),
        py::arg("iterations"), py::arg("verbose"));

    mod.def(
        "quality",
        [](const py::dict& m, double hsiz, const std::optional<Array<double>>& sizes,
           const std::string& bench_field) {
            TetMesh mesh = to_mesh(m);
            const volume::SizeSpec spec = size_spec(hsiz, sizes, bench_field, 0, 0, 0);
            py::gil_scoped_release release;
            const auto field = spec.any() ? volume::make_size_field(spec, mesh) : nullptr;
            return volume::quality_report_json(volume::compute_quality_report(mesh, field.get()));
        },
        py::arg("mesh"), py::arg("hsiz"), py::arg("sizes"), py::arg("bench_field"));

    mod.def(
        "check",
        [](const py::dict& m) {
            TetMesh mesh = to_mesh(m, false);
            std::vector<std::tuple<std::string, int, std::string>> out;
            {
                py::gil_scoped_release release;
                for (const auto& v : volume::check_mesh(mesh))
                    out.emplace_back(v.kind, v.element, v.message);
            }
            return out;
        },
        py::arg("mesh"));
}
