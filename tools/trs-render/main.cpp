// trs-render: renders a glTF scene lit by emissive textures and writes a linear EXR.
// Exit status: 0 success, 1 bad input or failed run, 2 bad command line, 130 interrupted by
// Ctrl-C (the image of the frames done is saved).

#include <csignal>

#include <atomic>
#include <chrono>
#include <iostream>
#include <new>
#include <string>
#include <vector>

#include "options.h"
#include "run.h"

namespace trs {
namespace {

std::atomic<bool> interrupted{false};
static_assert(std::atomic<bool>::is_always_lock_free, "set from a signal handler");

/// First Ctrl-C: finish the frames done and save them. A second one: the default action.
extern "C" void on_interrupt(int) {
  interrupted = true;
  std::signal(SIGINT, SIG_DFL);
}

/// A shell word: as it is when it is safe, in single quotes otherwise.
std::string quoted(const std::string& word) {
  if (!word.empty() && word.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-.,/:=%+@") ==
                           std::string::npos)
    return word;
  std::string out = "'";
  for (const char c : word) {
    if (c == '\'')
      out.append("'\\''");
    else
      out.push_back(c);
  }
  out.push_back('\'');
  return out;
}

/// --plan: the command line once per chunk of frames, with that chunk's --frames and without
/// --plan and --chunk.
int print_plan(const RenderOptions& options) {
  std::vector<std::string> kept;
  for (std::size_t i = 1; i < options.arguments.size(); ++i) {
    const std::string& a = options.arguments[i];
    if (a == "--plan" || a.starts_with("--chunk=") || a.starts_with("--frames=")) continue;
    if (a == "--chunk" || a == "--frames") {
      ++i;  // and its value
      continue;
    }
    kept.push_back(a);
  }
  const FrameRange frames = *options.frames;
  for (std::int64_t first = frames.first; first <= frames.last; first += *options.plan_chunk) {
    const std::int64_t last = std::min(frames.last, first + *options.plan_chunk - 1);
    std::cout << quoted(options.arguments[0]);
    for (const std::string& a : kept) std::cout << ' ' << quoted(a);
    std::cout << " --frames " << to_string(FrameRange{first, last}) << '\n';
  }
  return 0;
}

int run(const RenderOptions& options) {
  if (options.plan_chunk) return print_plan(options);
  const auto start = std::chrono::steady_clock::now();
  // From here on, Ctrl-C stops cleanly: temporaries are removed and what is done is saved.
  std::signal(SIGINT, on_interrupt);
  const auto print = [](const RunNote& note) { std::cerr << note_line(note) << "\n"; };
  return render(options, start, RunHooks{interrupted, std::cout, print});
}

}  // namespace
}  // namespace trs

int main(int argc, char** argv) {
  auto parsed = trs::parse_render_options(argc, argv);
  if (const int* status = std::get_if<int>(&parsed)) return *status;
  try {
    return trs::run(std::get<trs::RenderOptions>(parsed));
  } catch (const std::bad_alloc&) {
    std::cerr << "trs-render: error: out of memory\n";
  } catch (const std::exception& e) {
    std::cerr << "trs-render: error: " << e.what() << "\n";
  }
  return trs::kRunFailed;
}
