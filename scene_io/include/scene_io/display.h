#pragma once
// Linear Rec. 709 renders encoded for a display (the previews), through OpenColorIO: a config's
// display and view when a config is named (a filmic or ACES view rolls bright highlights off
// where the sRGB curve clips them), the sRGB curve of color.h otherwise.
//
// The input of the display transform is the config's colour space for linear Rec. 709, not its
// scene_linear role: that role is often ACEScg, and taking Rec. 709 values for ACEScg ones would
// oversaturate every colour. The space is found by the names and aliases that common configs give
// it (display.cpp lists them); a config that has none falls back on scene_linear, with a warning.

#include <functional>
#include <span>
#include <string>

namespace trs {

/// A display transform as the user names it; an empty field takes its default.
struct DisplayTransform {
  /// An OpenColorIO config file, or with OpenColorIO 2.2 and later a built-in config's URI
  /// (ocio://default); empty: no config, the sRGB curve.
  std::string config;
  /// The renders' colour space in the config (a name, alias or role); default: its linear
  /// Rec. 709 space, else its scene_linear role.
  std::string colorspace;
  std::string display;  ///< default: the config's default display
  std::string view;     ///< default: the display's default view for `colorspace`

  bool operator==(const DisplayTransform&) const = default;
};

/// A display transform ready to apply: the config read, the defaults filled in, the names
/// checked. Copies share the config's processor.
class DisplayEncoder {
 public:
  /// The sRGB curve (linear_to_srgb), without a config.
  DisplayEncoder();
  /// Throws FileError naming the config when it cannot be read, when it lacks a name given
  /// (the message lists the names it has) or when its transform cannot be built.
  explicit DisplayEncoder(const DisplayTransform& transform);

  /// The transform applied: every name the config's canonical one, the defaults filled in.
  const DisplayTransform& transform() const { return transform_; }
  /// Empty, or why the colour space is a guess (the config has no linear Rec. 709 space).
  const std::string& warning() const { return warning_; }

  /// Encodes linear RGB values (3 per pixel) for the display, in place. Values are not clamped:
  /// views may give values outside [0, 1].
  void encode(std::span<float> rgb) const { encode_(rgb); }

 private:
  DisplayTransform transform_;
  std::string warning_;
  std::function<void(std::span<float>)> encode_;
};

}  // namespace trs
