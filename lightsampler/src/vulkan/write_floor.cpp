// The Vulkan backend's floor: a kernel that writes N samples to device memory, timed on the GPU.

#include <string>
#include <vector>

#include "vulkan/context.h"
#include "vulkan/layouts.h"
#include "vulkan/passes.h"
#include "vulkan/write_floor.h"
#include "spirv/write_samples_comp.h"

namespace lightsampler::vk {

std::vector<double> sample_write_ms(const VulkanOptions& options, std::uint64_t count, int runs) {
  const auto context = Context::create({options.device, options.validation});
  const Buffer samples = context->create_buffer(std::max<std::uint64_t>(count, 1) * gpu::kSampleBytes);
  const ComputePipeline pipeline = context->create_compute(spirv::write_samples_comp, sizeof(gpu::WritePush));
  const gpu::WritePush push{samples.address(), count};
  std::vector<double> ms;
  for (int run = 0; run < runs; ++run) {
    Commands c = context->begin();
    c.dispatch(pipeline, &push, sizeof push, workgroups_for(count));
    c.timestamp("write");
    ms.push_back(context->submit(c).front().second);
  }
  return ms;
}

}  // namespace lightsampler::vk
