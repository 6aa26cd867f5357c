// The Vulkan runtime on whatever device the machine has (lavapipe in CI), with the validation
// layer on: device selection, buffers past 128 MiB written through device addresses, grid-stride
// dispatches doing the work of more than 65,535 workgroups, raster passes without attachments,
// and timestamps.

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstddef>
#include <cstdlib>
#include <iostream>
#include <string>
#include <vector>

#include "shaders/coverage.h"
#include "shaders/iota.h"
#include "spirv/count_frag.h"
#include "spirv/iota_comp.h"
#include "spirv/pass_geom.h"
#include "spirv/quad_vert.h"
#include "support/environment.h"
#include "vulkan_fixture.h"

namespace {

namespace vk = lightsampler::vk;
using trs_test::CoveragePush;
using trs_test::IotaPush;
using trs_test::VulkanTest;

static_assert(sizeof(IotaPush) == 24 && offsetof(IotaPush, count) == 8 && offsetof(IotaPush, first) == 16);
static_assert(sizeof(CoveragePush) == 8);

constexpr VkDeviceSize kMiB = VkDeviceSize(1) << 20;
// The most workgroups lavapipe (and the spec's minimum) allows in one dimension.
constexpr std::uint32_t kMaxGroups = 65535;

// Records iota.comp: word i of `count` words from byte `offset` of `b` becomes first + i.
void iota(vk::Commands& cmd, const vk::ComputePipeline& pipeline, const vk::Buffer& b, VkDeviceSize offset,
          std::uint64_t count, std::uint32_t first, std::uint32_t groups) {
  const IotaPush push{b.address() + offset, count, first, 0};
  cmd.dispatch(pipeline, &push, sizeof push, groups);
}

std::vector<std::uint32_t> download_words(vk::Context& context, const vk::Buffer& b, VkDeviceSize offset,
                                          std::size_t count) {
  std::vector<std::uint32_t> words(count);
  context.download(b, offset, words.data(), count * sizeof(std::uint32_t));
  return words;
}

// Index of the first word that is not first + i, or -1 (so a failure names the word).
std::ptrdiff_t first_wrong_iota(const std::vector<std::uint32_t>& words, std::uint32_t first) {
  for (std::size_t i = 0; i < words.size(); ++i)
    if (words[i] != first + std::uint32_t(i)) return std::ptrdiff_t(i);
  return -1;
}

std::string lower(std::string s) {
  for (char& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

TEST_F(VulkanTest, ListsDevicesWithTheirSuitability) {
  const auto devices = vk::Context::devices();
  ASSERT_FALSE(devices.empty());
  bool chosen_listed = false;
  for (std::size_t i = 0; i < devices.size(); ++i) {
    EXPECT_EQ(devices[i].index, i);
    EXPECT_EQ(devices[i].suitable, devices[i].missing.empty()) << devices[i].name << ": " << devices[i].missing;
    if (devices[i].name == context->device_name()) chosen_listed = chosen_listed || devices[i].suitable;
  }
  EXPECT_TRUE(chosen_listed) << context->device_name() << " is not listed as suitable";
}

TEST_F(VulkanTest, SelectsDeviceByIndex) {
  const auto devices = vk::Context::devices();
  for (const auto& d : devices) {
    if (!d.suitable) {
      EXPECT_THROW(vk::Context::create({.device = std::to_string(d.index)}), vk::Unavailable) << d.name;
      continue;
    }
    const auto chosen = vk::Context::create({.device = std::to_string(d.index)});
    EXPECT_EQ(chosen->device_name(), d.name);
  }
}

TEST_F(VulkanTest, SelectsDeviceByCaseInsensitiveNameSubstring) {
  // The first word of the name with its case flipped: "llvmpipe (LLVM 15...)" -> "LLVMPIPE".
  std::string word = context->device_name().substr(0, context->device_name().find(' '));
  for (char& c : word) c = char(std::islower(static_cast<unsigned char>(c)) ? std::toupper(c) : std::tolower(c));
  const auto chosen = vk::Context::create({.device = word});
  EXPECT_NE(lower(chosen->device_name()).find(lower(word)), std::string::npos) << chosen->device_name();
}

TEST_F(VulkanTest, UnknownDeviceIsUnavailableAndListsTheDevices) {
  const auto devices = vk::Context::devices();
  for (const std::string request : {"no such device", "99"}) {
    try {
      vk::Context::create({.device = request});
      ADD_FAILURE() << "device \"" << request << "\" was found";
    } catch (const vk::Unavailable& e) {
      const std::string message = e.what();
      EXPECT_NE(message.find("\"" + request + "\" not found"), std::string::npos) << message;
      for (const auto& d : devices) EXPECT_NE(message.find(d.name), std::string::npos) << message;
    }
  }
}

TEST_F(VulkanTest, EnvironmentChoosesTheDeviceUnlessOptionsDo) {
  const trs_test::ScopedEnvironment device("LIGHTSAMPLER_VULKAN_DEVICE", "no such device");
  EXPECT_THROW(vk::Context::create(), vk::Unavailable);
  const auto chosen = vk::Context::create({.device = context->device_name()});
  EXPECT_EQ(chosen->device_name(), context->device_name());
}

TEST_F(VulkanTest, ReportsCapabilitiesWithinTheSpecMinimums) {
  const vk::Capabilities& caps = context->capabilities();
  std::cout << context->device_name() << ": subgroup " << caps.subgroup_size << ", timestamp period "
            << caps.timestamp_period_ns << " ns, max workgroups x " << caps.max_workgroup_count_x
            << ", max buffer " << caps.max_buffer_size / kMiB << " MiB, raster " << caps.raster
            << ", geometry " << caps.geometry_shader << ", conservative " << caps.conservative_rasterization
            << ", validation " << context->validation_enabled() << "\n";
  EXPECT_GE(caps.subgroup_size, 1u);
  EXPECT_EQ(caps.subgroup_size & (caps.subgroup_size - 1), 0u) << "not a power of two";
  EXPECT_GT(caps.timestamp_period_ns, 0.0f);
  EXPECT_GE(caps.max_workgroup_count_x, kMaxGroups);
  EXPECT_GE(caps.max_buffer_size, VkDeviceSize(1) << 30);  // maxMemoryAllocationSize >= 1 GiB
  EXPECT_TRUE(caps.geometry_shader <= caps.raster);
}

TEST_F(VulkanTest, EmptyBuffersStillHaveAnAddress) {
  for (const bool host_visible : {false, true}) {
    const vk::Buffer b = context->create_buffer(0, host_visible);
    ASSERT_TRUE(b);
    EXPECT_EQ(b.size(), 0u);
    EXPECT_NE(b.address(), 0u);
    EXPECT_EQ(b.mapped() != nullptr, host_visible);
    context->upload(b, 0, nullptr, 0);
  }
}

TEST_F(VulkanTest, TransfersOutsideTheBufferThrow) {
  const vk::Buffer b = context->create_buffer(16);
  std::uint32_t words[8] = {};
  EXPECT_THROW(context->upload(b, 8, words, 16), std::out_of_range);
  EXPECT_THROW(context->download(b, 20, words, 0), std::out_of_range);
  EXPECT_NO_THROW(context->download(b, 0, words, 16));
}

// 200 MiB: more than lavapipe's 128 MiB maxStorageBufferRange and three staging chunks.
TEST_F(VulkanTest, UploadAndDownloadRoundTripBeyond128MiB) {
  const VkDeviceSize bytes = 200 * kMiB;
  const vk::Buffer b = context->create_buffer(bytes);
  std::vector<std::uint32_t> data(bytes / 4);
  for (std::size_t i = 0; i < data.size(); ++i) data[i] = std::uint32_t(i * 2654435761u);
  context->upload(b, 0, data.data(), bytes);
  EXPECT_EQ(download_words(*context, b, 0, data.size()), data);

  // A piece at an offset past 128 MiB replaces exactly its own range.
  const VkDeviceSize offset = 150 * kMiB + 4;
  const std::vector<std::uint32_t> piece(kMiB / 4, 0xABCD1234u);
  context->upload(b, offset, piece.data(), kMiB);
  std::copy(piece.begin(), piece.end(), data.begin() + offset / 4);
  EXPECT_EQ(download_words(*context, b, offset - 4 * kMiB, 6 * kMiB / 4),
            std::vector<std::uint32_t>(data.begin() + (offset - 4 * kMiB) / 4,
                                       data.begin() + (offset + 2 * kMiB) / 4));
}

// Grid-stride: 65,535 workgroups of 256 invocations write 52,428,800 words, the work of 204,800
// workgroups, each invocation looping 3 or 4 times; addresses run past 128 MiB.
TEST_F(VulkanTest, ComputeWrites200MiBThroughItsDeviceAddress) {
  const VkDeviceSize bytes = 200 * kMiB, tail = kMiB;
  const std::uint64_t words = bytes / 4;
  ASSERT_GT(words, std::uint64_t(kMaxGroups) * IOTA_WORKGROUP_SIZE);
  const vk::Buffer b = context->create_buffer(bytes + tail);
  const vk::ComputePipeline pipeline = context->create_compute(lightsampler::spirv::iota_comp, sizeof(IotaPush));

  vk::Commands cmd = context->begin();
  cmd.fill(b, bytes, tail, 0xDEADBEEFu);  // must survive: the shader stops at `words`
  cmd.barrier();
  iota(cmd, pipeline, b, 0, words, 7, kMaxGroups);
  context->submit(cmd);

  const auto result = download_words(*context, b, 0, words);
  EXPECT_EQ(first_wrong_iota(result, 7), -1);
  const auto after = download_words(*context, b, bytes, tail / 4);
  EXPECT_TRUE(std::all_of(after.begin(), after.end(), [](std::uint32_t w) { return w == 0xDEADBEEFu; }));
}

TEST_F(VulkanTest, HostVisibleBuffersAreMappedAndSeeShaderWrites) {
  const std::uint64_t words = 1 << 18;
  const vk::Buffer b = context->create_buffer(words * 4, true);
  ASSERT_NE(b.mapped(), nullptr);
  const vk::ComputePipeline pipeline = context->create_compute(lightsampler::spirv::iota_comp, sizeof(IotaPush));
  vk::Commands cmd = context->begin();
  iota(cmd, pipeline, b, 0, words, 1000, 64);
  context->submit(cmd);
  const auto* mapped = static_cast<const std::uint32_t*>(b.mapped());
  EXPECT_EQ(first_wrong_iota({mapped, mapped + words}, 1000), -1);

  const std::vector<std::uint32_t> data{1, 2, 3, 4};
  context->upload(b, 8, data.data(), 16);
  EXPECT_EQ(download_words(*context, b, 8, 4), data);
}

TEST_F(VulkanTest, BarriersOrderFillsCopiesAndDispatches) {
  const VkDeviceSize bytes = 4 * kMiB;
  const vk::Buffer a = context->create_buffer(bytes), b = context->create_buffer(bytes);
  const vk::ComputePipeline pipeline = context->create_compute(lightsampler::spirv::iota_comp, sizeof(IotaPush));
  vk::Commands cmd = context->begin();
  cmd.fill(a, 0, bytes, 5);
  cmd.fill(b, 0, bytes, 9);
  cmd.barrier();
  cmd.copy(a, 0, b, kMiB, kMiB);      // b: [0, 1) MiB 9, [1, 2) MiB 5, rest 9
  cmd.barrier();
  iota(cmd, pipeline, a, 0, 1024, 0, 4);  // a: words [0, 1024) iota, rest 5
  cmd.barrier();
  cmd.copy(a, 0, b, 0, 8192);         // b: words [0, 1024) iota, [1024, 2048) 5
  context->submit(cmd);

  const auto result = download_words(*context, b, 0, bytes / 4);
  for (std::size_t i = 0; i < result.size(); ++i) {
    const std::uint32_t expected = i < 1024 ? std::uint32_t(i) : i < 2048 ? 5 : i < kMiB / 4 ? 9 : i < kMiB / 2 ? 5 : 9;
    ASSERT_EQ(result[i], expected) << "word " << i;
  }
}

TEST_F(VulkanTest, DroppedCommandsRunNothing) {
  const vk::Buffer b = context->create_buffer(64);
  const std::vector<std::uint32_t> zeros(16, 0);
  context->upload(b, 0, zeros.data(), 64);
  {
    vk::Commands cmd = context->begin();
    cmd.fill(b, 0, 64, 1);
  }
  EXPECT_EQ(download_words(*context, b, 0, 16), zeros);
}

TEST_F(VulkanTest, CommandsAreSubmittedOnce) {
  vk::Commands cmd = context->begin();
  context->submit(cmd);
  EXPECT_THROW(context->submit(cmd), std::logic_error);
}

// 100 stamps: more than one query pool of 64.
TEST_F(VulkanTest, TimestampsAreNamedInOrderAndNonNegative) {
  const vk::Buffer b = context->create_buffer(4 * kMiB);
  const vk::ComputePipeline pipeline = context->create_compute(lightsampler::spirv::iota_comp, sizeof(IotaPush));
  for (int round = 0; round < 2; ++round) {
    vk::Commands cmd = context->begin();
    for (int i = 0; i < 100; ++i) {
      iota(cmd, pipeline, b, 0, kMiB, i, 256);
      cmd.barrier();
      cmd.timestamp("pass " + std::to_string(i));
    }
    const auto times = context->submit(cmd);
    ASSERT_EQ(times.size(), 100u);
    for (int i = 0; i < 100; ++i) {
      EXPECT_EQ(times[i].first, "pass " + std::to_string(i));
      EXPECT_GE(times[i].second, 0.0) << times[i].first;  // NaN fails too
      EXPECT_TRUE(std::isfinite(times[i].second)) << times[i].first;
    }
  }
}

class VulkanRasterTest : public VulkanTest {
 protected:
  // Draws quad.vert's two triangles over width x height with the given stages; returns the
  // fragments count.frag counted.
  std::uint32_t count_fragments(const vk::RasterStages& stages, std::uint32_t width, std::uint32_t height) {
    const vk::RasterPipeline pipeline = context->create_raster(stages, sizeof(CoveragePush));
    const vk::Buffer counter = context->create_buffer(4);
    vk::Commands cmd = context->begin();
    cmd.fill(counter, 0, 4, 0);
    cmd.barrier();
    const CoveragePush push{counter.address()};
    cmd.draw(pipeline, &push, sizeof push, width, height, 6);
    context->submit(cmd);
    return download_words(*context, counter, 0, 1)[0];
  }

  vk::RasterStages stages() const {
    return {.vertex = lightsampler::spirv::quad_vert, .fragment = lightsampler::spirv::count_frag};
  }

  void SetUp() override {
    VulkanTest::SetUp();
    if (context && !context->capabilities().raster) {
      EXPECT_THROW(context->create_raster(stages(), sizeof(CoveragePush)), vk::Unavailable);
      GTEST_SKIP() << context->device_name() << " cannot rasterize";
    }
  }
};

TEST_F(VulkanRasterTest, CoversEachPixelOnceWithoutAttachments) {
  EXPECT_EQ(count_fragments(stages(), 64, 48), 64u * 48u);
}

TEST_F(VulkanRasterTest, GeometryStagePassesTrianglesThrough) {
  vk::RasterStages with_geometry = stages();
  with_geometry.geometry = lightsampler::spirv::pass_geom;
  if (!context->capabilities().geometry_shader) {
    EXPECT_THROW(context->create_raster(with_geometry, sizeof(CoveragePush)), vk::Unavailable);
    GTEST_SKIP() << context->device_name() << " has no geometry shaders";
  }
  EXPECT_EQ(count_fragments(with_geometry, 64, 48), 64u * 48u);
}

// Conservative: the pixels on the shared diagonal belong to both triangles.
TEST_F(VulkanRasterTest, ConservativeRasterizationCoversEveryTouchedPixel) {
  vk::RasterStages conservative = stages();
  conservative.conservative = true;
  if (!context->capabilities().conservative_rasterization) {
    EXPECT_THROW(context->create_raster(conservative, sizeof(CoveragePush)), vk::Unavailable);
    GTEST_SKIP() << context->device_name() << " has no conservative rasterization";
  }
  const std::uint32_t fragments = count_fragments(conservative, 64, 48);
  EXPECT_GT(fragments, 64u * 48u);
  EXPECT_LE(fragments, 64u * 48u + 3 * (64u + 48u));
}

// The empty-message check of every other test can fail: misuse is reported.
TEST_F(VulkanTest, ValidationReportsMisuse) {
  const auto checked = vk::Context::create({.validation = true});
  if (!checked->validation_enabled()) {
    if (trs_test::vulkan_required()) FAIL() << "the Khronos validation layer is not installed";
    GTEST_SKIP() << "the Khronos validation layer is not installed";
  }
  const vk::Buffer b = checked->create_buffer(64);
  {
    vk::Commands cmd = checked->begin();
    cmd.fill(b, 2, 8, 0);  // vkCmdFillBuffer needs a multiple of 4 offset
  }
  const auto messages = checked->validation_messages();
  EXPECT_TRUE(std::any_of(messages.begin(), messages.end(),
                          [](const std::string& m) { return m.find("vkCmdFillBuffer") != std::string::npos; }));
  expect_reported_so_far();
}

}  // namespace
