#version 460
#extension GL_GOOGLE_include_directive : require
// Plain rejection sampling (Algorithm 1) through the candidate stream over the whole output:
// each subgroup walks segments of kSegmentSlots samples in turn; a candidate picks its triangle
// by area (a search in the area CDF that its cutpoints narrow) and a uniform point on it,
// accepted against the global bound. The same samples as the CPU backend's.
#include "cdf_pick.glsl"

layout(local_size_x = kWorkgroupSize) in;
layout(push_constant) uniform Push { RejectionPush p; };

float global_bound;
double total_area;

bool draw_candidate(uint64_t segment, uint64_t candidate, out Sample drawn) {
  uvec4 u = philox4x32(candidate_counter(0u, segment, candidate), uvec2(p.key0, p.key1));
  vec2 b = triangle_map(uniform_float(u.x), uniform_float(u.y));
  uint tri = pick_by_cdf(Doubles(p.area_cdf), Uints(p.area_guide), p.triangle_count, total_area, uniform_double(u.w));
  drawn = Sample(tri, b.x, b.y);
  return uniform_float(u.z) * global_bound <
         texel_triangle_density(Triangles(p.triangles).v[tri], Maps(p.maps), p.texels, b);
}

#include "candidate_stream.glsl"

void main() {
  global_bound = uintBitsToFloat(Totals(p.totals).t.max_density_bits);
  total_area = p.triangle_count > 0u ? Doubles(p.area_cdf).v[p.triangle_count - 1u] : 0.0lf;
  walk_output(Totals(p.totals), p.samples, p.max_tries);
}
