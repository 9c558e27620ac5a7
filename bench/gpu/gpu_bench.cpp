// gpu_bench [--sizes 1000,10000,...] [--csv out.csv]
//
// The particle system at each N: seconds per tick on the CPU reference (double) and on OpenCL
// (float), where a tick is what a zone pays (step, then sync), the float-versus-double position
// error after the same steps from the same start, and the crossover N from which OpenCL wins
// (gpu/offload.h's crossover, the rule --gpu auto uses). Zone flocks: planar_flock_bench.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "gpu/cl_runtime.h"
#include "gpu/default_runtime.h"
#include "gpu/offload.h"
#include "gpu/workload_scene.h"

namespace {

using zonesim::gpu::Backend;
using zonesim::gpu::Vec3d;
using zonesim::gpu::Workload;

struct Options {
  std::vector<std::size_t> sizes{1'000, 10'000, 100'000, 1'000'000};
  std::string csv;
};

std::vector<std::string> split(const std::string& text) {
  std::vector<std::string> out;
  std::stringstream in(text);
  for (std::string item; std::getline(in, item, ',');) out.push_back(item);
  return out;
}

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i + 1 < argc; i += 2) {
    std::string flag = argv[i], value = argv[i + 1];
    if (flag == "--sizes") {
      o.sizes.clear();
      for (const std::string& s : split(value)) o.sizes.push_back(std::stoull(s));
    } else if (flag == "--csv") {
      o.csv = value;
    } else {
      throw std::invalid_argument("unknown flag " + flag);
    }
  }
  return o;
}

// Fewer ticks at large N keep the 1e6 runs to seconds on two shared cores.
int stepsFor(std::size_t n) {
  return n >= 1'000'000 ? 2 : n >= 100'000 ? 4 : 10;
}
int repeatsFor(std::size_t n) {
  return n >= 1'000'000 ? 1 : 3;
}

struct Errors {
  double max = 0;
  double median = 0;
};

Errors compare(const std::vector<Vec3d>& a, const std::vector<Vec3d>& b) {
  std::vector<double> e(a.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    e[i] =
        std::max({std::abs(a[i].x - b[i].x), std::abs(a[i].y - b[i].y), std::abs(a[i].z - b[i].z)});
  }
  if (e.empty()) return {};
  std::sort(e.begin(), e.end());
  return {e.back(), e[e.size() / 2]};
}

}  // namespace

int main(int argc, char** argv) {
  try {
    Options o = parse(argc, argv);
    auto runtime = zonesim::gpu::defaultRuntime();
    std::printf("device: %s\n", runtime->description().c_str());
    std::printf("%-9s %9s %12s %12s %8s %6s %11s %11s\n", "workload", "N", "cpu ms/tick",
                "ocl ms/tick", "cpu/ocl", "steps", "max err m", "median err");
    std::ofstream csv;
    if (!o.csv.empty()) {
      csv.open(o.csv);
      csv << "workload,n,cpu_ms,opencl_ms,steps,max_error_m,median_error_m\n";
    }
    {
      const Workload w = Workload::Particles;
      std::vector<zonesim::gpu::ProbeSample> samples;
      for (std::size_t n : o.sizes) {
        zonesim::gpu::ParticleWorkload cpu(Backend::Cpu, n);
        zonesim::gpu::ParticleWorkload ocl(Backend::OpenCl, n, runtime);
        const int steps = stepsFor(n), repeats = repeatsFor(n);
        double cpu_s = zonesim::gpu::secondsPerTick(cpu, steps, repeats);
        double ocl_s = zonesim::gpu::secondsPerTick(ocl, steps, repeats);
        std::vector<Vec3d> xc, xo;
        cpu.readPositions(xc);
        ocl.readPositions(xo);
        Errors e = compare(xo, xc);
        const int total = 1 + steps * repeats;
        samples.push_back({n, cpu_s, ocl_s});
        std::printf("%-9s %9zu %12.4f %12.4f %8.2f %6d %11.2e %11.2e\n",
                    zonesim::gpu::workloadName(w), n, cpu_s * 1e3, ocl_s * 1e3, cpu_s / ocl_s,
                    total, e.max, e.median);
        std::fflush(stdout);
        if (csv.is_open()) {
          csv << zonesim::gpu::workloadName(w) << ',' << n << ',' << cpu_s * 1e3 << ','
              << ocl_s * 1e3 << ',' << total << ',' << e.max << ',' << e.median << '\n';
        }
      }
      std::size_t c = zonesim::gpu::crossover(samples);
      if (c == zonesim::gpu::kNeverOffload) {
        std::printf("%s crossover: none (OpenCL slower at the largest N)\n",
                    zonesim::gpu::workloadName(w));
      } else {
        std::printf("%s crossover: OpenCL wins from N = %zu\n", zonesim::gpu::workloadName(w), c);
      }
    }
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "gpu_bench: %s\n", e.what());
    return 1;
  }
}
