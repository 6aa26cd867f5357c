#version 460
#extension GL_GOOGLE_include_directive : require
// Fast rejection sampling (core/frs_table.h) through the candidate stream over the whole output,
// as plain rejection sampling: a candidate picks its micro-triangle by area times bound and a
// uniform point on it, accepted against the micro-triangle's bound. The same samples as the CPU
// backend's (cpu/frs.cpp).
#include "cdf_pick.glsl"

layout(local_size_x = kWorkgroupSize) in;
layout(push_constant) uniform Push { FrsPush p; };

double total_weight;  // the CDF's last entry

// Point s of micro-triangle m, in its parent's barycentrics. precise: the CPU's arithmetic, no
// fused multiply-add.
vec2 parent_barycentrics(uint m, vec2 s) {
  Floats c = Floats(p.corners + uint64_t(m) * 24ul);  // six floats per micro-triangle
  precise float b1 = c.v[0] + s.x * (c.v[2] - c.v[0]) + s.y * (c.v[4] - c.v[0]);
  precise float b2 = c.v[1] + s.x * (c.v[3] - c.v[1]) + s.y * (c.v[5] - c.v[1]);
  return vec2(b1, b2);
}

bool draw_candidate(uint64_t segment, uint64_t candidate, out Sample drawn) {
  uvec4 u = philox4x32(candidate_counter(0u, segment, candidate), uvec2(p.key0, p.key1));
  vec2 s = triangle_map(uniform_float(u.x), uniform_float(u.y));
  uint m = pick_by_cdf(Doubles(p.cdf), Uints(p.guide), p.micro_count, total_weight, uniform_double(u.w));
  vec2 b = parent_barycentrics(m, s);
  uint tri = Uints(p.parent).v[m];
  drawn = Sample(tri, b.x, b.y);
  // Rounding may carry a corner's point out of the parent: rejected, as on the CPU.
  precise float sum = b.x + b.y;
  if (!(b.x >= 0.0 && b.y >= 0.0 && sum <= 1.0)) return false;
  return uniform_float(u.z) * Floats(p.bound).v[m] <
         texel_triangle_density(Triangles(p.triangles).v[tri], Maps(p.maps), p.texels, b);
}

#include "candidate_stream.glsl"

void main() {
  total_weight = p.micro_count > 0u ? Doubles(p.cdf).v[p.micro_count - 1u] : 0.0lf;
  walk_output(Totals(p.totals), p.samples, p.max_tries);
}
