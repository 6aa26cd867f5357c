#pragma once
// Umbrella header of the lightsampler library.

#include "lightsampler/backend.h"
#include "lightsampler/buffer.h"
#include "lightsampler/mesh.h"
#include "lightsampler/overlap.h"
#include "lightsampler/random.h"
#include "lightsampler/refinement.h"
#include "lightsampler/sample.h"
#include "lightsampler/sampler.h"
#include "lightsampler/triangle_map.h"
#ifdef LIGHTSAMPLER_HAS_VULKAN
#include "lightsampler/vulkan.h"
#endif
