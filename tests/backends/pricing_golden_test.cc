// Pins every priced number of fixed, deterministic records, so that the
// pricing path can be made faster without changing what it says. The
// golden fingerprints below were produced by the pricing code as it stood
// before its speed work (commit 2406717), by running this test with
// RC_PRINT_PRICING_GOLDEN=1; they are not hand-derived and carry no
// meaning beyond "unchanged". A deliberate change to a cost model updates
// them the same way, and says so in its commit.
//
// The cases cover every path of the replay and the caches: the fully
// associative LRU L1 with a cold L2 (a grid larger than the L1), a
// set-associative LRU L2 (the L2 shrunk below the footprint), the cold L1
// (a grid that fits), two regions (rm's distance field), nodes wider than a
// sector with every SACT exit, and a partial last warp. Two cases sample
// the record as the CLI does (one SM of eight, every second block of it),
// for the sampled SM's replay and the estimate of the rest; their
// fingerprints were printed later, at the commit that added them, from
// code whose demo and beam-model timelines equal 0ab87ad's.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "backends/backend.h"
#include "common/angles.h"
#include "common/random_stream.h"
#include "maps/cmu_map_loader.h"
#include "robocore/ray_batch_recorded.h"
#include "robocore/shipped_programs.h"
#include "support/simd_levels.h"
#include "support/test_data.h"
#include "test_scenes.h"

