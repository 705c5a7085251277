#pragma once
// Weight functions of the diffuse (moving least squares) fits, as functions of s = d / rho,
// the distance to the evaluation point over the window radius.

#include <cmath>

namespace hdimesh::hdi
{

enum class WeightFunction
{
    Gaussian,       ///< exp(-(s / 0.4)^2): smooth, every neighbour counts a little
    QuarticSpline,  ///< 1 - 6s^2 + 8s^3 - 3s^4 on [0, 1], 0 beyond: C2, compact support
    Interpolating   ///< quartic spline / (s^2 + 1e-4): the fit (nearly) passes through the nodes
};

inline double quartic_spline(double s)
{
    if (s >= 1.0) return 0.0;
    const double s2 = s * s;
    return 1.0 - 6.0 * s2 + 8.0 * s2 * s - 3.0 * s2 * s2;
}

inline double diffuse_weight(WeightFunction function, double s)
{
    switch (function)
    {
        case WeightFunction::Gaussian: return std::exp(-s * s * (1.0 / 0.16));
        case WeightFunction::QuarticSpline: return quartic_spline(s);
        case WeightFunction::Interpolating: return quartic_spline(s) / (s * s + 1e-4);
    }
    return 0.0;
}

}  // namespace hdimesh::hdi
