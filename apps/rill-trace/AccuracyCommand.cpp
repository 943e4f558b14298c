// rill-trace accuracy: the options of the accuracy benchmark (AccuracyBench.h), which times
// every accuracy knob against its error on every backend.
#include "CliChecks.h"
#include "Commands.h"

namespace trace_cli {

CLI::App* add_accuracy_command(CLI::App& app, AccuracyCommandOptions& o) {
  CLI::App* acc = app.add_subcommand(
      "accuracy", "time against error for every accuracy knob on every backend (a benchmark)");
  acc->add_option("--backends", o.backends, "comma-separated (default: every available)");
  acc->add_option("--scenes", o.scenes,
                  "comma-separated subset of closed,inside,floor-far,floor-tiny,cornell,glass");
  add_parsed_option(acc, "--size", o.size, checked_size, "image size WxH (default 64x48)");
  acc->add_option("--repeats", o.bench.repeats, "timing repeats (median)")
      ->check(number_in(1, 100, true));
  acc->add_flag(
      "--one-at-a-time", [&](int64_t) { o.bench.factorial = false; },
      "vary one knob at a time instead of every combination");
  acc->add_option("--out-dir", o.bench.out_dir, "where accuracy.{md,csv,gp,svg} go");
  return acc;
}

int accuracy(const AccuracyCommandOptions& o) {
  rt::AccuracyBenchOptions bench = o.bench;
  bench.backends = split_list(o.backends);
  bench.scenes = split_list(o.scenes);
  if (!o.size.empty()) parse_size(o.size, bench.width, bench.height);
  return rt::accuracy_bench(bench);
}

}  // namespace trace_cli