namespace rc {
namespace {

// Every field of a BatchCost a model computes, doubles as hex floats (bit
// exact).
std::string Fingerprint(const BatchCost& c) {
  std::ostringstream s;
  char buffer[64];
  auto hex = [&](double v) {
    std::snprintf(buffer, sizeof buffer, "%a", v);
    return std::string(buffer);
  };
  s << c.backend << " q=" << c.queries << " n=" << c.nodes << " cyc=" << c.cycles << " launch=" << c.launch_cycles
    << " e=" << hex(c.energy_joules) << " s=" << hex(c.seconds) << " eff=" << hex(c.simt_efficiency)
    << " mem=" << c.memory.sector_requests << '/' << c.memory.l1_hits << '/' << c.memory.l2_accesses << '/'
    << c.memory.l2_hits << '/' << c.memory.dram_accesses << " ops=";
  for (std::uint64_t n : c.micro_ops) s << n << ',';
  s << " pred=" << c.predicated_off_micro_ops << " hops=" << c.interconnect_hops << " ctrl=" << c.ctrl_exits
    << " push=" << c.nodes_counted << " wi=" << c.warp_instructions << " ti=" << c.thread_instructions
    << " bound=" << c.bound << " l1=" << c.l1_model << " l2=" << c.l2_model;
  return s.str();
}

std::vector<std::string> PriceEveryBackend(const KernelRecord& record, const BackendParameters& params) {
  std::vector<std::unique_ptr<Backend>> owned;
  std::vector<const Backend*> backends;
  for (const std::string& name : Backend::ModelledNames()) {
    owned.push_back(Backend::Create(name, params));
    backends.push_back(owned.back().get());
  }
  std::vector<std::string> out;
  for (const BatchCost& c : PriceAll(backends, record)) out.push_back(Fingerprint(c));
  return out;
}

KernelRecord RayRecord(int size_x, int size_y, RayCastMethod method, int particles, int beams, std::uint64_t seed,
                       const RecordOptions& options = {}) {
  const OccupancyGrid grid = test::RoomGrid(size_x, size_y, 0.1, 0.03, seed);
  const RayCastScene scene(grid, method);
  const RayBatch batch = test::FanBatch(grid, particles, beams, 10.0, seed + 1);
  std::vector<RayHit> hits;
  KernelRecord record;
  CastRayBatchRecorded(scene, batch, hits, record, options);
  return record;
}

// The CLI's address sample (one SM of eight, every second block of it):
// the sampled SM's replay and the estimate of the others.
KernelRecord SampledRayRecord(int size_x, int size_y, RayCastMethod method, int particles, int beams,
                              std::uint64_t seed) {
  RecordOptions options;
  options.sample.sampled_sms = 1;
  options.sample.block_stride = 2;
  KernelRecord record = RayRecord(size_x, size_y, method, particles, beams, seed, options);
  EXPECT_TRUE(record.sampled());
  EXPECT_LT(record.address_offsets.back(), record.total_nodes() / 4) << "most addresses should be left out";
  return record;
}

// The shipped SACT program on 64-byte nodes (two sectors each), queries of
// 1..9 nodes, exits drawn from every axis and "overlap"; 1000 queries end
// in a partial warp.
KernelRecord SactRecord() {
  constexpr std::uint64_t kBase = std::uint64_t{1} << 32;
  constexpr std::uint64_t kNodes = 4096;
  MemoryRegion region = test::ByteRegion(kBase, kNodes);
  region.element_bytes = 64;
  KernelRecordBuilder b(ShippedStepProgram(StepProgramKind::kSactTest), StepProgramKind::kSactTest, region);
  RandomStream s(61, StreamPurpose::kTest, 0, 0);
  for (int q = 0; q < 1000; ++q) {
    const int n = 1 + static_cast<int>(s.Uniform() * 9);
    std::vector<std::uint64_t> a(n);
    std::vector<std::uint8_t> e(n);
    for (int k = 0; k < n; ++k) {
      a[k] = kBase + 64 * static_cast<std::uint64_t>(s.Uniform() * kNodes);
      const int axis = static_cast<int>(s.Uniform() * 16);
      e[k] = axis == 15 ? kNoExit : static_cast<std::uint8_t>(axis);
    }
    b.AddQuery(a, e);
  }
  return b.Build();
}

// Prints fingerprints as C++ string literals, wrapped at spaces.
void PrintAsLiterals(const std::string& name, const std::vector<std::string>& fingerprints) {
  std::printf("    // %s\n", name.c_str());
  for (const std::string& f : fingerprints) {
    std::size_t at = 0;
    while (at < f.size()) {
      std::size_t end = std::min(f.size(), at + 88);
      if (end < f.size()) {
        const std::size_t space = f.rfind(' ', end);
        if (space != std::string::npos && space > at) end = space;
      }
      std::printf("    \"%s\"%s\n", f.substr(at, end - at).c_str(), end == f.size() ? "," : "");
      at = end;
    }
  }
}

struct GoldenCase {
  std::string name;
  std::vector<std::string> expected;  // one fingerprint per modelled backend
};

// Records (make_record()) and prices on every SIMD path this CPU has: the
// record's casts and the models' per-query terms and ranks each run in
// scalar code, AVX2 and AVX-512 where the CPU runs them, and every path
// must give the golden numbers.
template <class MakeRecord>
void Check(const GoldenCase& golden, MakeRecord make_record, const BackendParameters& params = {}) {
  for (SimdLevel level : test::SimdLevelsThisCpuRuns()) {
    const test::ScopedSimdLimit limit(level);
    const std::vector<std::string> actual = PriceEveryBackend(make_record(), params);
    if (std::getenv("RC_PRINT_PRICING_GOLDEN") && level == CpuSimdLevel()) PrintAsLiterals(golden.name, actual);
    ASSERT_EQ(actual.size(), golden.expected.size()) << golden.name << ", " << ToString(level);
    for (std::size_t i = 0; i < actual.size(); ++i)
      EXPECT_EQ(actual[i], golden.expected[i]) << golden.name << ", " << ToString(level);
  }
}

// The expected fingerprints below are pasted as RC_PRINT_PRICING_GOLDEN=1
// prints them; clang-format would re-wrap them, so it leaves them alone.
// clang-format off
TEST(PricingGolden, DdaOnAGridLargerThanTheL1) {
  Check({"dda 400x300", {
    "simt q=5400 n=150802 cyc=46008 launch=5000 e=0x1.40b22470babb3p-13"
    " s=0x1.1abdff907a445p-15 eff=0x1.46a8aff5d3811p-2 mem=77022/66693/10329/6652/3677"
    " ops=317804,156202,156202,10800,770210,323204,5400,0,0,0,0,0,0,161602,457806,0,0,150802,"
    "5400,301604,150802, pred=0 hops=0 ctrl=0 push=150802 wi=631683 ti=6448278 bound=latency"
    " (resident warps) l1=lru (fully associative) l2=cold (footprint fits: compulsory misses"
    " only)",
    "ttaplus q=5400 n=150802 cyc=78550 launch=5036 e=0x1.cb4ef8d4021dap-14"
    " s=0x1.e2baa3449f9abp-15 eff=nan mem=150802/140436/10366/6689/3677"
    " ops=317804,156202,156202,10800,770210,323204,5400,0,0,0,0,0,0,161602,457806,0,0,150802,"
    "5400,0,150802, pred=0 hops=1734422 ctrl=0 push=150802 wi=0 ti=0 bound=latency (warp"
    " buffer) l1=lru (fully associative) l2=cold (footprint fits: compulsory misses only)",
    "ttaplus-p q=5400 n=150802 cyc=80789 launch=5038 e=0x1.f0c6288b190a7p-14"
    " s=0x1.f07d23e747f1p-15 eff=nan mem=150802/140436/10366/6689/3677"
    " ops=307084,150842,150842,10800,748770,312484,5400,0,0,0,0,0,0,156242,441726,0,0,150802,"
    "5400,296244,150802, pred=80400 hops=2036026 ctrl=0 push=150802 wi=0 ti=0 bound=latency"
    " (warp buffer) l1=lru (fully associative) l2=cold (footprint fits: compulsory misses"
    " only)",
    "ttaplus-cr q=5400 n=150802 cyc=80659 launch=5038 e=0x1.e874b6ada5094p-14"
    " s=0x1.efb09e34f622ap-15 eff=nan mem=150802/140436/10366/6689/3677"
    " ops=307084,150842,150842,10800,748770,312484,5400,0,0,0,0,0,0,156242,441726,0,0,150802,"
    "5400,296244,150802, pred=0 hops=1977066 ctrl=0 push=150802 wi=0 ti=0 bound=latency (warp"
    " buffer) l1=lru (fully associative) l2=cold (footprint fits: compulsory misses only)",
    "robocore q=5400 n=150802 cyc=80660 launch=5039 e=0x1.e874b6ada5094p-14"
    " s=0x1.efb230f55939ep-15 eff=nan mem=150802/140436/10366/6689/3677"
    " ops=307084,150842,150842,10800,748770,312484,5400,0,0,0,0,0,0,156242,441726,0,0,150802,"
    "5400,296244,150802, pred=0 hops=1977066 ctrl=0 push=150802 wi=0 ti=0 bound=latency (warp"
    " buffer) l1=lru (fully associative) l2=cold (footprint fits: compulsory misses only)",
  }}, [] { return RayRecord(400, 300, RayCastMethod::kDda, 60, 90, 71); });
}

// An L2 of 32 KiB, below the march cases' footprint (set associative), and
// an L1 of 8 KiB.
BackendParameters SmallCaches() {
  BackendParameters small;
  small.gpu.l2_bytes = 32768;
  small.gpu.l1_bytes = 8192;
  return small;
}

TEST(PricingGolden, MarchWithASetAssociativeL2) {
  Check({"march 400x300, L2 32 KiB", {
    "simt q=2560 n=69849 cyc=103028 launch=5000 e=0x1.ffc78cbbdd66cp-14"
    " s=0x1.3c944d63b44cep-14 eff=0x1.61c875aac8a9cp-2 mem=40447/10214/30233/22017/8216"
    " ops=144818,5120,2560,5120,284516,152498,0,0,0,0,0,0,0,5120,212107,0,0,69849,2560,139698"
    ",69849, pred=0 hops=0 ctrl=0 push=69849 wi=221392 ti=2447648 bound=latency (resident"
    " warps) l1=lru (fully associative) l2=lru (set associative)",
    "ttaplus q=2560 n=69849 cyc=57805 launch=5031 e=0x1.6d4a3f3cd9d49p-14"
    " s=0x1.633d9b26c89fdp-15 eff=nan mem=69849/59925/9924/2476/7448"
    " ops=144818,5120,2560,5120,284516,152498,0,0,0,0,0,0,0,5120,212107,0,0,69849,2560,0,6984"
    "9, pred=0 hops=452374 ctrl=0 push=69849 wi=0 ti=0 bound=latency (warp buffer) l1=lru"
    " (fully associative) l2=lru (set associative)",
    "ttaplus-p q=2560 n=69849 cyc=59307 launch=5033 e=0x1.7eba96457d488p-14"
    " s=0x1.6c789fec2b07bp-15 eff=nan mem=69849/59925/9924/2476/7448"
    " ops=139800,5120,2560,5120,276989,147480,0,0,0,0,0,0,0,5120,204580,0,0,69849,2560,137189"
    ",69849, pred=27599 hops=592072 ctrl=0 push=69849 wi=0 ti=0 bound=latency (warp buffer)"
    " l1=lru (fully associative) l2=lru (set associative)",
    "ttaplus-cr q=2560 n=69849 cyc=59273 launch=5033 e=0x1.7c4ef67a496a9p-14"
    " s=0x1.6c43225f01f14p-15 eff=nan mem=69849/59925/9924/2476/7448"
    " ops=139800,5120,2560,5120,276989,147480,0,0,0,0,0,0,0,5120,204580,0,0,69849,2560,137189"
    ",69849, pred=0 hops=577018 ctrl=0 push=69849 wi=0 ti=0 bound=latency (warp buffer)"
    " l1=lru (fully associative) l2=lru (set associative)",
    "robocore q=2560 n=69849 cyc=59274 launch=5034 e=0x1.7c4ef67a496a9p-14"
    " s=0x1.6c44b51f65088p-15 eff=nan mem=69849/59925/9924/2476/7448"
    " ops=139800,5120,2560,5120,276989,147480,0,0,0,0,0,0,0,5120,204580,0,0,69849,2560,137189"
    ",69849, pred=0 hops=577018 ctrl=0 push=69849 wi=0 ti=0 bound=latency (warp buffer)"
    " l1=lru (fully associative) l2=lru (set associative)",
  }}, [] { return RayRecord(400, 300, RayCastMethod::kMarch, 40, 64, 72); }, SmallCaches());
}

TEST(PricingGolden, DdaSampledOnOneSmEverySecondBlock) {
  Check({"dda 400x300, sampled", {
    "simt q=18000 n=491940 cyc=79061 launch=5000 e=0x1.c76e6b9f29d97p-12"
    " s=0x1.e5de914a6b02ep-15 eff=0x1.4b3659a16bc5cp-2 mem=258902/227596/31306/27556/3750"
    " ops=1037880,509940,509940,36000,2513700,1055880,18000,0,0,0,0,0,0,527940,1493820,0,0,49"
    "1940,18000,983880,491940, pred=0 hops=0 ctrl=0 push=491940 wi=2036220 ti=21075660"
    " bound=latency (resident warps) l1=lru (fully associative) l2=cold (footprint fits:"
    " compulsory misses only)",
    "ttaplus q=18000 n=491940 cyc=177324 launch=5036 e=0x1.3245f273daf18p-12"
    " s=0x1.106fa9475af7ep-13 eff=nan mem=491940/460761/31179/27429/3750"
    " ops=1037880,509940,509940,36000,2513700,1055880,18000,0,0,0,0,0,0,527940,1493820,0,0,49"
    "1940,18000,0,491940, pred=0 hops=5663340 ctrl=0 push=491940 wi=0 ti=0 bound=latency"
    " (warp buffer) l1=lru (fully associative) l2=cold (footprint fits: compulsory misses"
    " only)",
    "ttaplus-p q=18000 n=491940 cyc=183903 launch=5038 e=0x1.50d117c729927p-12"
    " s=0x1.1a8b42d3fe969p-13 eff=nan mem=491940/460761/31179/27429/3750"
    " ops=1002130,492065,492065,36000,2442200,1020130,18000,0,0,0,0,0,0,510065,1440195,0,0,49"
    "1940,18000,966005,491940, pred=268125 hops=6647220 ctrl=0 push=491940 wi=0 ti=0"
    " bound=latency (warp buffer) l1=lru (fully associative) l2=cold (footprint fits:"
    " compulsory misses only)",
    "ttaplus-cr q=18000 n=491940 cyc=183513 launch=5038 e=0x1.49e1ba56b60cep-12"
    " s=0x1.19f1de8e413bcp-13 eff=nan mem=491940/460761/31179/27429/3750"
    " ops=1002130,492065,492065,36000,2442200,1020130,18000,0,0,0,0,0,0,510065,1440195,0,0,49"
    "1940,18000,966005,491940, pred=0 hops=6450595 ctrl=0 push=491940 wi=0 ti=0 bound=latency"
    " (warp buffer) l1=lru (fully associative) l2=cold (footprint fits: compulsory misses"
    " only)",
    "robocore q=18000 n=491940 cyc=183514 launch=5039 e=0x1.49e1ba56b60cep-12"
    " s=0x1.19f2433e5a019p-13 eff=nan mem=491940/460761/31179/27429/3750"
    " ops=1002130,492065,492065,36000,2442200,1020130,18000,0,0,0,0,0,0,510065,1440195,0,0,49"
    "1940,18000,966005,491940, pred=0 hops=6450595 ctrl=0 push=491940 wi=0 ti=0 bound=latency"
    " (warp buffer) l1=lru (fully associative) l2=cold (footprint fits: compulsory misses"
    " only)",
  }}, [] { return SampledRayRecord(400, 300, RayCastMethod::kDda, 200, 90, 71); });
}

TEST(PricingGolden, MarchSampledWithASetAssociativeL2) {
  Check({"march 400x300, L2 32 KiB, sampled", {
    "simt q=7680 n=202438 cyc=202550 launch=5000 e=0x1.9a2e80db746b5p-12"
    " s=0x1.373159b06f333p-13 eff=0x1.54480f6cfd7f1p-2 mem=123792/14527/109265/81930/27335"
    " ops=420236,15360,7680,15360,825112,443276,0,0,0,0,0,0,0,15360,614994,0,0,202438,7680,40"
    "4876,202438, pred=0 hops=0 ctrl=0 push=202438 wi=669136 ti=7115456 bound=SFU pipe l1=lru"
    " (fully associative) l2=lru (set associative)",
    "ttaplus q=7680 n=202438 cyc=99067 launch=5031 e=0x1.13bf745a0e6a5p-12"
    " s=0x1.30687c051af06p-14 eff=nan mem=202438/174240/28198/5246/22952"
    " ops=420236,15360,7680,15360,825112,443276,0,0,0,0,0,0,0,15360,614994,0,0,202438,7680,0,"
    "202438, pred=0 hops=1314468 ctrl=0 push=202438 wi=0 ti=0 bound=latency (warp buffer)"
    " l1=lru (fully associative) l2=lru (set associative)",
    "ttaplus-p q=7680 n=202438 cyc=101241 launch=5033 e=0x1.2060d59ba9ab4p-12"
    " s=0x1.37169ae9daa7fp-14 eff=nan mem=202438/174240/28198/5246/22952"
    " ops=405184,15360,7680,15360,802534,428224,0,0,0,0,0,0,0,15360,592416,0,0,202438,7680,39"
    "7350,202438, pred=82786 hops=1719344 ctrl=0 push=202438 wi=0 ti=0 bound=latency (warp"
    " buffer) l1=lru (fully associative) l2=lru (set associative)",
    "ttaplus-cr q=7680 n=202438 cyc=101190 launch=5033 e=0x1.1e902d9176aeep-12"
    " s=0x1.36ee7cbffbd72p-14 eff=nan mem=202438/174240/28198/5246/22952"
    " ops=405184,15360,7680,15360,802534,428224,0,0,0,0,0,0,0,15360,592416,0,0,202438,7680,39"
    "7350,202438, pred=0 hops=1674188 ctrl=0 push=202438 wi=0 ti=0 bound=latency (warp"
    " buffer) l1=lru (fully associative) l2=lru (set associative)",
    "robocore q=7680 n=202438 cyc=101191 launch=5034 e=0x1.1e902d9176aeep-12"
    " s=0x1.36ef46202d62cp-14 eff=nan mem=202438/174240/28198/5246/22952"
    " ops=405184,15360,7680,15360,802534,428224,0,0,0,0,0,0,0,15360,592416,0,0,202438,7680,39"
    "7350,202438, pred=0 hops=1674188 ctrl=0 push=202438 wi=0 ti=0 bound=latency (warp"
    " buffer) l1=lru (fully associative) l2=lru (set associative)",
  }}, [] { return SampledRayRecord(400, 300, RayCastMethod::kMarch, 120, 64, 72); }, SmallCaches());
}

TEST(PricingGolden, RmOnAGridThatFitsTheL1) {
  Check({"rm 120x100", {
    "simt q=2250 n=41082 cyc=126904 launch=5000 e=0x1.790724907fb1ep-14"
    " s=0x1.85f1bcf096768p-14 eff=0x1.49b750cbbbfdcp-2 mem=24678/18131/6547/5051/1496"
    " ops=253242,168828,84414,45582,335406,337656,2250,0,0,0,0,0,0,209910,207660,0,0,41082,22"
    "50,82164,41082, pred=0 hops=0 ctrl=0 push=41082 wi=400122 ti=4122708 bound=latency"
    " (resident warps) l1=cold (footprint fits: compulsory misses only) l2=cold (footprint"
    " fits: compulsory misses only)",
    "ttaplus q=2250 n=41082 cyc=45212 launch=5061 e=0x1.04119925eefb7p-14"
    " s=0x1.15d9b15c5dfa3p-15 eff=nan mem=41082/34535/6547/5051/1496"
    " ops=253242,168828,84414,45582,335406,337656,2250,0,0,0,0,0,0,209910,207660,0,0,41082,22"
    "50,0,41082, pred=0 hops=1184046 ctrl=0 push=41082 wi=0 ti=0 bound=latency (warp buffer)"
    " l1=cold (footprint fits: compulsory misses only) l2=cold (footprint fits: compulsory"
    " misses only)",
    "ttaplus-p q=2250 n=41082 cyc=45795 launch=5063 e=0x1.0d9d538779c0fp-14"
    " s=0x1.196ee57e07ec5p-15 eff=nan mem=41082/34535/6547/5051/1496"
    " ops=239748,159832,79916,43333,319663,319664,2250,0,0,0,0,0,0,198665,196415,0,0,41082,22"
    "50,79915,41082, pred=87711 hops=1266210 ctrl=0 push=41082 wi=0 ti=0 bound=latency (warp"
    " buffer) l1=cold (footprint fits: compulsory misses only) l2=cold (footprint fits:"
    " compulsory misses only)",
    "ttaplus-cr q=2250 n=41082 cyc=45460 launch=5063 e=0x1.04a739231a51ep-14"
    " s=0x1.175fdbbc5c7fep-15 eff=nan mem=41082/34535/6547/5051/1496"
    " ops=239748,159832,79916,43333,319663,319664,2250,0,0,0,0,0,0,198665,196415,0,0,41082,22"
    "50,79915,41082, pred=0 hops=1203238 ctrl=0 push=41082 wi=0 ti=0 bound=latency (warp"
    " buffer) l1=cold (footprint fits: compulsory misses only) l2=cold (footprint fits:"
    " compulsory misses only)",
    "robocore q=2250 n=41082 cyc=45461 launch=5064 e=0x1.04a739231a51ep-14"
    " s=0x1.17616e7cbf972p-15 eff=nan mem=41082/34535/6547/5051/1496"
    " ops=239748,159832,79916,43333,319663,319664,2250,0,0,0,0,0,0,198665,196415,0,0,41082,22"
    "50,79915,41082, pred=0 hops=1203238 ctrl=0 push=41082 wi=0 ti=0 bound=latency (warp"
    " buffer) l1=cold (footprint fits: compulsory misses only) l2=cold (footprint fits:"
    " compulsory misses only)",
  }}, [] { return RayRecord(120, 100, RayCastMethod::kRayMarching, 50, 45, 73); });
}

// Enough warps per SM that throughput bounds (issue, OP units) can win.
TEST(PricingGolden, MarchManyRaysOnAGridThatFitsTheL1) {
  Check({"march 250x250, 200 x 180 rays", {
    "simt q=36000 n=945494 cyc=768710 launch=5000 e=0x1.4539a4fd72b98p-11"
    " s=0x1.2741b8acb453dp-11 eff=0x1.89c216e00a293p-2 mem=331041/315833/15208/13254/1954"
    " ops=1962988,72000,36000,72000,3853976,2070988,0,0,0,0,0,0,0,72000,2872482,0,0,945494,36"
    "000,1890988,945494, pred=0 hops=0 ctrl=0 push=945494 wi=2701663 ti=33243808 bound=SFU"
    " pipe l1=cold (footprint fits: compulsory misses only) l2=cold (footprint fits:"
    " compulsory misses only)",
    "ttaplus q=36000 n=945494 cyc=174267 launch=5031 e=0x1.7a51a9da54525p-12"
    " s=0x1.0bbd4e6f88cfep-13 eff=nan mem=945494/930286/15208/13254/1954"
    " ops=1962988,72000,36000,72000,3853976,2070988,0,0,0,0,0,0,0,72000,2872482,0,0,945494,36"
    "000,0,945494, pred=0 hops=6140964 ctrl=0 push=945494 wi=0 ti=0 bound=latency (warp"
    " buffer) l1=cold (footprint fits: compulsory misses only) l2=cold (footprint fits:"
    " compulsory misses only)",
    "ttaplus-p q=36000 n=945494 cyc=184786 launch=5033 e=0x1.b54e600c5f80ap-12"
    " s=0x1.1be68e3970e2cp-13 eff=nan mem=945494/930286/15208/13254/1954"
    " ops=1892328,72000,36000,72000,3747986,2000328,0,0,0,0,0,0,0,72000,2766492,0,0,945494,36"
    "000,1855658,945494, pred=388630 hops=8031952 ctrl=0 push=945494 wi=0 ti=0 bound=latency"
    " (warp buffer) l1=cold (footprint fits: compulsory misses only) l2=cold (footprint fits:"
    " compulsory misses only)",
    "ttaplus-cr q=36000 n=945494 cyc=184353 launch=5033 e=0x1.acc91873cb73dp-12"
    " s=0x1.1b3c405f8a4e1p-13 eff=nan mem=945494/930286/15208/13254/1954"
    " ops=1892328,72000,36000,72000,3747986,2000328,0,0,0,0,0,0,0,72000,2766492,0,0,945494,36"
    "000,1855658,945494, pred=0 hops=7819972 ctrl=0 push=945494 wi=0 ti=0 bound=latency (warp"
    " buffer) l1=cold (footprint fits: compulsory misses only) l2=cold (footprint fits:"
    " compulsory misses only)",
    "robocore q=36000 n=945494 cyc=184354 launch=5034 e=0x1.acc91873cb73dp-12"
    " s=0x1.1b3ca50fa313ep-13 eff=nan mem=945494/930286/15208/13254/1954"
    " ops=1892328,72000,36000,72000,3747986,2000328,0,0,0,0,0,0,0,72000,2766492,0,0,945494,36"
    "000,1855658,945494, pred=0 hops=7819972 ctrl=0 push=945494 wi=0 ti=0 bound=latency (warp"
    " buffer) l1=cold (footprint fits: compulsory misses only) l2=cold (footprint fits:"
    " compulsory misses only)",
  }}, [] { return RayRecord(250, 250, RayCastMethod::kMarch, 200, 180, 74); });
}

// The pricing benchmark's workload (benchmarks/backend_pricing_benchmark.cc):
// the first DeliBot update on the Wean map, every ray caster.
TEST(PricingGolden, WeanDeliBotUpdate) {
  RC_REQUIRE_SHARED_DATA("wean/wean.dat");
  const OccupancyGrid grid = LoadCmuMap(test::SharedDataPath("wean/wean.dat"));
  RandomStream s(7, StreamPurpose::kTest, 0, 0);
  RayBatch batch;
  batch.max_range_m = 10.0;
  for (int placed = 0; placed < 500;) {
    const double x = s.Uniform(0, grid.extent_x_m()), y = s.Uniform(0, grid.extent_y_m());
    if (!grid.IsFreePoint(x, y)) continue;
    const double heading = s.Uniform(-kPi, kPi);
    for (int k = 0; k < 180; ++k) batch.queries.push_back({x, y, heading - kPi / 2 + kPi * k / 179});
    ++placed;
  }
  const std::vector<std::vector<std::string>> expected = {
    {
    "simt q=90000 n=2123645 cyc=1008490 launch=5000 e=0x1.5c6a2844ea4e6p-10"
    " s=0x1.835acf857c11fp-11 eff=0x1.547ad473e316ap-1 mem=546853/506378/40475/37642/2833"
    " ops=4427290,180000,90000,180000,8674580,4697290,0,0,0,0,0,0,0,180000,6460935,0,0,212364"
    "5,90000,4247290,2123645, pred=0 hops=0 ctrl=0 push=2123645 wi=3544487 ti=75426640"
    " bound=SFU pipe l1=lru (fully associative) l2=cold (footprint fits: compulsory misses"
    " only)",
    "ttaplus q=90000 n=2123645 cyc=303938 launch=5031 e=0x1.a646b0b4a59e4p-11"
    " s=0x1.d2f67843961d9p-13 eff=nan mem=2123645/2083102/40543/37710/2833"
    " ops=4427290,180000,90000,180000,8674580,4697290,0,0,0,0,0,0,0,180000,6460935,0,0,212364"
    "5,90000,0,2123645, pred=0 hops=13911870 ctrl=0 push=2123645 wi=0 ti=0 bound=op unit CMP"
    " l1=lru (fully associative) l2=cold (footprint fits: compulsory misses only)",
    "ttaplus-p q=90000 n=2123645 cyc=303940 launch=5033 e=0x1.e870d47104728p-11"
    " s=0x1.d2f741a3c7a93p-13 eff=nan mem=2123645/2083102/40543/37710/2833"
    " ops=4252348,180000,90000,180000,8412167,4522348,0,0,0,0,0,0,0,180000,6198522,0,0,212364"
    "5,90000,4159819,2123645, pred=962181 hops=18159160 ctrl=0 push=2123645 wi=0 ti=0"
    " bound=op unit CMP l1=lru (fully associative) l2=cold (footprint fits: compulsory misses"
    " only)",
    "ttaplus-cr q=90000 n=2123645 cyc=298308 launch=5033 e=0x1.dde497e2e2cap-11"
    " s=0x1.ca501f82c7cabp-13 eff=nan mem=2123645/2083102/40543/37710/2833"
    " ops=4252348,180000,90000,180000,8412167,4522348,0,0,0,0,0,0,0,180000,6198522,0,0,212364"
    "5,90000,4159819,2123645, pred=0 hops=17634334 ctrl=0 push=2123645 wi=0 ti=0 bound=L1"
    " requests l1=lru (fully associative) l2=cold (footprint fits: compulsory misses only)",
    "robocore q=90000 n=2123645 cyc=298309 launch=5034 e=0x1.dde497e2e2cap-11"
    " s=0x1.ca508432e0908p-13 eff=nan mem=2123645/2083102/40543/37710/2833"
    " ops=4252348,180000,90000,180000,8412167,4522348,0,0,0,0,0,0,0,180000,6198522,0,0,212364"
    "5,90000,4159819,2123645, pred=0 hops=17634334 ctrl=0 push=2123645 wi=0 ti=0 bound=L1"
    " requests l1=lru (fully associative) l2=cold (footprint fits: compulsory misses only)",
    },
    {
    "simt q=90000 n=2596476 cyc=182340 launch=5000 e=0x1.fefb8d1cfd434p-10"
    " s=0x1.182483acbedap-13 eff=0x1.527e47dfd7ca9p-1 mem=837880/797565/40315/37505/2810"
    " ops=5462952,2686476,2686476,180000,13252380,5552952,90000,0,0,0,0,0,0,2776476,7879428,0"
    ",0,2596476,90000,5192952,2596476, pred=0 hops=0 ctrl=0 push=2596476 wi=5233194"
    " ti=110712564 bound=issue l1=lru (fully associative) l2=cold (footprint fits: compulsory"
    " misses only)",
    "ttaplus q=90000 n=2596476 cyc=462282 launch=5036 e=0x1.63950c9905c91p-10"
    " s=0x1.631e88cf2394ap-12 eff=nan mem=2596476/2556617/39859/37049/2810"
    " ops=5462952,2686476,2686476,180000,13252380,5552952,90000,0,0,0,0,0,0,2776476,7879428,0"
    ",0,2596476,90000,0,2596476, pred=0 hops=29821236 ctrl=0 push=2596476 wi=0 ti=0 bound=op"
    " unit CMP l1=lru (fully associative) l2=cold (footprint fits: compulsory misses only)",
    "ttaplus-p q=90000 n=2596476 cyc=462284 launch=5038 e=0x1.8beee830fac2fp-10"
    " s=0x1.631eed7f3c5a7p-12 eff=nan mem=2596476/2556617/39859/37049/2810"
    " ops=5287880,2598940,2598940,180000,12902236,5377880,90000,0,0,0,0,0,0,2688940,7616820,0"
    ",0,2596476,90000,5105416,2596476, pred=1313040 hops=35014188 ctrl=0 push=2596476 wi=0"
    " ti=0 bound=op unit CMP l1=lru (fully associative) l2=cold (footprint fits: compulsory"
    " misses only)",
    "ttaplus-cr q=90000 n=2596476 cyc=451309 launch=5038 e=0x1.83715d1733f8fp-10"
    " s=0x1.5ab0a0c43823ep-12 eff=nan mem=2596476/2556617/39859/37049/2810"
    " ops=5287880,2598940,2598940,180000,12902236,5377880,90000,0,0,0,0,0,0,2688940,7616820,0"
    ",0,2596476,90000,5105416,2596476, pred=0 hops=34051292 ctrl=0 push=2596476 wi=0 ti=0"
    " bound=op unit CMP l1=lru (fully associative) l2=cold (footprint fits: compulsory misses"
    " only)",
    "robocore q=90000 n=2596476 cyc=451310 launch=5039 e=0x1.83715d1733f8fp-10"
    " s=0x1.5ab0d31c4486cp-12 eff=nan mem=2596476/2556617/39859/37049/2810"
    " ops=5287880,2598940,2598940,180000,12902236,5377880,90000,0,0,0,0,0,0,2688940,7616820,0"
    ",0,2596476,90000,5105416,2596476, pred=0 hops=34051292 ctrl=0 push=2596476 wi=0 ti=0"
    " bound=op unit CMP l1=lru (fully associative) l2=cold (footprint fits: compulsory misses"
    " only)",
    },
    {
    "simt q=90000 n=1013904 cyc=723820 launch=5000 e=0x1.f9c766d23a734p-10"
    " s=0x1.1603c6f6b8a81p-11 eff=0x1.1e99c53b69ba7p-1 mem=368800/271634/97166/89318/7848"
    " ops=6353424,4235616,2117808,1193904,8381232,8471232,90000,0,0,0,0,0,0,5249520,5159520,0"
    ",0,1013904,90000,2027808,1013904, pred=0 hops=0 ctrl=0 push=1013904 wi=5903516"
    " ti=105746976 bound=SFU pipe l1=lru (fully associative) l2=cold (footprint fits:"
    " compulsory misses only)",
    "ttaplus q=90000 n=1013904 cyc=353997 launch=5061 e=0x1.54887f949ea2cp-10"
    " s=0x1.0fefa35fdb74p-12 eff=nan mem=1013904/915340/98564/90716/7848"
    " ops=6353424,4235616,2117808,1193904,8381232,8471232,90000,0,0,0,0,0,0,5249520,5159520,0"
    ",0,1013904,90000,0,1013904, pred=0 hops=29739312 ctrl=0 push=1013904 wi=0 ti=0"
    " bound=latency (warp buffer) l1=lru (fully associative) l2=cold (footprint fits:"
    " compulsory misses only)",
    "ttaplus-p q=90000 n=1013904 cyc=357267 launch=5063 e=0x1.62856f5a11fccp-10"
    " s=0x1.1272b40e12d3p-12 eff=nan mem=1013904/915340/98564/90716/7848"
    " ops=5828208,3885472,1942736,1106368,7768480,7770944,90000,0,0,0,0,0,0,4811840,4721840,0"
    ",0,1013904,90000,1940272,1013904, pred=3413904 hops=31767120 ctrl=0 push=1013904 wi=0"
    " ti=0 bound=latency (warp buffer) l1=lru (fully associative) l2=cold (footprint fits:"
    " compulsory misses only)",
    "ttaplus-cr q=90000 n=1013904 cyc=351652 launch=5063 e=0x1.4cb8b72ca4e16p-10"
    " s=0x1.0e227ad665752p-12 eff=nan mem=1013904/915340/98564/90716/7848"
    " ops=5828208,3885472,1942736,1106368,7768480,7770944,90000,0,0,0,0,0,0,4811840,4721840,0"
    ",0,1013904,90000,1940272,1013904, pred=0 hops=29316112 ctrl=0 push=1013904 wi=0 ti=0"
    " bound=latency (warp buffer) l1=lru (fully associative) l2=cold (footprint fits:"
    " compulsory misses only)",
    "robocore q=90000 n=1013904 cyc=351653 launch=5064 e=0x1.4cb8b72ca4e16p-10"
    " s=0x1.0e22ad2e71d81p-12 eff=nan mem=1013904/915340/98564/90716/7848"
    " ops=5828208,3885472,1942736,1106368,7768480,7770944,90000,0,0,0,0,0,0,4811840,4721840,0"
    ",0,1013904,90000,1940272,1013904, pred=0 hops=29316112 ctrl=0 push=1013904 wi=0 ti=0"
    " bound=latency (warp buffer) l1=lru (fully associative) l2=cold (footprint fits:"
    " compulsory misses only)",
    }};
  const RayCastMethod methods[] = {RayCastMethod::kMarch, RayCastMethod::kDda, RayCastMethod::kRayMarching};
  for (int m = 0; m < 3; ++m) {
    const RayCastScene scene(grid, methods[m]);
    Check({std::string("wean ") + ToString(methods[m]), expected[m]}, [&] {
      std::vector<RayHit> hits;
      KernelRecord record;
      CastRayBatchRecorded(scene, batch, hits, record);
      return record;
    });
  }
}

TEST(PricingGolden, SactWideNodesEveryExit) {
  Check({"sact 64-byte nodes", {
    "simt q=1000 n=5017 cyc=15954 launch=5000 e=0x1.1fb256f03236ep-14 s=0x1.882e667d7b851p-17"
    " eff=0x1.2669466ce7c02p-1 mem=10014/1022/8992/3216/5776"
    " ops=0,0,0,0,0,0,0,0,0,0,5017,30102,45153,0,0,0,0,5017,0,75255,5017, pred=0 hops=0"
    " ctrl=0 push=5017 wi=56416 ti=1038094 bound=latency (resident warps) l1=lru (fully"
    " associative) l2=cold (footprint fits: compulsory misses only)",
    "ttaplus q=1000 n=5017 cyc=15396 launch=5049 e=0x1.e7bb1923a660fp-15"
    " s=0x1.7a76e91d88d18p-17 eff=nan mem=10034/1056/8978/3202/5776"
    " ops=0,50170,0,0,75255,0,0,60204,45153,5017,0,0,0,0,0,0,0,5017,0,0,5017, pred=0"
    " hops=190646 ctrl=0 push=5017 wi=0 ti=0 bound=latency (warp buffer) l1=lru (fully"
    " associative) l2=cold (footprint fits: compulsory misses only)",
    "ttaplus-p q=1000 n=5017 cyc=14729 launch=5064 e=0x1.f3075bf74aad7p-15"
    " s=0x1.6a117c14d2856p-17 eff=nan mem=10034/1056/8978/3202/5776"
    " ops=0,45562,0,0,42717,0,0,50988,17223,5017,0,0,0,0,0,0,0,316,0,42717,5017, pred=111531"
    " hops=265901 ctrl=0 push=316 wi=0 ti=0 bound=latency (warp buffer) l1=lru (fully"
    " associative) l2=cold (footprint fits: compulsory misses only)",
    "ttaplus-cr q=1000 n=5017 cyc=14055 launch=5064 e=0x1.d7bbf0fdce488p-15"
    " s=0x1.5980020145ae5p-17 eff=nan mem=10034/1056/8978/3202/5776"
    " ops=0,45562,0,0,42717,0,0,50988,17223,5017,0,0,0,0,0,0,0,316,0,42717,5017, pred=0"
    " hops=158978 ctrl=0 push=316 wi=0 ti=0 bound=latency (warp buffer) l1=lru (fully"
    " associative) l2=cold (footprint fits: compulsory misses only)",
    "robocore q=1000 n=5017 cyc=11329 launch=5034 e=0x1.aff3b096669f9p-15"
    " s=0x1.167d4f849f6c1p-17 eff=nan mem=10034/1056/8978/3202/5776"
    " ops=0,0,0,0,0,0,0,0,0,0,5017,25494,17223,0,0,0,0,316,0,0,5017, pred=0 hops=316"
    " ctrl=42717 push=316 wi=0 ti=0 bound=latency (warp buffer) l1=lru (fully associative)"
    " l2=cold (footprint fits: compulsory misses only)",
  }}, SactRecord);
  BackendParameters small;
  small.gpu.l1_bytes = 4096;
  small.gpu.l2_bytes = 65536;
  Check({"sact 64-byte nodes, small caches", {
    "simt q=1000 n=5017 cyc=15954 launch=5000 e=0x1.83290d9fa012p-14 s=0x1.882e667d7b851p-17"
    " eff=0x1.2669466ce7c02p-1 mem=10014/42/9972/1206/8766"
    " ops=0,0,0,0,0,0,0,0,0,0,5017,30102,45153,0,0,0,0,5017,0,75255,5017, pred=0 hops=0"
    " ctrl=0 push=5017 wi=56416 ti=1038094 bound=latency (resident warps) l1=lru (fully"
    " associative) l2=lru (set associative)",
    "ttaplus q=1000 n=5017 cyc=15443 launch=5049 e=0x1.541f7e953465ap-14"
    " s=0x1.7b9eae664de45p-17 eff=nan mem=10034/76/9958/1290/8668"
    " ops=0,50170,0,0,75255,0,0,60204,45153,5017,0,0,0,0,0,0,0,5017,0,0,5017, pred=0"
    " hops=190646 ctrl=0 push=5017 wi=0 ti=0 bound=latency (warp buffer) l1=lru (fully"
    " associative) l2=lru (set associative)",
    "ttaplus-p q=1000 n=5017 cyc=14883 launch=5064 e=0x1.59c59fff068bfp-14"
    " s=0x1.6dda9b034276bp-17 eff=nan mem=10034/76/9958/1290/8668"
    " ops=0,45562,0,0,42717,0,0,50988,17223,5017,0,0,0,0,0,0,0,316,0,42717,5017, pred=111531"
    " hops=265901 ctrl=0 push=316 wi=0 ti=0 bound=latency (warp buffer) l1=lru (fully"
    " associative) l2=lru (set associative)",
    "ttaplus-cr q=1000 n=5017 cyc=14364 launch=5064 e=0x1.4c1fea8248597p-14"
    " s=0x1.61188adfb1edfp-17 eff=nan mem=10034/76/9958/1290/8668"
    " ops=0,45562,0,0,42717,0,0,50988,17223,5017,0,0,0,0,0,0,0,316,0,42717,5017, pred=0"
    " hops=158978 ctrl=0 push=316 wi=0 ti=0 bound=latency (warp buffer) l1=lru (fully"
    " associative) l2=lru (set associative)",
    "robocore q=1000 n=5017 cyc=11795 launch=5034 e=0x1.383bca4e9485p-14"
    " s=0x1.21f1d85620b41p-17 eff=nan mem=10034/76/9958/1290/8668"
    " ops=0,0,0,0,0,0,0,0,0,0,5017,25494,17223,0,0,0,0,316,0,0,5017, pred=0 hops=316"
    " ctrl=42717 push=316 wi=0 ti=0 bound=DRAM bandwidth l1=lru (fully associative) l2=lru"
    " (set associative)",
  }}, SactRecord, small);
}

// clang-format on

}  // namespace
}  // namespace rc
