#version 460
// Writes first + i into word i of a buffer reached by its device address. Grid-stride: any
// number of workgroups covers any count, however large.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require

#include "iota.h"

layout(local_size_x = IOTA_WORKGROUP_SIZE) in;
layout(push_constant) uniform Push { IotaPush p; };
layout(buffer_reference, std430, buffer_reference_align = 4) buffer Word { uint value; };

void main() {
  const uint64_t stride = uint64_t(gl_NumWorkGroups.x) * IOTA_WORKGROUP_SIZE;
  // 64-bit address arithmetic: buffers may exceed 4 GiB (and any one binding's range).
  for (uint64_t i = gl_GlobalInvocationID.x; i < p.count; i += stride)
    Word(p.words + 4 * i).value = p.first + uint(i);
}
