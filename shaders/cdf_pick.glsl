// The pick of an element by an inclusive CDF through its cutpoints (core/area_pick.h): plain
// rejection sampling's triangles by area, FRS's micro-triangles by area times bound.
#ifndef LIGHTSAMPLER_CDF_PICK_GLSL
#define LIGHTSAMPLER_CDF_PICK_GLSL

#include "common.glsl"

// core::pick_by_area over `count` > 0 elements whose CDF ends at `total`: the first element whose
// CDF exceeds u times the total, searched between the cutpoints of u's bucket and its neighbours.
uint pick_by_cdf(Doubles cdf, Uints guide, uint count, double total, double u) {
  uint k = min(uint(u * double(count)), count - 1u);
  uint lo = guide.v[k > 0u ? k - 1u : 0u], hi = guide.v[min(k + 2u, count)];
  double target = u * total;
  while (lo < hi) {
    uint mid = lo + (hi - lo) / 2u;
    if (cdf.v[mid] > target) hi = mid; else lo = mid + 1u;
  }
  return lo;
}

#endif
