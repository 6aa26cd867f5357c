// The CPU backend's floor: writing N samples to host memory, in parallel, as realization does.

#include <algorithm>
#include <chrono>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "cpu/passes.h"

namespace lightsampler::cpu {

std::vector<double> sample_write_ms(const CpuOptions& options, std::uint64_t count, int runs) {
  tbb::task_arena arena(int(worker_threads(options)));
  Buffer<Sample> samples;
  std::vector<double> ms;
  arena.execute([&] {
    for (int run = 0; run < runs; ++run) {
      const auto start = std::chrono::steady_clock::now();
      samples.resize(count);
      tbb::parallel_for(tbb::blocked_range<std::uint64_t>(0, count, 1 << 16),
                        [&](const tbb::blocked_range<std::uint64_t>& r) {
                          for (std::uint64_t i = r.begin(); i != r.end(); ++i)
                            samples[i] = {std::uint32_t(i), 0.25f, 0.25f};
                        });
      ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
    }
  });
  return ms;
}

}  // namespace lightsampler::cpu
