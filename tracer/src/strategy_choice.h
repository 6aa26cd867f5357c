#pragma once
// `auto`: the strategy that renders a scene most efficiently, chosen by a pilot (strategy_choice.cpp).

#include <memory>

#include "tracer/camera.h"
#include "tracer/emitters.h"
#include "tracer/geometry.h"
#include "tracer/light_strategy.h"
#include "tracer/renderer.h"
#include "tracer/scene.h"

namespace tracer {

/// A strategy made, and why.
struct ChosenStrategy {
  StrategyChoice choice;
  std::unique_ptr<LightStrategy> strategy;
  /// `auto`: the pilot's time, milliseconds (the strategies it weighed made, their passes
  /// rendered, the texel gain's frame drawn).
  double pilot_ms = 0.0;
};

/// The strategy settings.strategy names, made. For `auto`, each of kPilotStrategies renders a
/// few pilot passes over a grid of the image's pixels, kPilotReuse and kPilotReused the same
/// passes over blocks of neighbouring pixels, and the cheapest within kCheaperMargin of the least
/// relative variance times cost per pass renders. The pilot's seeds are its own: every seed of a scene renders with
/// the same strategy, and the pilot's paths stay out of the image.
ChosenStrategy choose_strategy(const Scene& scene, const Geometry& geometry, Emitters& emitters,
                               const PinholeCamera& camera, const RenderSettings& settings);

}  // namespace tracer
