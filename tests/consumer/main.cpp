// Builds one tet with the installed library and checks its volume and quality.
#include <hdimesh/volume/mesh/tet_mesh.h>

#include <cmath>
#include <cstdio>

int main()
{
    hdimesh::volume::TetMesh mesh;
    mesh.add_vertex({0, 0, 0});
    mesh.add_vertex({1, 0, 0});
    mesh.add_vertex({0, 1, 0});
    mesh.add_vertex({0, 0, 1});
    mesh.add_tet({0, 1, 2, 3});
    mesh.build_adjacency();
    const double volume = mesh.total_volume();
    std::printf("consumer: 1 tet, volume %.6f, Qe %.6f\n", volume, mesh.quality(0));
    return std::abs(volume - 1.0 / 6.0) < 1e-12 ? 0 : 1;
}
