#version 460
#extension GL_GOOGLE_include_directive : require
// Plain rejection sampling (Algorithm 1) through the candidate stream over the whole output:
// each subgroup walks segments of kSegmentSlots samples in turn; a candidate picks its triangle
// by area (a search in the area CDF that its cutpoints narrow) and a uniform point on it,
// accepted against the global bound. The same samples as the CPU backend's.
#include "workgroup.glsl"

layout(local_size_x = kWorkgroupSize) in;
layout(push_constant) uniform Push { RejectionPush p; };

float global_bound;
double total_area;

// core::pick_by_area: the first triangle whose CDF exceeds u times the total area, searched
// between the cutpoints of u's bucket and its neighbours.
uint pick_by_area(double u) {
  Doubles cdf = Doubles(p.area_cdf);
  Uints guide = Uints(p.area_guide);
  uint k = min(uint(u * double(p.triangle_count)), p.triangle_count - 1u);
  uint lo = guide.v[k > 0u ? k - 1u : 0u], hi = guide.v[min(k + 2u, p.triangle_count)];
  double target = u * total_area;
  while (lo < hi) {
    uint mid = lo + (hi - lo) / 2u;
    if (cdf.v[mid] > target) hi = mid; else lo = mid + 1u;
  }
  return lo;
}

bool draw_candidate(uint64_t segment, uint64_t candidate, out Sample drawn) {
  uvec4 u = philox4x32(candidate_counter(0u, segment, candidate), uvec2(p.key0, p.key1));
  vec2 b = triangle_map(uniform_float(u.x), uniform_float(u.y));
  uint tri = pick_by_area(uniform_double(u.w));
  drawn = Sample(tri, b.x, b.y);
  return uniform_float(u.z) * global_bound <
         texel_triangle_density(Triangles(p.triangles).v[tri], Maps(p.maps), p.texels, b);
}

#include "candidate_stream.glsl"

void main() {
  Totals totals = Totals(p.totals);
  uint64_t n = totals.t.realized;
  uint64_t segments = (n + uint64_t(kSegmentSlots) - 1ul) / uint64_t(kSegmentSlots);
  uint64_t stride = uint64_t(gl_NumWorkGroups.x) * uint64_t(gl_NumSubgroups);
  global_bound = uintBitsToFloat(totals.t.max_density_bits);
  total_area = p.triangle_count > 0u ? Doubles(p.area_cdf).v[p.triangle_count - 1u] : 0.0lf;
  WalkTally tally = WalkTally(0ul, 0ul);
  for (uint64_t s = uint64_t(gl_WorkGroupID.x) * uint64_t(gl_NumSubgroups) + uint64_t(gl_SubgroupID); s < segments;
       s += stride) {
    uint64_t first = s * uint64_t(kSegmentSlots);
    walk_segment(p.samples, s, first, uint(min(uint64_t(kSegmentSlots), n - first)), p.max_tries, tally);
  }
  count_tries(totals, tally.candidates, tally.exhausted);
}
