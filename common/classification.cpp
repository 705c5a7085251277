#include "common/classification.h"

namespace hdimesh
{

const char* to_string(Dimension d)
{
    switch (d)
    {
        case Dimension::Corner: return "corner";
        case Dimension::Curve: return "curve";
        case Dimension::Surface: return "surface";
        case Dimension::Volume: return "volume";
    }
    return "?";
}

}  // namespace hdimesh
