// What the counting passes share: a triangle's texel-space vertices and lattice bounding box,
// and the accumulation of one cell's contribution into N-bar_T and D_T^max.
#ifndef LIGHTSAMPLER_COUNTING_GLSL
#define LIGHTSAMPLER_COUNTING_GLSL

#include "common.glsl"
#include "overlap.glsl"

struct TriangleCells {
  vec2 a, b, c;
  int64_t first_x, first_y;  // lattice cell of the bounding box's corner
  uint64_t columns, rows;
  float uv_area;             // texel units squared
};

TriangleCells triangle_cells(TexelTriangle t) {
  TriangleCells r;
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
// triangle reduce first and issue one atomic per subgroup (paper, Section 5); otherwise, or
// without kSubgroupReduction, each lane issues its own. `writer` is false for fragment helper
// invocations, whose stores are discarded: they add nothing and never carry a subgroup's atomic.
void accumulate(uint64_t expected, uint64_t max_density, uint tri, float contribution, float density,
                bool writer) {
  if (!writer) contribution = density = 0.0;
  if (kSubgroupReduction && subgroupAllEqual(tri)) {
    float sum = subgroupAdd(contribution);
    float bound = subgroupMax(density);
    // The lowest writer adds for the subgroup; with no writer the ballot is empty and its
    // find-LSB undefined, so `writer` is tested first.
    if (writer && gl_SubgroupInvocationID == subgroupBallotFindLSB(subgroupBallot(writer))) {
      if (sum > 0.0) atomicAdd(Floats(expected).v[tri], sum);
      if (bound > 0.0) atomic_max_float(Uints(max_density), tri, bound);
    }
  } else {
    if (contribution > 0.0) atomicAdd(Floats(expected).v[tri], contribution);
    if (density > 0.0) atomic_max_float(Uints(max_density), tri, density);
  }
}

// Where the cell [lo, hi] lies against the triangle: -1 wholly outside one edge (no overlap),
// +1 wholly inside every edge (full overlap), 0 across an edge (the overlap formula decides). Edge
// functions in double, like the overlap itself.
int classify(TriangleCells tt, dvec2 lo, dvec2 hi) {
  dvec2 v[3] = dvec2[3](dvec2(tt.a), dvec2(tt.b), dvec2(tt.c));
  double orientation = sign((v[1].x - v[0].x) * (v[2].y - v[0].y) - (v[1].y - v[0].y) * (v[2].x - v[0].x));
  bool inside = true;
  for (int i = 0; i < 3; ++i) {
    dvec2 e = v[(i + 1) % 3] - v[i];
    dvec2 inward = orientation * dvec2(-e.y, e.x);
    dvec2 most_in = dvec2(inward.x >= 0.0lf ? hi.x : lo.x, inward.y >= 0.0lf ? hi.y : lo.y);
    dvec2 most_out = dvec2(inward.x >= 0.0lf ? lo.x : hi.x, inward.y >= 0.0lf ? lo.y : hi.y);
    if (dot(inward, most_in - v[i]) <= 0.0lf) return -1;
    inside = inside && dot(inward, most_out - v[i]) >= 0.0lf;
  }
  return inside ? 1 : 0;
}

// Contribution of lattice cell (ix, iy) to a triangle: density times overlap, scaled from
// texel area to world area. Returns the density read, zero where the overlap is empty.
float cell_contribution(TexelTriangle t, TriangleCells tt, DensityMap map, uint64_t texels, int64_t ix,
                        int64_t iy, out float density) {
  // Cells beyond the bounding box (the raster path's dilation reaches them) only touch the
  // triangle: the CPU backend never visits them, and the closed form's rounding could give one
  // a positive overlap and raise D_T^max.
  bool in_box = ix >= tt.first_x && iy >= tt.first_y && uint64_t(ix - tt.first_x) < tt.columns &&
                uint64_t(iy - tt.first_y) < tt.rows;
  dvec2 lo = dvec2(double(ix), double(iy)), hi = lo + dvec2(1.0lf);
  int where = in_box ? classify(tt, lo, hi) : -1;
  double overlap = where < 0 ? 0.0lf
                 : where > 0 ? 1.0lf
                             : boundary_overlap(dvec2(tt.a), dvec2(tt.b), dvec2(tt.c), lo, hi);
  density = overlap > 0.0lf ? cell_density(map, texels, ix, iy) : 0.0;
  return float(double(density) * overlap * double(t.area / tt.uv_area));
}

// A triangle's integral and bound over every cell of its bounding box, by one invocation: rows,
// then columns, so that no single loop reaches lavapipe's 65535-iteration limit.
void count_cells_of(TexelTriangle t, TriangleCells tt, DensityMap map, uint64_t texels, out float sum,
                    out float bound) {
  sum = 0.0;
  bound = 0.0;
  for (uint64_t row = 0ul; row < tt.rows; ++row)
    for (uint64_t column = 0ul; column < tt.columns; ++column) {
      float density;
      sum += cell_contribution(t, tt, map, texels, tt.first_x + int64_t(column), tt.first_y + int64_t(row), density);
      bound = max(bound, density);
    }
}

#endif
