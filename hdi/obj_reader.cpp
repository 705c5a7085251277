#include "hdi/obj_reader.h"

#include <fstream>
#include <sstream>

#include "common/errors.h"

namespace hdimesh::hdi
{

TriangleSurface read_obj(const std::string& path)
{
    std::ifstream in(path);
    if (!in) throw IoError("hdi: cannot open " + path);
    TriangleSurface surface;
    std::string line;
    int line_number = 0;
    std::vector<int> polygon;
    auto fail = [&](const std::string& what) {
        throw InputError(path + ":" + std::to_string(line_number) + ": " + what);
    };
    while (std::getline(in, line))
    {
        ++line_number;
        std::istringstream fields(line);
        std::string keyword;
        if (!(fields >> keyword)) continue;
        if (keyword == "v")
        {
            Vec3 p;
            if (!(fields >> p.x() >> p.y() >> p.z())) fail("a vertex needs three coordinates");
            surface.points.push_back(p);
        }
        else if (keyword == "f")
        {
            polygon.clear();
            std::string corner;
            while (fields >> corner)
            {
                // "i", "i/t", "i//n" or "i/t/n": the vertex index is the part before the first
                // slash.
                int index = 0;
                try
                {
                    std::size_t used = 0;
                    index = std::stoi(corner, &used);
                    if (used == 0) fail("bad face corner '" + corner + "'");
                }
                catch (const std::logic_error&)
                {
                    fail("bad face corner '" + corner + "'");
                }
                const int count = static_cast<int>(surface.points.size());
                const int zero_based = index > 0 ? index - 1 : count + index;
                if (index == 0 || zero_based < 0 || zero_based >= count)
                    fail("face corner " + corner + " names no vertex read so far");
                polygon.push_back(zero_based);
            }
            if (polygon.size() < 3) fail("a face needs at least three corners");
            for (std::size_t i = 1; i + 1 < polygon.size(); ++i)
                surface.triangles.push_back({polygon[0], polygon[i], polygon[i + 1]});
        }
    }
    if (in.bad()) throw IoError("hdi: read error in " + path);
    return surface;
}

}  // namespace hdimesh::hdi
