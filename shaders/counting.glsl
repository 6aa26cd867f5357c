// What the counting passes share: a triangle's texel-space vertices and lattice bounding box,
// and the accumulation of one cell's contribution into N-bar_T and D_T^max.
#ifndef LIGHTSAMPLER_COUNTING_GLSL
#define LIGHTSAMPLER_COUNTING_GLSL

#include "common.glsl"
#include "overlap.glsl"

struct TexelTriangle {
  vec2 a, b, c;
  int64_t first_x, first_y;  // lattice cell of the bounding box's corner
  uint64_t columns, rows;
  float uv_area;             // texel units squared
};

TexelTriangle texel_triangle(GpuTriangle t) {
  TexelTriangle r;
  r.a = vec2(t.origin_x, t.origin_y);
  r.b = r.a + vec2(t.edge1_x, t.edge1_y);
  r.c = r.a + vec2(t.edge2_x, t.edge2_y);
  vec2 lo = min(r.a, min(r.b, r.c)), hi = max(r.a, max(r.b, r.c));
  r.first_x = floor_to_int(lo.x);
  r.first_y = floor_to_int(lo.y);
  r.columns = uint64_t(floor_to_int(hi.x) - r.first_x + 1l);
  r.rows = uint64_t(floor_to_int(hi.y) - r.first_y + 1l);
  r.uv_area = 0.5 * abs(t.edge1_x * t.edge2_y - t.edge1_y * t.edge2_x);
  return r;
}

// Adds one cell's density * overlap to triangle `tri`. Lanes of a subgroup that all work on one
// triangle reduce first and issue one atomic per subgroup (paper, Section 5); otherwise each
// lane issues its own. `writer` is false for fragment helper invocations, whose stores are
// discarded: they add nothing and never carry a subgroup's atomic.
void accumulate(uint64_t expected, uint64_t max_density, uint tri, float contribution, float density,
                bool writer) {
  if (!writer) contribution = density = 0.0;
  if (subgroupAllEqual(tri)) {
    float sum = subgroupAdd(contribution);
    float bound = subgroupMax(density);
    if (gl_SubgroupInvocationID == subgroupBallotFindLSB(subgroupBallot(writer))) {
      if (sum > 0.0) atomicAdd(Floats(expected).v[tri], sum);
      if (bound > 0.0) atomic_max_float(Uints(max_density), tri, bound);
    }
  } else {
    if (contribution > 0.0) atomicAdd(Floats(expected).v[tri], contribution);
    if (density > 0.0) atomic_max_float(Uints(max_density), tri, density);
  }
}

// Whether the cell [lo, hi] lies wholly outside one of the triangle's edges: then it does not
// overlap, exactly. Without this test the float closed form can leave rounding noise for cells
// that only pass near the triangle, and such a cell would raise D_T^max (a valid bound, but a
// looser one than the CPU backend's).
bool separated(TexelTriangle tt, vec2 lo, vec2 hi) {
  vec2 v[3] = vec2[3](tt.a, tt.b, tt.c);
  float orientation = sign((tt.b.x - tt.a.x) * (tt.c.y - tt.a.y) - (tt.b.y - tt.a.y) * (tt.c.x - tt.a.x));
  for (int i = 0; i < 3; ++i) {
    vec2 e = v[(i + 1) % 3] - v[i];
    vec2 inward = orientation * vec2(-e.y, e.x);
    vec2 corner = vec2(inward.x >= 0.0 ? hi.x : lo.x, inward.y >= 0.0 ? hi.y : lo.y);  // most inside
    if (dot(inward, corner - v[i]) <= 0.0) return true;
  }
  return false;
}

// Contribution of lattice cell (ix, iy) to a triangle: density times overlap, scaled from
// texel area to world area. Returns the density read, zero where the overlap is empty.
float cell_contribution(GpuTriangle t, TexelTriangle tt, GpuMap map, uint64_t texels, int64_t ix,
                        int64_t iy, out float density) {
  vec2 lo = vec2(float(ix), float(iy));
  float overlap = separated(tt, lo, lo + vec2(1.0)) ? 0.0 : rect_triangle_overlap(tt.a, tt.b, tt.c, lo, lo + vec2(1.0));
  density = overlap > 0.0 ? cell_density(map, texels, ix, iy) : 0.0;
  return density * overlap * (t.area / tt.uv_area);
}

#endif
