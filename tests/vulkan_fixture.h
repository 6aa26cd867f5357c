#pragma once
// Base fixture of the Vulkan tests: a Context on the default device. Without a usable device the
// test is skipped with the reason, unless LIGHTSAMPLER_REQUIRE_VULKAN=1 (set by CI), which makes
// it fail instead. During each test the validation layer must report nothing (its messages are
// the process's, since every Context shares the process's one instance).

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
    reported_before_ = lightsampler::vk::validation_message_count();
    try {
      context = lightsampler::vk::Context::create();
    } catch (const lightsampler::vk::Unavailable& e) {
      if (vulkan_required()) FAIL() << "LIGHTSAMPLER_REQUIRE_VULKAN=1 but Vulkan is unavailable: " << e.what();
      GTEST_SKIP() << "Vulkan unavailable: " << e.what();
    }
  }

  void TearDown() override {
    if (!context) return;
    const auto messages = context->validation_messages();
    for (std::size_t i = reported_before_; i < messages.size(); ++i) ADD_FAILURE() << messages[i];
  }

  /// For tests that provoke validation messages on purpose: what was reported so far is expected.
  void expect_reported_so_far() { reported_before_ = lightsampler::vk::validation_message_count(); }

  std::unique_ptr<lightsampler::vk::Context> context;

 private:
  std::size_t reported_before_ = 0;
};

}  // namespace trs_test
