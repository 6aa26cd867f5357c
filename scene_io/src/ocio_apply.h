#pragma once
// Applying an OpenColorIO processor to packed float values: the texture decoding of color.cpp and
// the display transforms of display.cpp.

#include <OpenColorIO/OpenColorIO.h>

#include <span>

namespace trs {

/// Applies `processor` to `values` in place, as RGB triples in parallel; one or two values left
/// over are padded to a triple, which suits processors that treat every channel alike.
void apply(const OCIO_NAMESPACE::CPUProcessor& processor, std::span<float> values);

}  // namespace trs
