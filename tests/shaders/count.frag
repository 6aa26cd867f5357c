#version 460
// Counts fragments into a buffer reached by its device address (there are no attachments).
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require

#include "coverage.h"

layout(push_constant) uniform Push { CoveragePush p; };
layout(buffer_reference, std430, buffer_reference_align = 4) buffer Counter { uint value; };

void main() { atomicAdd(Counter(p.counter).value, 1u); }
