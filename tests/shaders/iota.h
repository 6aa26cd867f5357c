// Push constants of iota.comp, shared by the shader and vulkan_context_test.cpp.
#ifndef TRS_TEST_IOTA_H
#define TRS_TEST_IOTA_H

#ifdef __cplusplus
#include <cstdint>
namespace trs_test {
using uint = std::uint32_t;
using std::uint64_t;
#endif

#define IOTA_WORKGROUP_SIZE 256

struct IotaPush {
  uint64_t words;  // device address of the uint array to write
  uint64_t count;  // words to write: word i gets first + i (mod 2^32)
  uint first;
  uint pad;
};

#ifdef __cplusplus
}  // namespace trs_test
#endif
#endif
