#pragma once
// Base fixture of the Vulkan tests: a Context on the default device. Without a usable device the
// test is skipped with the reason, unless LIGHTSAMPLER_REQUIRE_VULKAN=1 (set by CI), which makes
// it fail instead. After each test the validation layer must have reported nothing.

#include <cstdlib>
#include <memory>
#include <string_view>

#include <gtest/gtest.h>

#include "vulkan/context.h"

namespace trs_test {

inline bool vulkan_required() {
  const char* value = std::getenv("LIGHTSAMPLER_REQUIRE_VULKAN");
  return value && std::string_view(value) == "1";
}

class VulkanTest : public ::testing::Test {
 protected:
  void SetUp() override {
    try {
      context = lightsampler::vk::Context::create();
    } catch (const lightsampler::vk::Unavailable& e) {
      if (vulkan_required()) FAIL() << "LIGHTSAMPLER_REQUIRE_VULKAN=1 but Vulkan is unavailable: " << e.what();
      GTEST_SKIP() << "Vulkan unavailable: " << e.what();
    }
  }

  void TearDown() override {
    if (!context) return;
    for (const auto& message : context->validation_messages()) ADD_FAILURE() << message;
  }

  std::unique_ptr<lightsampler::vk::Context> context;
};

}  // namespace trs_test
