// Push constants of the coverage shaders (quad.vert, pass.geom, count.frag), shared by them and
// vulkan_context_test.cpp.
#ifndef TRS_TEST_COVERAGE_H
#define TRS_TEST_COVERAGE_H

#ifdef __cplusplus
#include <cstdint>
namespace trs_test {
using std::uint64_t;
#endif

struct CoveragePush {
  uint64_t counter;  // device address of one uint, incremented once per fragment
};

#ifdef __cplusplus
}  // namespace trs_test
#endif
#endif
