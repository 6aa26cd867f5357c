#pragma once
// A small OpenColorIO config for tests of the previews' display transforms, whose views are
// known functions, so that a test can compute a preview's bytes exactly:
// - display "Gamma": view "Square root" (an ExponentTransform of 2, inverted: v^(1/2), negatives
//   to 0), then view "Raw" (the values as they are);
// - display "Linear": view "Raw".
// Its reference space is the renders' linear Rec. 709, under a name the test chooses; its
// scene_linear role is ACEScg, a matrix away, so that a transform that took the renders for
// scene_linear would mix their channels.

#include <string>

namespace trs_test {

/// The config's text: `linear` names the reference space, `aliases` are its aliases (a YAML flow
/// list's items, "lin_rec709"); with `linear_display_first`, "Linear" is the default display.
inline std::string ocio_config(const std::string& linear, const std::string& aliases = "",
                               bool linear_display_first = false) {
  const std::string gamma = "  Gamma:\n    - !<View> {name: Square root, colorspace: gamma 2}\n"
                            "    - !<View> {name: Raw, colorspace: " + linear + "}\n";
  const std::string raw = "  Linear:\n    - !<View> {name: Raw, colorspace: " + linear + "}\n";
  return "ocio_profile_version: 2\n\nroles:\n  default: " + linear + "\n  scene_linear: ACEScg\n\n"
         "displays:\n" + (linear_display_first ? raw + gamma : gamma + raw) +
         "\ncolorspaces:\n"
         "  - !<ColorSpace>\n    name: " + linear + "\n    aliases: [" + aliases + "]\n"
         "  - !<ColorSpace>\n    name: ACEScg\n"
         "    to_scene_reference: !<MatrixTransform> {matrix: [1.70505, -0.62179, -0.08326, 0, "
         "-0.13026, 1.14080, -0.01055, 0, -0.02400, -0.12897, 1.15297, 0, 0, 0, 0, 1]}\n"
         "  - !<ColorSpace>\n    name: gamma 2\n"
         "    to_scene_reference: !<ExponentTransform> {value: 2}\n";
}

}  // namespace trs_test
