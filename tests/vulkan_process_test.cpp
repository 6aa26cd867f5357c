// The process's Vulkan: one instance and one device, however many samplers and contexts come and
// go, and a dropped sampler gives its device memory back. Some drivers cannot be loaded again
// after a few instances (NVIDIA's fails after about 14 in one process), so the library must make
// exactly one. The loader's create, destroy, allocate and free calls are interposed to count
// them: this executable's definitions take the place of the loader's, then call the loader's own.

#include <dlfcn.h>

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "lightsampler/vulkan.h"
#include "sampler_fixtures.h"
#include "vulkan_fixture.h"

namespace {

std::atomic<int> instances_created{0}, instances_destroyed{0}, devices_created{0}, devices_destroyed{0};

// Device memory allocated and not yet freed, by allocation.
std::mutex memory_mutex;
std::map<VkDeviceMemory, VkDeviceSize> live_memory;

VkDeviceSize live_memory_bytes() {
  const std::lock_guard lock(memory_mutex);
  VkDeviceSize bytes = 0;
  for (const auto& [memory, size] : live_memory) bytes += size;
  return bytes;
}

template <class Function>
Function loader(const char* name) {
  return reinterpret_cast<Function>(dlsym(RTLD_NEXT, name));
}

}  // namespace

extern "C" {

VKAPI_ATTR VkResult VKAPI_CALL vkCreateInstance(const VkInstanceCreateInfo* info,
                                                const VkAllocationCallbacks* allocator, VkInstance* instance) {
  static const auto create = loader<PFN_vkCreateInstance>("vkCreateInstance");
  ++instances_created;
  return create(info, allocator, instance);
}

VKAPI_ATTR void VKAPI_CALL vkDestroyInstance(VkInstance instance, const VkAllocationCallbacks* allocator) {
  static const auto destroy = loader<PFN_vkDestroyInstance>("vkDestroyInstance");
  ++instances_destroyed;
  destroy(instance, allocator);
}

VKAPI_ATTR VkResult VKAPI_CALL vkCreateDevice(VkPhysicalDevice physical, const VkDeviceCreateInfo* info,
                                              const VkAllocationCallbacks* allocator, VkDevice* device) {
  static const auto create = loader<PFN_vkCreateDevice>("vkCreateDevice");
  ++devices_created;
  return create(physical, info, allocator, device);
}

VKAPI_ATTR void VKAPI_CALL vkDestroyDevice(VkDevice device, const VkAllocationCallbacks* allocator) {
  static const auto destroy = loader<PFN_vkDestroyDevice>("vkDestroyDevice");
  ++devices_destroyed;
  destroy(device, allocator);
}

VKAPI_ATTR VkResult VKAPI_CALL vkAllocateMemory(VkDevice device, const VkMemoryAllocateInfo* info,
                                                const VkAllocationCallbacks* allocator, VkDeviceMemory* memory) {
  static const auto allocate = loader<PFN_vkAllocateMemory>("vkAllocateMemory");
  const VkResult result = allocate(device, info, allocator, memory);
  if (result == VK_SUCCESS) {
    const std::lock_guard lock(memory_mutex);
    live_memory[*memory] = info->allocationSize;
  }
  return result;
}

VKAPI_ATTR void VKAPI_CALL vkFreeMemory(VkDevice device, VkDeviceMemory memory, const VkAllocationCallbacks* allocator) {
  static const auto free = loader<PFN_vkFreeMemory>("vkFreeMemory");
  {
    const std::lock_guard lock(memory_mutex);
    live_memory.erase(memory);
  }
  free(device, memory, allocator);
}

}  // extern "C"

