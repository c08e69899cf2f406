// The round trip of a cache line between two cores: one thread on each of
// the first two CPUs this process may run on, passing a flag back and forth.
// Prints the median over batches, in nanoseconds, one number on one line.
// With --stream, also what 2 MiB cost handed between the two cores: one
// core writes it over the copy the other just read, the other reads what
// the first just wrote, each timed and set beside the same on one core;
// on x86-64 a second time with non-temporal stores (movnti), which
// invalidate the other core's copies without first fetching the lines.
//
// Why: on a virtual machine the host places the two vCPUs, and where it puts
// them decides what a line one thread writes over the other's copy costs;
// a priced two-thread run does that every update (docs/pricing.md, "Where
// the host puts the two cores"). benchmarks/pricing_end_to_end.sh runs this
// beside every pair of runs to say which placement each saw.
//
// Exit status 0; 2 when fewer than two CPUs are available or a thread
// cannot be pinned to its CPU (the figures would not be between two cores).
#include <pthread.h>
#include <sched.h>

#if defined(__x86_64__)
#include <emmintrin.h>
#endif

#include <CLI/CLI.hpp>
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <thread>
#include <vector>

namespace {

constexpr int kTripsPerBatch = 20000;
constexpr int kBatches = 9;
constexpr std::size_t kStreamWords = (std::size_t{2} << 20) / sizeof(std::uint64_t);  // 2 MiB
constexpr int kStreamRounds = 100;

double Seconds(std::chrono::steady_clock::time_point since) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
}

bool PinTo(int cpu) {
  cpu_set_t set;
  CPU_ZERO(&set);
  CPU_SET(cpu, &set);
  return pthread_setaffinity_np(pthread_self(), sizeof set, &set) == 0;
}

// False once a measuring thread could not be pinned to cpus[1]. The caller
// pins itself to cpus[0] before measuring.
std::atomic<bool> pinned_other{true};

// Median round trip of the flag between cpus[0] and cpus[1], ns.
double RoundTripNs(const std::vector<int>& cpus) {
  // The flag alone on its line: 1 = the other thread's turn, 0 = ours.
  alignas(64) std::atomic<int> flag{0};
  std::thread other([&] {
    if (!PinTo(cpus[1])) pinned_other = false;
    for (long i = 0; i < static_cast<long>(kBatches) * kTripsPerBatch; ++i) {
      while (flag.load(std::memory_order_acquire) != 1) {
      }
      flag.store(0, std::memory_order_release);
    }
  });
  std::vector<double> ns;
  for (int b = 0; b < kBatches; ++b) {
    const auto start = std::chrono::steady_clock::now();
    for (int i = 0; i < kTripsPerBatch; ++i) {
      flag.store(1, std::memory_order_release);
      while (flag.load(std::memory_order_acquire) != 0) {
      }
    }
    ns.push_back(Seconds(start) * 1e9 / kTripsPerBatch);
  }
  other.join();
  std::nth_element(ns.begin(), ns.begin() + kBatches / 2, ns.end());
  return ns[kBatches / 2];
}

