// trs-render's settings file (`--settings FILE`: `key = value` lines, TOML), through its command
// line parser.
#include <iostream>
#include <sstream>

#include "fuzz_input.h"
#include "options.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return trs_fuzz::parse_as_file(data, size, ".toml", [](const std::filesystem::path& path) {
    std::string file = path.string();
    char program[] = "trs-render", scene[] = "scene.gltf", flag[] = "--settings";
    char* argv[] = {program, scene, flag, file.data(), nullptr};
    // The parser reports a bad file on standard error: keep the fuzzer's output readable.
    std::ostringstream silenced;
    std::streambuf* err = std::cerr.rdbuf(silenced.rdbuf());
    try {
      trs::parse_render_options(4, argv);
    } catch (...) {
      std::cerr.rdbuf(err);
      throw;
    }
    std::cerr.rdbuf(err);
  });
}