namespace {

using namespace lightsampler;
using trs_test::Map;
using trs_test::Mesh;
using trs_test::VulkanTest;

// After any Vulkan work of the process: one instance and one device made, none destroyed. Zero
// made would mean the interposition failed, so this cannot pass vacuously.
void expect_one_instance_and_one_device() {
  EXPECT_EQ(instances_created.load(), 1);
  EXPECT_EQ(devices_created.load(), 1);
  EXPECT_EQ(instances_destroyed.load(), 0);
  EXPECT_EQ(devices_destroyed.load(), 0);
}

// Draws samples from `sampler` and checks that they lie where the density is positive.
void expect_working(Sampler& sampler, double target, std::uint64_t seed) {
  Frame frame;
  sampler.generate({.seed = seed, .target_count = target}, frame);
  ASSERT_GT(frame.sample_count, 0u);
  ASSERT_EQ(frame.samples.size(), frame.sample_count);
  EXPECT_EQ(frame.exhausted, 0u);
  for (const Sample& s : frame.samples) ASSERT_GT(sampler.maps().density(s.triangle, s.b1, s.b2), 0.0f);
}

TEST_F(VulkanTest, OneInstanceAndOneDeviceServeEveryContextAndSampler) {
  const Mesh quad = trs_test::quad(1, 1, 0, 0, 1, 1);
  const Map map = trs_test::random_map(8, 8, 0.5, 1);
  const DensityMapView view = map.view();
  {
    const auto second = vk::Context::create();
    const auto by_name = vk::Context::create({.device = context->device_name()});
    EXPECT_FALSE(vk::Context::devices().empty());
    EXPECT_FALSE(vulkan_devices().empty());
    auto a = make_vulkan_sampler(quad.view(), {&view, 1});
    auto b = make_sampler(quad.view(), {&view, 1}, {.backend = Backend::vulkan});
    auto c = make_sampler(quad.view(), {&view, 1},
                          {.backend = Backend::automatic, .cpu = {}, .vulkan = {.device = context->device_name()}});
    EXPECT_EQ(c->backend(), Backend::vulkan);
    for (Sampler* s : {a.get(), b.get(), c.get()}) expect_working(*s, 1000, 1);
  }
  expect_one_instance_and_one_device();
}

TEST(VulkanProcess, FirstUseFromSeveralThreadsMakesOneInstance) {
  // Eight threads make their samplers at once, the process's first Vulkan use when this test runs
  // in a process of its own (as under ctest), then draw frames side by side on the one queue.
  const std::size_t reported_before = vk::validation_message_count();
  const Mesh mesh = trs_test::random_triangles(100, 0.0f, 1.0f, 4);
  const Map map = trs_test::random_map(16, 16, 0.3, 5);
  const DensityMapView view = map.view();
  std::vector<std::string> unavailable(8);
  std::vector<std::thread> threads;
  for (std::size_t t = 0; t < unavailable.size(); ++t)
    threads.emplace_back([&, t] {
      try {
        auto sampler = make_vulkan_sampler(mesh.view(), {&view, 1});
        for (std::uint64_t frame = 0; frame < 5; ++frame) expect_working(*sampler, 5000, t * 5 + frame);
      } catch (const VulkanUnavailable& e) {
        unavailable[t] = e.what();
      }
    });
  for (std::thread& thread : threads) thread.join();
  if (!unavailable[0].empty()) {
    if (trs_test::vulkan_required()) FAIL() << "Vulkan is required here: " << unavailable[0];
    GTEST_SKIP() << "no Vulkan device: " << unavailable[0];
  }
  for (const std::string& u : unavailable) EXPECT_TRUE(u.empty()) << u;
  expect_one_instance_and_one_device();
  EXPECT_EQ(vk::validation_message_count(), reported_before) << "the validation layer reported problems";
}

TEST_F(VulkanTest, SixtySamplersComeAndGo) {
  const Mesh mesh = trs_test::random_triangles(50, 0.0f, 1.0f, 2);
  const Map map = trs_test::random_map(16, 16, 0.3, 3);
  const DensityMapView view = map.view();
  const VkDeviceSize before = live_memory_bytes();
  for (int i = 0; i < 60; ++i) {
    SCOPED_TRACE("sampler " + std::to_string(i));
    {
      auto sampler = make_vulkan_sampler(mesh.view(), {&view, 1});
      expect_working(*sampler, 2000, std::uint64_t(i));
      if (HasFatalFailure()) return;
    }
    ASSERT_EQ(live_memory_bytes(), before) << "device memory left behind by a dropped sampler";
  }
  expect_one_instance_and_one_device();
}

TEST_F(VulkanTest, DroppedSamplersGiveTheirDeviceMemoryBack) {
  // Samplers made and dropped one after another, each holding a map of an eighth of the largest
  // device-local heap (at most the largest buffer, and 1 GiB: host memory holds it twice), until
  // together they have held more than the heap. A sampler that kept its memory would make a
  // later one fail to allocate; where a driver does not enforce its heap size (lavapipe), the
  // count of live allocations still must come back to where it was.
  const vk::Capabilities& caps = context->capabilities();
  const VkDeviceSize bytes =
      std::min({caps.device_local_bytes / 8, caps.max_buffer_size, VkDeviceSize(1) << 30}) & ~VkDeviceSize(0xffff);
  const std::uint32_t width = 16384, height = std::uint32_t(bytes / sizeof(float) / width);
  const Map map{std::vector<float>(std::size_t(width) * height, 1.0f), width, height};
  const DensityMapView view = map.view();
  // Over a few texels only: the memory is the point, not the counting.
  const Mesh quad = trs_test::quad(1, 1, 0, 0, 4.0f / float(width), 4.0f / float(height));
  const VkDeviceSize before = live_memory_bytes();
  const VkDeviceSize held_bytes = VkDeviceSize(width) * height * sizeof(float);
  const std::uint64_t samplers = caps.device_local_bytes / held_bytes + 2;
  for (std::uint64_t i = 0; i < samplers; ++i) {
    SCOPED_TRACE("sampler " + std::to_string(i) + " of " + std::to_string(samplers));
    {
      auto sampler = make_vulkan_sampler(quad.view(), {&view, 1});
      EXPECT_GE(live_memory_bytes(), before + held_bytes);
      expect_working(*sampler, 1000, i);
      if (HasFatalFailure()) return;
    }
    ASSERT_EQ(live_memory_bytes(), before) << "device memory left behind by a dropped sampler";
  }
  EXPECT_GT(samplers * held_bytes, caps.device_local_bytes);
  expect_one_instance_and_one_device();
}

}  // namespace
