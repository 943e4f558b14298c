// rill-trace noise: the options of the sampling-noise benchmark (NoiseBench.h), which times
// path-traced renders against their error per spp, backend, math mode and sampling variant.
#include "CliChecks.h"
#include "Commands.h"
#include "rill/rt/scene/Scene.h"

namespace trace_cli {

CLI::App* add_noise_command(CLI::App& app, NoiseCommandOptions& o) {
  CLI::App* n = app.add_subcommand(
      "noise",
      "path tracing: error against spp and time, per backend, mode and sampling (a "
      "benchmark)");
  n->add_option("--scene", o.bench.scene, "a path-traced scene (default builtin:cornell-path)")
      ->check(non_empty());
  n->add_option("--backends", o.backends, "comma-separated (default: every available)");
  n->add_option("--variants", o.variants, "comma-separated of nee+mis,nee,bsdf (default: all)");
  n->add_option("--modes", o.modes, "comma-separated of strict,fast,double (default: strict,fast)");
  add_parsed_option(n, "--size", o.size, checked_size, "image size WxH (default 32x32)");
  n->add_option("--max-spp", o.bench.max_spp, "spp runs over 1, 2, 4, ... up to this (default 256)")
      ->check(number_in(1, 1 << 20, true));
  n->add_option("--repeats", o.bench.repeats, "timed renders per point (median; default 3)")
      ->check(number_in(1, 100, true));
  n->add_option("--ref-spp", o.bench.ref_spp, "the reference's spp (default 8192)")
      ->check(number_in(1, 1 << 20, true));
  n->add_option("--ref-backend", o.bench.ref_backend, "the reference's backend (default simd)");
  n->add_option("--reference", o.bench.reference,
                "keep the reference's sums in this file (reused, or resumed to --ref-spp)")
      ->check(file_name());
  n->add_option("--seed", o.bench.seed, "the measured renders' seed (default 1)");
  n->add_option("--ref-seed", o.bench.ref_seed, "the reference's seed (default 1000003)");
  n->add_option("--targets", o.targets,
                "comma-separated relative RMSE targets (default 0.05,0.01)");
  n->add_option("--fit-from", o.bench.fit_from,
                "fit the line for the targets over spp >= this (default 16)")
      ->check(number_in(1, 1 << 20, true));
  n->add_option("--out-dir", o.bench.out_dir, "where noise.{md,csv,svg} go");
  return n;
}

int noise(const NoiseCommandOptions& o) {
  rt::NoiseBenchOptions bench = o.bench;
  if (bench.seed == bench.ref_seed)
    throw rt::SceneError("--seed and --ref-seed are both " + std::to_string(bench.seed) +
                         ": the errors would not be independent");
  bench.backends = split_list(o.backends);
  bench.variants = split_list(o.variants);
  for (const std::string& m : split_list(o.modes)) bench.modes.push_back(rill::parse_accuracy(m));
  if (!o.targets.empty()) {
    bench.targets.clear();
    for (const std::string& t : split_list(o.targets)) {
      size_t used = 0;
      double v = 0;
      try {
        v = std::stod(t, &used);
      } catch (const std::exception&) {
      }
      if (used != t.size() || !(v > 0 && v < 1))
        throw rt::SceneError("--targets: '" + t + "' is not a relative RMSE in (0, 1)");
      bench.targets.push_back(v);
    }
  }
  if (!o.size.empty()) parse_size(o.size, bench.width, bench.height);
  return rt::noise_bench(bench);
}

}  // namespace trace_cli
