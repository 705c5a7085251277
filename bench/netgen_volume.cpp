// Netgen's volume mesher as a peer of bench/compare_volume_peers.py (issue 15), through nglib:
// a closed surface with outward triangles in, Ng_GenerateVolumeMesh with maxh = H and the default
// optimization (3 steps), a Medit mesh out. Only Ng_GenerateVolumeMesh is timed (thread CPU).
//
//   netgen_volume IN.off|IN.stl OUT.mesh H      prints "seconds X" on stdout
//
// Built only where Debian's libnglib-dev is installed (bench/CMakeLists.txt).

#include <time.h>

#include <array>
#include <cstdio>
#include <fstream>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace nglib
{
#include <nglib.h>
}

namespace
{

using Point = std::array<double, 3>;
using Triangle = std::array<int, 3>;

struct Surface
{
    std::vector<Point> points;
    std::vector<Triangle> triangles;
};

Surface read_off(std::istream& in, const std::string& path)
{
    Surface s;
    std::string magic;
    std::size_t n_points = 0, n_faces = 0, n_edges = 0;
    if (!(in >> magic >> n_points >> n_faces >> n_edges) || magic != "OFF")
        throw std::runtime_error(path + ": not an OFF file");
    s.points.resize(n_points);
    for (Point& p : s.points) in >> p[0] >> p[1] >> p[2];
    if (!in) throw std::runtime_error(path + ": truncated vertex list");
    for (std::size_t f = 0; f < n_faces; ++f)
    {
        int corners = 0;
        Triangle t{};
        if (!(in >> corners >> t[0] >> t[1] >> t[2]) || corners != 3)
            throw std::runtime_error(path + ": face " + std::to_string(f) + " is not a triangle");
        s.triangles.push_back(t);
    }
    return s;
}

// ASCII STL; facets carry their own corners, so equal coordinates are welded into one point.
Surface read_ascii_stl(std::istream& in)
{
    Surface s;
    std::map<Point, int> index_of;
    std::vector<int> corners;
    std::string word;
    while (in >> word)
    {
        if (word != "vertex") continue;
        Point p;
        in >> p[0] >> p[1] >> p[2];
        auto inserted = index_of.emplace(p, static_cast<int>(s.points.size()));
        if (inserted.second) s.points.push_back(p);
        corners.push_back(inserted.first->second);
        if (corners.size() < 3) continue;
        s.triangles.push_back({corners[0], corners[1], corners[2]});
        corners.clear();
    }
    return s;
}

Surface read_surface(const std::string& path)
{
    std::ifstream in(path);
    if (!in) throw std::runtime_error(path + ": cannot open");
    Surface s = path.size() > 4 && path.substr(path.size() - 4) == ".stl" ? read_ascii_stl(in)
                                                                          : read_off(in, path);
    if (s.triangles.empty()) throw std::runtime_error(path + ": no triangles");
    for (const Triangle& t : s.triangles)
        for (int v : t)
            if (v < 0 || v >= static_cast<int>(s.points.size()))
                throw std::runtime_error(path + ": vertex index out of range");
    return s;
}

// Six times the enclosed volume: positive when the triangles face outward.
double signed_volume6(const Surface& s)
{
    double sum = 0;
    for (const Triangle& t : s.triangles)
    {
        const Point &a = s.points[t[0]], &b = s.points[t[1]], &c = s.points[t[2]];
        sum += a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
               a[2] * (b[0] * c[1] - b[1] * c[0]);
    }
    return sum;
}

double thread_seconds()
{
    timespec t{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return t.tv_sec + 1e-9 * t.tv_nsec;
}

void write_medit(nglib::Ng_Mesh* mesh, const std::string& path)
{
    const std::string tmp = path + ".tmp";
    std::ofstream out(tmp);
    out.precision(17);
    out << "MeshVersionFormatted 2\nDimension 3\nVertices\n" << nglib::Ng_GetNP(mesh) << "\n";
    for (int i = 1; i <= nglib::Ng_GetNP(mesh); ++i)
    {
        double x[3];
        nglib::Ng_GetPoint(mesh, i, x);
        out << x[0] << ' ' << x[1] << ' ' << x[2] << " 0\n";
    }
    out << "Tetrahedra\n" << nglib::Ng_GetNE(mesh) << "\n";
    for (int e = 1; e <= nglib::Ng_GetNE(mesh); ++e)
    {
        int v[NG_VOLUME_ELEMENT_MAXPOINTS];
        nglib::Ng_GetVolumeElement(mesh, e, v);
        // Netgen's tets are negatively oriented: swapping two corners makes them positive.
        out << v[0] << ' ' << v[2] << ' ' << v[1] << ' ' << v[3] << " 1\n";
    }
    out << "Triangles\n" << nglib::Ng_GetNSE(mesh) << "\n";
    for (int f = 1; f <= nglib::Ng_GetNSE(mesh); ++f)
    {
        int v[NG_SURFACE_ELEMENT_MAXPOINTS];
        nglib::Ng_GetSurfaceElement(mesh, f, v);
        out << v[0] << ' ' << v[1] << ' ' << v[2] << " 1\n";
    }
    out << "End\n";
    out.close();
    if (!out || std::rename(tmp.c_str(), path.c_str()) != 0)
        throw std::runtime_error(path + ": cannot write");
}

}  // namespace

int main(int argc, char** argv)
{
    if (argc != 4)
    {
        std::fprintf(stderr, "usage: netgen_volume IN.off|IN.stl OUT.mesh H\n");
        return 2;
    }
    try
    {
        Surface surface = read_surface(argv[1]);
        if (signed_volume6(surface) <= 0)
            throw std::runtime_error(std::string(argv[1]) + ": triangles do not face outward");
        nglib::Ng_Init();
        nglib::Ng_Mesh* mesh = nglib::Ng_NewMesh();
        for (Point& p : surface.points) nglib::Ng_AddPoint(mesh, p.data());
        for (const Triangle& t : surface.triangles)
        {
            int one_based[3] = {t[0] + 1, t[1] + 1, t[2] + 1};
            nglib::Ng_AddSurfaceElement(mesh, nglib::NG_TRIG, one_based);
        }
        nglib::Ng_Meshing_Parameters parameters;  // optsteps_3d = 3 by default
        parameters.maxh = std::stod(argv[3]);
        const double start = thread_seconds();
        const nglib::Ng_Result result = nglib::Ng_GenerateVolumeMesh(mesh, &parameters);
        const double seconds = thread_seconds() - start;
        if (result != nglib::NG_OK)
            throw std::runtime_error("Ng_GenerateVolumeMesh failed with code " +
                                     std::to_string(static_cast<int>(result)));
        write_medit(mesh, argv[2]);
        std::printf("seconds %.6f\n", seconds);
        nglib::Ng_DeleteMesh(mesh);
        nglib::Ng_Exit();
    }
    catch (const std::exception& e)
    {
        std::fprintf(stderr, "netgen_volume: %s\n", e.what());
        return 1;
    }
    return 0;
}
