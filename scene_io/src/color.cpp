#include "scene_io/color.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>

#include "ocio_apply.h"

namespace OCIO = OCIO_NAMESPACE;

namespace trs {
namespace {

/// The sRGB curve; its forward direction decodes (encoded to linear), as ExponentTransform's does.
OCIO::ConstCPUProcessorRcPtr srgb_curve(OCIO::TransformDirection direction) {
  auto curve = OCIO::ExponentWithLinearTransform::Create();
  curve->setGamma({2.4, 2.4, 2.4, 1.0});
  curve->setOffset({0.055, 0.055, 0.055, 0.0});
  curve->setDirection(direction);
  // Lossless: the default optimisation trades pow for a fast approximation.
  return OCIO::Config::CreateRaw()->getProcessor(curve)->getOptimizedCPUProcessor(
      OCIO::OPTIMIZATION_LOSSLESS);
}

}  // namespace

void apply(const OCIO::CPUProcessor& processor, std::span<float> values) {
  // Whole RGB pixels in parallel blocks (applying a processor is thread-safe), then the one or
  // two values left over as a padded pixel.
  const std::size_t pixels = values.size() / 3;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, pixels, 16384),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      OCIO::PackedImageDesc block(values.data() + 3 * range.begin(),
                                                  long(range.size()), 1, 3);
                      processor.apply(block);
                    });
  const std::span<float> rest = values.subspan(3 * pixels);
  if (rest.empty()) return;
  std::array<float, 3> pixel{};
  std::copy(rest.begin(), rest.end(), pixel.begin());
  processor.applyRGB(pixel.data());
  std::copy_n(pixel.begin(), rest.size(), rest.begin());
}

void srgb_to_linear(std::span<float> values) {
  static const OCIO::ConstCPUProcessorRcPtr decode = srgb_curve(OCIO::TRANSFORM_DIR_FORWARD);
  apply(*decode, values);
}

void linear_to_srgb(std::span<float> values) {
  static const OCIO::ConstCPUProcessorRcPtr encode = srgb_curve(OCIO::TRANSFORM_DIR_INVERSE);
  apply(*encode, values);
}

}  // namespace trs
