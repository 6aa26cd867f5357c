// trs-render's settings file (`--settings FILE`: `key = value` lines, TOML), through its command
// line parser.
#include "fuzz_input.h"
#include "options.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return trs_fuzz::parse_as_file(data, size, ".toml", [](const std::filesystem::path& path) {
    // A bad file comes back as a usage error, not printed: the fuzzer's output stays readable.
    trs::parse_render_arguments({"trs-render", "scene.gltf", "--settings", path.string()}, true);
  });
}
