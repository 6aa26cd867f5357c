// trs-render: renders a glTF scene lit by emissive textures and writes a linear EXR.
// Exit status: 0 success, 1 bad input or failed run, 2 bad command line; 128 + the signal when
// stopped by SIGINT (Ctrl-C, 130), SIGTERM (Slurm's time limit and scancel, 143) or SIGHUP (129):
// a still saves the passes done, a sequence the frames done (and the frame under way with
// --save-partial).

#include <signal.h>

#include <csignal>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <iostream>
#include <new>
#include <string>
#include <vector>

#include "options.h"
#include "plan.h"
#include "run.h"
#include "slurm.h"

namespace trs {
namespace {

/// The signals that stop a render cleanly: Ctrl-C, and what Slurm sends at a time limit, on
/// scancel and on preemption (SIGTERM, then SIGKILL after its KillWait), and a hang-up.
constexpr int kStopSignals[] = {SIGINT, SIGTERM, SIGHUP};

std::atomic<bool> interrupted{false};
std::atomic<int> stop_signal{0};
static_assert(std::atomic<bool>::is_always_lock_free && std::atomic<int>::is_always_lock_free,
              "set from a signal handler");

/// The first stop signal: the passes done are saved. A second one: the default action.
extern "C" void on_stop_signal(int signal) {
  stop_signal = signal;
  interrupted = true;
  for (const int s : kStopSignals) {
    struct sigaction current;
    if (sigaction(s, nullptr, &current) == 0 && current.sa_handler == on_stop_signal) std::signal(s, SIG_DFL);
  }
}

/// From here on, a stop signal stops cleanly: temporaries are removed and what is done is saved.
/// A signal ignored on entry (SIGHUP under nohup) stays ignored.
void catch_stop_signals() {
  for (const int s : kStopSignals) {
    struct sigaction current;
    if (sigaction(s, nullptr, &current) == 0 && current.sa_handler != SIG_IGN) std::signal(s, on_stop_signal);
  }
}

/// --plan: the command line once per chunk of frames, with that chunk's --frames and without
/// --plan and --chunk.
int print_plan(const RenderOptions& options) {
  for (const PlannedCommand& c : plan_commands(options, options.arguments[0], *options.plan_chunk, false))
    std::cout << c.command << '\n';
  return 0;
}

/// --submit slurm: the job id on standard output, the rest on standard error; with --wait, the
/// frames of the tasks that failed.
int submit(const RenderOptions& options) {
  const SlurmOutcome outcome = submit_to_slurm(options, std::filesystem::canonical("/proc/self/exe"), std::cerr);
  std::cout << outcome.job.id << std::endl;
  if (!options.submit->wait) return 0;
  for (std::size_t i = 0; i < outcome.missing.size(); ++i) {
    std::cerr << "trs-render: error: Slurm job " << outcome.job.id << " task " << outcome.missing_tasks[i]
              << " left frames " << to_string(outcome.missing[i]) << " unwritten (its log: trs-render-"
              << outcome.job.id << "_" << outcome.missing_tasks[i] << ".log beside the outputs)\n";
  }
  if (!outcome.missing.empty()) return kRunFailed;
  if (outcome.sbatch_status != 0) {
    std::cerr << "trs-render: error: Slurm job " << outcome.job.id << " ended with sbatch status "
              << outcome.sbatch_status << ", though every frame is written\n";
    return kRunFailed;
  }
  return 0;
}

int run(const RenderOptions& options) {
  if (options.plan_chunk) return print_plan(options);
  if (options.submit) return submit(options);
  const auto start = std::chrono::steady_clock::now();
  catch_stop_signals();
  const auto print = [](const RunNote& note) { std::cerr << note_line(note) << "\n"; };
  const int status = render(options, start, RunHooks{interrupted, std::cout, print});
  return status == kInterrupted && stop_signal != 0 ? 128 + stop_signal : status;
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
