// The backend-neutral factory: present in every build of the library, with or without Vulkan.

#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "lightsampler/backend.h"
#include "sampler_fixtures.h"

using namespace lightsampler;

namespace {

const trs_test::Mesh kQuad = trs_test::quad(1, 1, 0, 0, 1, 1);
const trs_test::Map kMap{{1.0f, 3.0f}, 2, 1};

std::unique_ptr<Sampler> make(const SamplerOptions& options) {
  const DensityMapView view = kMap.view();
  return make_sampler(kQuad.view(), {&view, 1}, options);
}

TEST(Backend, CpuIsAlwaysThere) {
  auto sampler = make({.backend = Backend::cpu});
  EXPECT_EQ(sampler->backend(), Backend::cpu);
  Frame frame;
  sampler->generate({.seed = 1, .target_count = 1000}, frame);
  EXPECT_EQ(frame.expected_total, 2.0);
}

TEST(Backend, WithoutVulkanAutomaticIsTheCpuAndVulkanIsRefused) {
  if (has_vulkan_backend()) GTEST_SKIP() << "this build has the Vulkan backend (the vulkan tests cover it)";
  EXPECT_EQ(make({})->backend(), Backend::cpu);
  EXPECT_TRUE(vulkan_devices().empty());
  try {
    make({.backend = Backend::vulkan});
    ADD_FAILURE() << "Backend::vulkan gave a sampler in a build without Vulkan";
  } catch (const VulkanUnavailable& e) {
    EXPECT_NE(std::string(e.what()).find("LIGHTSAMPLER_VULKAN=OFF"), std::string::npos) << e.what();
  }
}

TEST(Backend, TheCpuWriteFloorIsATime) {
  const double ms = sample_write_ms(Backend::cpu, {}, 1'000'000, 3);
  EXPECT_TRUE(std::isfinite(ms) && ms > 0) << ms;
  EXPECT_THROW(sample_write_ms(Backend::automatic, {}, 1000), std::invalid_argument);
  EXPECT_THROW(sample_write_ms(Backend::cpu, {}, 1000, 0), std::invalid_argument);
  if (!has_vulkan_backend()) EXPECT_THROW(sample_write_ms(Backend::vulkan, {}, 1000), VulkanUnavailable);
}

TEST(Backend, NamesAreTheCommandLines) {
  EXPECT_STREQ(to_string(Backend::automatic), "auto");
  EXPECT_STREQ(to_string(Backend::cpu), "cpu");
  EXPECT_STREQ(to_string(Backend::vulkan), "vulkan");
}

}  // namespace
