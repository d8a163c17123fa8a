// Embree ray records filled the one way every caller in src/trace needs.
#pragma once

#include "obscura/math.h"

#include <embree3/rtcore.h>

namespace obscura::trace {

// A ray (and empty hit) from o along d over (tnear, tfar), all masks on, no motion blur.
RTCRayHit makeRayHit(Vec3 o, Vec3 d, float tnear, float tfar);

} // namespace obscura::trace