// Mean time per round of writing 2 MiB and of reading it, in us: with
// `cross`, cpus[0] writes over what cpus[1] read in the round before and
// cpus[1] reads what cpus[0] just wrote; without, cpus[0] does both. With
// `streaming`, the writes are non-temporal on x86-64 (plain elsewhere).
struct StreamCost {
  double write_us = 0, read_us = 0;
};
StreamCost Stream(const std::vector<int>& cpus, bool cross, bool streaming) {
  std::vector<std::uint64_t> data(kStreamWords, 0);
  std::atomic<std::uint64_t> sink{0};
  double write_s = 0, read_s = 0;
  auto write = [&](int round) {
    const auto start = std::chrono::steady_clock::now();
#if defined(__x86_64__)
    if (streaming) {
      auto* out = reinterpret_cast<long long*>(data.data());
      for (std::size_t i = 0; i < data.size(); ++i)
        _mm_stream_si64(out + i, static_cast<long long>(i + static_cast<std::uint64_t>(round)));
      _mm_sfence();  // the stores reach memory before the reader is told
      write_s += Seconds(start);
      return;
    }
#endif
    for (std::size_t i = 0; i < data.size(); ++i) data[i] = i + static_cast<std::uint64_t>(round);
    write_s += Seconds(start);
  };
  auto read = [&] {
    const auto start = std::chrono::steady_clock::now();
    std::uint64_t sum = 0;
    for (const std::uint64_t v : data) sum += v;
    read_s += Seconds(start);
    sink += sum;
  };
  if (!cross) {
    for (int r = 0; r < kStreamRounds; ++r) {
      write(r);
      read();
    }
  } else {
    alignas(64) std::atomic<int> turn{0};  // 0: the writer's, 1: the reader's
    std::thread reader([&] {
      if (!PinTo(cpus[1])) pinned_other = false;
      for (int r = 0; r < kStreamRounds; ++r) {
        while (turn.load(std::memory_order_acquire) != 1) {
        }
        read();
        turn.store(0, std::memory_order_release);
      }
    });
    for (int r = 0; r < kStreamRounds; ++r) {
      while (turn.load(std::memory_order_acquire) != 0) {
      }
      write(r);
      turn.store(1, std::memory_order_release);
    }
    reader.join();
  }
  return {write_s / kStreamRounds * 1e6, read_s / kStreamRounds * 1e6};
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Round trip of a cache line between the first two CPUs this process may run on (ns)"};
  bool stream = false;
  app.add_flag("--stream", stream, "Also time 2 MiB written and read across the two cores and on one core (us)");
  CLI11_PARSE(app, argc, argv);
  cpu_set_t allowed;
  CPU_ZERO(&allowed);
  if (sched_getaffinity(0, sizeof allowed, &allowed) != 0) {
    std::fprintf(stderr, "core_to_core_latency: cannot read this process's CPUs\n");
    return 2;
  }
  std::vector<int> cpus;
  for (int c = 0; c < CPU_SETSIZE && cpus.size() < 2; ++c)
    if (CPU_ISSET(c, &allowed)) cpus.push_back(c);
  if (cpus.size() < 2) {
    std::fprintf(stderr, "core_to_core_latency: needs two CPUs, this process may run on %zu\n", cpus.size());
    return 2;
  }
  if (!PinTo(cpus[0])) {
    std::fprintf(stderr, "core_to_core_latency: cannot pin a thread to CPU %d\n", cpus[0]);
    return 2;
  }
  // Everything is measured before anything is printed, so that a thread
  // that could not be pinned leaves no figures behind.
  const double trip_ns = RoundTripNs(cpus);
  StreamCost across, one, nt_across, nt_one;
  if (stream) {
    across = Stream(cpus, true, false);
    one = Stream(cpus, false, false);
#if defined(__x86_64__)
    nt_across = Stream(cpus, true, true);
    nt_one = Stream(cpus, false, true);
#endif
  }
  if (!pinned_other) {
    std::fprintf(stderr, "core_to_core_latency: cannot pin a thread to CPU %d\n", cpus[1]);
    return 2;
  }
  if (!stream) {
    std::printf("%.0f\n", trip_ns);
    return 0;
  }
  std::printf("round trip                              %.0f ns\n", trip_ns);
  std::printf("2 MiB written over the other core's copy %.0f us (one core: %.0f us)\n", across.write_us,
              one.write_us);
  std::printf("2 MiB read after the other core wrote it %.0f us (one core: %.0f us)\n", across.read_us, one.read_us);
#if defined(__x86_64__)
  std::printf("the same with non-temporal stores:      written %.0f us (one core: %.0f us), read %.0f us (one core: %.0f us)\n",
              nt_across.write_us, nt_one.write_us, nt_across.read_us, nt_one.read_us);
#endif
  return 0;
}
