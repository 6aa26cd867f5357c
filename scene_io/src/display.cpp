#include "scene_io/display.h"

#include <OpenColorIO/OpenColorIO.h>

#include <algorithm>
#include <vector>

#include "ocio_apply.h"
#include "scene_io/color.h"
#include "scene_io/file_error.h"

namespace OCIO = OCIO_NAMESPACE;

namespace trs {
namespace {

/// Names and aliases of linear Rec. 709 in common configs, looked up in this order (OpenColorIO
/// ignores case): OpenColorIO's CG and studio configs, Blender's, the ACES 1.x configs.
constexpr const char* kLinearRec709Names[] = {"Linear Rec.709 (sRGB)", "lin_rec709_srgb", "lin_rec709",
                                              "lin_srgb", "Linear Rec.709", "Utility - Linear - Rec.709",
                                              "Utility - Linear - sRGB"};

/// `names` quoted and separated by commas: names have spaces and punctuation of their own.
std::string quoted_list(const std::vector<std::string>& names) {
  std::string list;
  for (const std::string& name : names) list += (list.empty() ? "\"" : ", \"") + name + "\"";
  return list.empty() ? "none" : list;
}

std::vector<std::string> display_names(const OCIO::Config& config) {
  std::vector<std::string> names;
  for (int i = 0; i < config.getNumDisplays(); ++i) names.emplace_back(config.getDisplay(i));
  return names;
}

std::vector<std::string> view_names(const OCIO::Config& config, const std::string& display) {
  std::vector<std::string> names;
  for (int i = 0; i < config.getNumViews(display.c_str()); ++i)
    names.emplace_back(config.getView(display.c_str(), i));
  return names;
}

std::vector<std::string> colorspace_names(const OCIO::Config& config) {
  std::vector<std::string> names;
  for (int i = 0; i < config.getNumColorSpaces(); ++i)
    names.emplace_back(config.getColorSpaceNameByIndex(i));
  return names;
}

OCIO::ConstConfigRcPtr read_config(const std::string& file) {
#if OCIO_VERSION_HEX < 0x02020000
  // Older versions take the URI for a file name and say that they cannot read it.
  if (file.starts_with("ocio://"))
    throw FileError(file, "built-in configs need OpenColorIO 2.2 or later; this build has "
                          OCIO_VERSION_STR);
#endif
  try {
    return OCIO::Config::CreateFromFile(file.c_str());
  } catch (const OCIO::Exception& e) {
    throw FileError(file, std::string("cannot read the OpenColorIO config: ") + e.what());
  }
}

/// `given`, or `fallback` when none is given, checked against the config's `names` of `what`.
std::string checked_name(const std::string& file, const std::string& what,
                         const std::vector<std::string>& names, const std::string& given,
                         const std::string& fallback) {
  const std::string& name = given.empty() ? fallback : given;
  if (std::find(names.begin(), names.end(), name) == names.end())
    throw FileError(file, (given.empty() ? "no default " + what : "no " + what + " \"" + given + "\"") +
                              " (its " + what + "s: " + quoted_list(names) + ")");
  return name;
}

struct InputSpace {
  std::string name;
  std::string warning;  ///< why the space is a guess, if it is one
};

/// The renders' colour space: the one given, else the config's linear Rec. 709, else its
/// scene_linear role, named as the config names it (not by an alias or role).
InputSpace input_space(const OCIO::Config& config, const std::string& file,
                       const std::string& given) {
  if (!given.empty()) {
    if (const OCIO::ConstColorSpaceRcPtr space = config.getColorSpace(given.c_str()))
      return {space->getName(), ""};
    throw FileError(file, "no colour space \"" + given + "\" (its colour spaces: " +
                              quoted_list(colorspace_names(config)) + ")");
  }
  for (const char* name : kLinearRec709Names)
    if (const OCIO::ConstColorSpaceRcPtr space = config.getColorSpace(name))
      return {space->getName(), ""};
  const std::vector<std::string> tried(std::begin(kLinearRec709Names), std::end(kLinearRec709Names));
  const std::string missing = "no colour space for linear Rec. 709 (none of " + quoted_list(tried) + ")";
  if (const OCIO::ConstColorSpaceRcPtr space = config.getColorSpace(OCIO::ROLE_SCENE_LINEAR))
    return {space->getName(), file + ": " + missing + "; the renders are taken to be in its scene_linear role's, \"" +
                                  space->getName() + "\", whose primaries may not be Rec. 709's"};
  throw FileError(file, missing + " and no scene_linear role: the renders' colour space must be named (its colour spaces: " +
                            quoted_list(colorspace_names(config)) + ")");
}

/// The processor from `t.colorspace` to `t.display` and `t.view`, names the config has.
OCIO::ConstCPUProcessorRcPtr display_processor(const OCIO::Config& config, const DisplayTransform& t) {
  try {
    // Lossless: the default optimisation trades pow and log for fast approximations.
    return config.getProcessor(t.colorspace.c_str(), t.display.c_str(), t.view.c_str(), OCIO::TRANSFORM_DIR_FORWARD)
        ->getOptimizedCPUProcessor(OCIO::OPTIMIZATION_LOSSLESS);
  } catch (const OCIO::Exception& e) {
    throw FileError(t.config, "cannot make the transform from \"" + t.colorspace + "\" to display \"" + t.display +
                                  "\", view \"" + t.view + "\": " + e.what());
  }
}

}  // namespace

DisplayEncoder::DisplayEncoder() : DisplayEncoder(DisplayTransform{}) {}

DisplayEncoder::DisplayEncoder(const DisplayTransform& transform) : transform_(transform), encode_(linear_to_srgb) {
  if (transform.config.empty()) return;
  const std::string& file = transform.config;
  const OCIO::ConstConfigRcPtr config = read_config(file);
  InputSpace input = input_space(*config, file, transform.colorspace);
  transform_.colorspace = input.name;
  warning_ = std::move(input.warning);
  transform_.display = checked_name(file, "display", display_names(*config), transform.display,
                                    config->getDefaultDisplay());
  transform_.view = checked_name(file, "view", view_names(*config, transform_.display), transform.view,
                                 config->getDefaultView(transform_.display.c_str(), transform_.colorspace.c_str()));
  const OCIO::ConstCPUProcessorRcPtr processor = display_processor(*config, transform_);
  encode_ = [processor](std::span<float> rgb) { apply(*processor, rgb); };
}

}  // namespace trs
