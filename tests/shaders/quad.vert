#version 460
// Two triangles covering the whole viewport, from gl_VertexIndex alone (no vertex input).
vec2 corners[6] = vec2[](vec2(-1, -1), vec2(1, -1), vec2(1, 1), vec2(-1, -1), vec2(1, 1), vec2(-1, 1));

void main() { gl_Position = vec4(corners[gl_VertexIndex], 0, 1); }
