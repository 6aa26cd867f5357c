// Samples a unit quad with a 2x1 density map through the installed library.
#include <cstdio>
#include <vector>

#include <lightsampler/lightsampler.h>

int main() {
  const std::vector<float> positions = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
  const std::vector<float> uvs = {0, 0, 1, 0, 1, 1, 0, 1};
  const std::vector<std::uint32_t> indices = {0, 1, 2, 0, 2, 3};
  const std::vector<float> texels = {1.0f, 3.0f};
  const lightsampler::DensityMapView map{texels, 2, 1};
  // The backend-neutral factory, present whatever backends the library was built with.
  auto sampler = lightsampler::make_sampler({positions, uvs, indices, {}}, {&map, 1},
                                            {.backend = lightsampler::Backend::cpu});
  lightsampler::Frame frame;
  sampler->generate({.seed = 1, .target_count = 1000}, frame);
  std::printf("%llu samples, N-bar %.3f, on %s\n", static_cast<unsigned long long>(frame.sample_count),
              frame.expected_total, sampler->device().c_str());
  return frame.sample_count == 1000 && frame.expected_total == 2.0 ? 0 : 1;
}
