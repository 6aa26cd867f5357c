#version 460
#extension GL_GOOGLE_include_directive : require
// Dilation for devices without conservative rasterization: each edge moves outward by half a
// texel's extent along its normal, plus p.dilation (the rasterizer's vertex snapping and float
// rounding), so the center of every texel the triangle touches falls inside. Extra fragments
// are harmless: their exact overlap is zero. Where the moved edges meet far out (a sharp
// corner) or not at all (rounding), the triangle's dilated bounding box is drawn instead.
// Degenerate input (including the triangles the vertex shader culled) emits nothing.
#include "common.glsl"

layout(triangles) in;
layout(triangle_strip, max_vertices = 4) out;
layout(push_constant) uniform Push { RasterPush p; };
layout(location = 0) in flat uint v_triangle[];
layout(location = 0) out flat uint g_triangle;

vec2 to_texels(vec4 ndc) { return (ndc.xy * 0.5 + 0.5) * vec2(p.width, p.height); }
vec4 to_ndc(vec2 texels) { return vec4(texels / vec2(p.width, p.height) * 2.0 - 1.0, 0.0, 1.0); }

void emit(vec2 texels) {
  gl_Position = to_ndc(texels);
  g_triangle = v_triangle[0];
  EmitVertex();
}

void main() {
  vec2 v[3] = vec2[3](to_texels(gl_in[0].gl_Position), to_texels(gl_in[1].gl_Position),
                      to_texels(gl_in[2].gl_Position));
  float orientation = sign((v[1].x - v[0].x) * (v[2].y - v[0].y) - (v[1].y - v[0].y) * (v[2].x - v[0].x));
  if (orientation == 0.0) return;
  // Offset edge lines n . x = c, n pointing outward.
  vec2 normal[3];
  float offset[3];
  for (int i = 0; i < 3; ++i) {
    vec2 e = v[(i + 1) % 3] - v[i];
    normal[i] = orientation * vec2(e.y, -e.x);
    offset[i] = dot(normal[i], v[i]) + 0.5 * (abs(normal[i].x) + abs(normal[i].y)) + p.dilation * length(normal[i]);
  }
  float margin = 0.5 + p.dilation;
  vec2 lo = min(v[0], min(v[1], v[2])) - margin, hi = max(v[0], max(v[1], v[2])) + margin;
  vec2 corner[3];
  bool near = true;
  for (int i = 0; i < 3; ++i) {
    // Corner i: where the offset lines of its two edges meet.
    vec2 a = normal[(i + 2) % 3], b = normal[i];
    float ca = offset[(i + 2) % 3], cb = offset[i];
    float det = a.x * b.y - a.y * b.x;
    corner[i] = det != 0.0 ? vec2(ca * b.y - cb * a.y, a.x * cb - b.x * ca) / det : vec2(0.0);
    near = near && det != 0.0 && all(greaterThanEqual(corner[i], lo - 2.0)) && all(lessThanEqual(corner[i], hi + 2.0));
  }
  if (near) {
    for (int i = 0; i < 3; ++i) emit(corner[i]);
  } else {
    emit(lo);
    emit(vec2(hi.x, lo.y));
    emit(vec2(lo.x, hi.y));
    emit(hi);
  }
  EndPrimitive();
}
