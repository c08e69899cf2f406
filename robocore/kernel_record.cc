#include "robocore/kernel_record.h"

#include <algorithm>
#include <limits>
#include <stdexcept>

namespace rc {

const char* ToString(StepProgramKind kind) {
  switch (kind) {
    case StepProgramKind::kGridMarch: return "grid_march";
    case StepProgramKind::kDdaStep: return "dda_step";
    case StepProgramKind::kRmStep: return "rm_step";
    case StepProgramKind::kSactTest: return "sact_obb_aabb";
    case StepProgramKind::kSphereTest: return "sphere_aabb";
    case StepProgramKind::kBallQueryPRay: return "ball_query_pray";
    case StepProgramKind::kBallQueryPSphere: return "ball_query_psphere";
  }
  return "?";
}

StepProgramKind StepProgramFor(RayCastMethod method) {
  switch (method) {
    case RayCastMethod::kMarch: return StepProgramKind::kGridMarch;
    case RayCastMethod::kDda: return StepProgramKind::kDdaStep;
    case RayCastMethod::kRayMarching: return StepProgramKind::kRmStep;
  }
  throw std::logic_error("unhandled ray-cast method");
}

std::uint64_t KernelRecord::footprint_begin() const {
  std::uint64_t begin = std::numeric_limits<std::uint64_t>::max();
  for (const MemoryRegion& r : regions) begin = std::min(begin, r.base);
  return regions.empty() ? 0 : begin;
}

std::uint64_t KernelRecord::footprint_end() const {
  std::uint64_t end = 0;
  for (const MemoryRegion& r : regions) end = std::max(end, r.base + r.bytes());
  return end;
}

void KernelRecord::Validate() const {
  auto fail = [](const std::string& what) { throw std::logic_error("kernel record: " + what); };
  if (!program || !program->has_loop()) fail("no step program with a loop");
  if ((leaf == nullptr) != (leaf_kind == LeafProgramKind::kNone)) fail("leaf program and leaf kind disagree");
  if (scalar_bytes != 4 && scalar_bytes != 8) fail("scalar_bytes must be 4 (float) or 8 (double)");
  if (fetch_offsets.empty() || fetch_offsets.front() != 0) fail("offsets must start at 0");
  if (exits_tallied() ? !node_exits.empty() || !last_exits.empty()
      : exits_per_query() ? (last_exits.size() != query_count() || !node_exits.empty())
                          : node_exits.size() != fetch_offsets.back())
    fail("one exit per fetch (or, last-pass exits, one per query; or tallied exits alone) expected");
  for (std::size_t i = 1; i < fetch_offsets.size(); ++i)
    if (fetch_offsets[i] < fetch_offsets[i - 1]) fail("offsets decrease");
  if (exits_tallied()) ValidateTalliedExits();
  if (!sampled()) {
    if (!address_sample.KeepsAll()) fail("a sample without address offsets");
    if (fetch_offsets.back() != fetch_addresses.size()) fail("offsets do not end at the fetch count");
  } else {
    // A block's queries share an SM, so the sample keeps all of them or none.
    if (address_offsets != KeptAddressOffsets(fetch_offsets, address_sample))
      fail("address offsets: one per block plus one, a kept block's nodes each");
    if (address_offsets.back() != fetch_addresses.size()) fail("address offsets do not end at the address count");
  }
  // Branch-free scans first (records hold millions of fetches); the slow
  // search for the culprit only when one fails.
  const int returns = program->ReturnIfCount(ProgramSection::kLoop);
  if (exits_tallied())
    for (const std::uint8_t v : tallied_exits->variant)
      if (v > returns)
        fail("a tallied exit names RETURN_IF #" + std::to_string(v - 1) + " but the loop of '" + program->name() +
             "' has " + std::to_string(returns));
  const std::vector<std::uint8_t>& exits = exits_per_query() ? last_exits : node_exits;
  std::uint8_t highest = 0;  // 1 + the highest RETURN_IF named (kNoExit + 1 wraps to 0)
  for (const std::uint8_t e : exits) highest = std::max(highest, static_cast<std::uint8_t>(e + 1));
  if (highest > returns)
    for (std::uint8_t e : exits)
      if (e != kNoExit && e >= returns)
        fail("an exit names RETURN_IF #" + std::to_string(e) + " but the loop of '" + program->name() + "' has " +
             std::to_string(returns));
  std::uint64_t lowest_address = ~std::uint64_t{0}, highest_address = 0;
  for (const std::uint64_t a : fetch_addresses) {
    lowest_address = std::min(lowest_address, a);
    highest_address = std::max(highest_address, a);
  }
  for (const MemoryRegion& r : regions)
    if (lowest_address >= r.base && highest_address + node_bytes <= r.base + r.bytes()) return;  // one region holds all
  for (std::uint64_t a : fetch_addresses) {
    bool inside = false;
    for (const MemoryRegion& r : regions) inside = inside || (a >= r.base && a + node_bytes <= r.base + r.bytes());
    if (!inside) fail("address " + std::to_string(a) + " lies outside every region");
  }
}

void KernelRecord::ValidateTalliedExits() const {
  auto fail = [](const std::string& what) { throw std::logic_error("kernel record: tallied exits: " + what); };
  const ExitProfile& t = *tallied_exits;
  if (t.offsets.size() != fetch_offsets.size() || t.offsets.front() != 0) fail("one offset per query plus one expected");
  if (t.offsets.back() != t.variant.size() || t.variant.size() != t.passes.size())
    fail("offsets do not end at the variant and pass counts");
  for (std::size_t q = 0; q < query_count(); ++q) {
    if (t.offsets[q + 1] < t.offsets[q] || t.offsets[q + 1] > t.variant.size()) fail("offsets decrease");
    std::uint64_t passes = 0;
    for (std::uint32_t i = t.offsets[q]; i < t.offsets[q + 1]; ++i) passes += t.passes[i];
    if (passes != nodes(q)) fail("query " + std::to_string(q) + "'s passes do not add up to its node count");
  }
}

KernelRecordBuilder::KernelRecordBuilder(std::shared_ptr<const MicroProgram> program, StepProgramKind kind,
                                         MemoryRegion region) {
  record_.program = std::move(program);
  record_.step_kind = kind;
  record_.node_bytes = region.element_bytes;
  record_.regions.push_back(std::move(region));
}

KernelRecordBuilder& KernelRecordBuilder::SetLeaf(std::shared_ptr<const MicroProgram> leaf, LeafProgramKind kind) {
  record_.leaf = std::move(leaf);
  record_.leaf_kind = kind;
  return *this;
}

KernelRecordBuilder& KernelRecordBuilder::AddQuery(const std::vector<std::uint64_t>& addresses,
                                                   const std::vector<std::uint8_t>& exits) {
  if (!exits.empty() && exits.size() != addresses.size())
    throw std::invalid_argument("KernelRecordBuilder: one exit per address expected");
  record_.fetch_addresses.insert(record_.fetch_addresses.end(), addresses.begin(), addresses.end());
  if (exits.empty())
    record_.node_exits.insert(record_.node_exits.end(), addresses.size(), kNoExit);
  else
    record_.node_exits.insert(record_.node_exits.end(), exits.begin(), exits.end());
  record_.fetch_offsets.push_back(record_.fetch_addresses.size());
  return *this;
}

KernelRecord KernelRecordBuilder::Build() const {
  record_.Validate();
  return record_;
}

std::vector<std::uint64_t> KeptAddressOffsets(const std::vector<std::uint64_t>& fetch_offsets,
                                              const AddressSample& sample) {
  const std::size_t n = fetch_offsets.size() - 1, block = sample.BlockQueries();
  std::vector<std::uint64_t> offsets(1, 0);
  offsets.reserve((n + block - 1) / block + 1);
  std::uint64_t kept = 0;
  for (std::size_t lo = 0; lo < n; lo += block) {
    if (sample.KeepsQuery(lo)) kept += fetch_offsets[std::min(n, lo + block)] - fetch_offsets[lo];
    offsets.push_back(kept);
  }
  return offsets;
}

}  // namespace rc
