#pragma once
// Colour encodings, through OpenColorIO: the one place that knows the sRGB transfer curve.
// Textures and density maps stored as 8- or 16-bit integers are sRGB-encoded (glTF says so for
// colour textures; most painted maps are), renders are linear Rec. 709, previews are shown on
// sRGB displays unless a config says otherwise (display.h). sRGB and Rec. 709 share their
// primaries, so both directions are the curve alone.
//
// The processors are built from a raw OpenColorIO config with the IEC 61966-2-1 piecewise curve
// (an ExponentWithLinearTransform: gamma 2.4, offset 0.055). The config named by the OCIO
// environment variable is deliberately not consulted here: the tracer's contract is linear
// Rec. 709 and glTF fixes texture encodings, whereas a studio config's scene_linear role (often
// ACEScg) would silently change the primaries, and renders would depend on the user's
// environment. A user's config changes the previews only (display.h).

#include <span>

namespace trs {

/// Rec. 709 luminance of linear RGB. The weights are positive: a colour that is not black has a
/// luminance that is not zero (what makes luminance a safe light-sampling density).
template <class T>
constexpr T luminance(T r, T g, T b) {
  return T(0.2126) * r + T(0.7152) * g + T(0.0722) * b;
}

/// Decodes sRGB-encoded values to linear, in place. The curve acts on each value on its own, so
/// any packed layout (RGB, grey) works. Values outside [0, 1] continue the curve's linear segment
/// below 0 and its power segment above 1.
void srgb_to_linear(std::span<float> values);

/// Encodes linear values for an sRGB display, in place: the inverse of srgb_to_linear.
void linear_to_srgb(std::span<float> values);

}  // namespace trs
