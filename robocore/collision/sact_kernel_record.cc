#include "robocore/collision/sact_kernel_record.h"

#include <algorithm>
#include <stdexcept>
#include <vector>

#include <omp.h>

#include "robocore/exit_profile.h"
#include "robocore/shipped_programs.h"

namespace rc {
namespace {

bool Fail(std::string* why, const std::string& reason) {
  if (why) *why = reason;
  return false;
}

std::uint8_t SactExitOf(const NodeVisit& v) { return v.exit >= 0 ? static_cast<std::uint8_t>(v.exit) : kNoExit; }

// Which sectors of a node array a batch touched (every sector of every
// fetched node), numbered from the array's base. Marked a bit per node as
// the visits happen (a shift and an OR in the traversal, no address
// arithmetic), turned into sectors once, when counted.
class TouchedSectors {
 public:
  TouchedSectors(std::uint64_t node_count, std::uint64_t node_bytes, int sector_bytes)
      : node_count_(node_count), node_bytes_(node_bytes), nodes_((node_count + 63) / 64, 0) {
    while ((1 << shift_) < sector_bytes) ++shift_;
  }
  void Mark(std::uint32_t node) { nodes_[node >> 6] |= std::uint64_t{1} << (node & 63); }
  void Merge(const TouchedSectors& other) {
    for (std::size_t w = 0; w < nodes_.size(); ++w) nodes_[w] |= other.nodes_[w];
  }
  std::uint64_t Count() const {
    const std::uint64_t sectors =
        node_bytes_ == 0 || node_count_ == 0 ? 0 : ((node_count_ * node_bytes_ - 1) >> shift_) + 1;
    std::vector<std::uint64_t> touched((sectors + 63) / 64, 0);
    for (std::size_t w = 0; w < nodes_.size(); ++w)
      for (std::uint64_t bits = nodes_[w]; bits != 0; bits &= bits - 1) {
        const std::uint64_t first = (w * 64 + static_cast<std::uint64_t>(__builtin_ctzll(bits))) * node_bytes_;
        for (std::uint64_t s = first >> shift_; s <= (first + node_bytes_ - 1) >> shift_; ++s)
          touched[s >> 6] |= std::uint64_t{1} << (s & 63);
      }
    std::uint64_t n = 0;
    for (const std::uint64_t b : touched) n += static_cast<std::uint64_t>(__builtin_popcountll(b));
    return n;
  }

 private:
  std::uint64_t node_count_, node_bytes_;
  int shift_ = 0;
  std::vector<std::uint64_t> nodes_;  // a bit per node
};

// The batch as a record: query i's fetches are its visits, in order
// (fetch_offsets = the batch's visit offsets); exit_of maps a visit to its
// exit, kept per fetch or tallied per query. Addresses are kept for the
// queries `sample` keeps. One pass over the visits.
template <typename ExitOf>
KernelRecord BuildRecord(const CollisionBatch& batch, std::shared_ptr<const MicroProgram> program, StepProgramKind kind,
                         const AddressSample& sample, RecordedExits exits, ExitOf&& exit_of) {
  KernelRecord record;
  record.program = std::move(program);
  record.step_kind = kind;
  record.regions.push_back(TreeNodeRegion(batch));
  record.node_bytes = record.regions.front().element_bytes;
  record.scalar_bytes = batch.scalar_bytes;
  record.fetch_offsets = batch.visit_offsets;
  const std::size_t n = batch.query_count();
  const std::vector<NodeVisit>& visits = batch.visits;
  const bool tally_exits = exits == RecordedExits::kTallied;
  ExitTally tally;
  std::shared_ptr<ExitProfile> profile;
  if (tally_exits) {
    profile = std::make_shared<ExitProfile>();
    profile->offsets.assign(n + 1, 0);
    profile->variant.reserve(n);
    profile->passes.reserve(n);
  } else {
    record.node_exits.resize(visits.size());
  }
  record.address_sample = sample;
  if (!sample.KeepsAll()) record.address_offsets = KeptAddressOffsets(record.fetch_offsets, sample);
  record.fetch_addresses.reserve(sample.KeepsAll() ? visits.size() : record.address_offsets.back());
  // Sectors the whole batch touched, numbered from the region's base (the
  // record's footprint_begin()); only a sampled record counts them.
  const bool mark = !sample.KeepsAll();
  TouchedSectors touched(mark ? batch.node_count : 0, batch.node_bytes, sample.sector_bytes);
  for (std::size_t q = 0; q < n; ++q) {
    const bool keep = sample.KeepsQuery(q);
    for (std::uint64_t k = batch.visit_offsets[q]; k < batch.visit_offsets[q + 1]; ++k) {
      const std::uint8_t exit = exit_of(visits[k]);
      if (tally_exits)
        tally.Add(exit);
      else
        record.node_exits[k] = exit;
      if (mark) touched.Mark(visits[k].node);
      if (keep) record.fetch_addresses.push_back(batch.Address(visits[k]));
    }
    if (tally_exits) profile->offsets[q + 1] = profile->offsets[q] + tally.Append(profile->variant, profile->passes);
  }
  if (tally_exits) record.tallied_exits = std::move(profile);
  if (mark) record.touched_sectors = touched.Count();
  record.Validate();
  return record;
}

}  // namespace

MemoryRegion TreeNodeRegion(const CollisionBatch& batch) {
  return TreeNodeRegion(batch.base_address, batch.node_bytes, batch.node_count);
}

MemoryRegion TreeNodeRegion(std::uint64_t base_address, std::uint32_t node_bytes, std::uint64_t node_count) {
  MemoryRegion region;
  region.name = "box tree nodes";
  region.kind = FetchKind::kTreeNode;
  region.base = base_address;
  region.element_bytes = node_bytes;
  region.elements = node_count;
  return region;
}

bool KeepsSactExitContract(const MicroProgram& program, std::string* why) {
  const std::vector<MicroOp>& loop = program.section(ProgramSection::kLoop);
  if (loop.empty()) return Fail(why, "program '" + program.name() + "' has no loop: section");
  bool any_sact = false;
  for (const MicroOp& op : loop) any_sact = any_sact || InfoOf(op.opcode).sact;
  if (!any_sact)
    return Fail(why, "program '" + program.name() + "' has no SACT section (no PRE, BOX or EDGE micro-op in its loop)");
  bool pre_seen = false;
  int next_axis = 0;     // the axis whose test must come next
  int axis_tested = -1;  // the highest axis tested so far, in order
  int return_ifs = 0;
  for (const MicroOp& op : loop) {
    const std::string where = "program '" + program.name() + "' line " + std::to_string(op.line) + ": ";
    if (op.opcode == Opcode::kPre) pre_seen = true;
    if (op.opcode == Opcode::kBox || op.opcode == Opcode::kEdge) {
      const int axis = op.opcode == Opcode::kBox ? op.axis : kSactBoxNormalAxes + op.axis;
      if (!pre_seen) return Fail(why, where + "an axis test before the PRE pre-process");
      if (axis != next_axis)
        return Fail(why, where + "tests SACT axis " + std::to_string(axis) + " where axis " +
                             std::to_string(next_axis) + " (sact.h stage order) is due");
      axis_tested = axis;
      ++next_axis;
    }
    if (op.opcode == Opcode::kReturnIf) {
      if (return_ifs >= kSactAxisCount)
        return Fail(why, where + "more than " + std::to_string(kSactAxisCount) + " RETURN_IFs");
      if (axis_tested < return_ifs)
        return Fail(why, where + "RETURN_IF #" + std::to_string(return_ifs) + " comes before axis " +
                             std::to_string(return_ifs) + " is tested");
      ++return_ifs;
    }
  }
  if (next_axis != kSactAxisCount || return_ifs != kSactAxisCount)
    return Fail(why, "program '" + program.name() + "' has no SACT section: its loop tests " +
                         std::to_string(next_axis) + " of the 15 axes (PRE, BOX 0..5, EDGE 0..8) with " +
                         std::to_string(return_ifs) + " RETURN_IFs");
  return true;
}

KernelRecord SactKernelRecord(const CollisionBatch& batch, std::shared_ptr<const MicroProgram> program,
                              const AddressSample& sample, RecordedExits exits) {
  if (batch.robot_model != CollisionRobotModel::kObb)
    throw std::invalid_argument("SactKernelRecord: a sphere-robot batch is priced by SphereKernelRecord");
  if (batch.sphere_pretests)
    throw std::invalid_argument("SactKernelRecord: the SACT program has no sphere pre-test section");
  if (!program) program = ShippedStepProgram(StepProgramKind::kSactTest);
  std::string why;
  if (!KeepsSactExitContract(*program, &why)) throw std::invalid_argument("SactKernelRecord: " + why);
  return BuildRecord(batch, std::move(program), StepProgramKind::kSactTest, sample, exits, SactExitOf);
}

template <typename Scalar>
void CollideBatchRecorded(const FlatBoxTree<Scalar>& tree, const std::vector<Obb<Scalar>>& obbs,
                          const CollisionOptions<Scalar>& options, const AddressSample& sample,
                          std::vector<TraversalOutcome>* outcomes, KernelRecord* record, std::uint64_t base_address) {
  std::string error;
  if (!options.sact.IsValid(&error)) throw std::invalid_argument("SACT options: " + error);
  if (record && options.sact.sphere_pretests)
    throw std::invalid_argument("CollideBatchRecorded: the SACT program has no sphere pre-test section");
  const long n = static_cast<long>(obbs.size());
  const long block = static_cast<long>(sample.BlockQueries());  // KeptAddressOffsets' blocks
  const long blocks = (n + block - 1) / block;
  outcomes->resize(obbs.size());
  const std::uint64_t node_count = tree.nodes().size();
  const std::uint32_t node_bytes = tree.node_bytes();
  // Per thread, the exit tallies (pairs of variant and passes) of the
  // queries of its blocks and the addresses of its kept blocks, each block's
  // in one span; per query, how many pairs it has. A thread's lists are its
  // own cache lines: threads take adjacent blocks, and growing lists that
  // shared a line would bounce it between cores at every query.
  struct alignas(64) ThreadLists {
    // The first `pairs` entries are written; the rest is room, so that a
    // query's pairs go in through raw pointers (ExitTally::Write).
    std::vector<std::uint8_t> variant;
    std::vector<std::uint32_t> passes;
    std::size_t pairs = 0;
    std::vector<std::uint64_t> addresses;
  };
  struct BlockSpan {
    const ThreadLists* lists = nullptr;
    std::size_t pair_begin = 0, pair_end = 0, address_begin = 0, address_end = 0;
  };
  std::vector<ThreadLists> thread_lists(record ? static_cast<std::size_t>(std::max(1, omp_get_max_threads())) : 0);
  std::vector<BlockSpan> block_spans(record ? static_cast<std::size_t>(blocks) : 0);
  std::vector<std::uint32_t> query_pairs(record ? obbs.size() : 0);
  const bool mark = record && !sample.KeepsAll();
  std::vector<TouchedSectors> touched;
#pragma omp parallel if (blocks > 1)
  {
    std::vector<std::uint32_t> scratch;
    ExitTally tally;
    TouchedSectors mine(mark ? node_count : 0, node_bytes, sample.sector_bytes);
#pragma omp for schedule(dynamic, 1)
    for (long b = 0; b < blocks; ++b) {
      const long lo = b * block, hi = std::min(n, lo + block);
      if (!record) {
        for (long i = lo; i < hi; ++i)
          (*outcomes)[i] = CollideObbVisiting(
              tree, obbs[i], options, [](const NodeVisit&) {}, &scratch);
        continue;
      }
      // Each visit kept as it happens: its exit tallied, in a sampled record
      // its sectors marked as touched, and in a kept block its address. A
      // query's tally joins the thread's lists when the query ends.
      ThreadLists& lists = thread_lists[static_cast<std::size_t>(omp_get_thread_num())];
      BlockSpan span{&lists, lists.pairs, 0, lists.addresses.size(), 0};
      std::size_t pairs = lists.pairs;
      const bool keep = sample.KeepsQuery(static_cast<std::size_t>(lo));
      // keep and mark are fixed for the block: copied, not read back after
      // every store.
      auto record_visit = [&, keep, mark](const NodeVisit& v) {
        tally.Add(SactExitOf(v));
        if (mark) mine.Mark(v.node);
        if (keep) lists.addresses.push_back(base_address + std::uint64_t{v.node} * node_bytes);
      };
      for (long i = lo; i < hi; ++i) {
        (*outcomes)[i] = CollideObbVisiting(tree, obbs[i], options, record_visit, &scratch);
        if (pairs + tally.pairs() > lists.variant.size()) {
          const std::size_t room = std::max<std::size_t>(2 * lists.variant.size(), pairs + 256);
          lists.variant.resize(room);
          lists.passes.resize(room);
        }
        query_pairs[i] = tally.Write(lists.variant.data() + pairs, lists.passes.data() + pairs);
        pairs += query_pairs[i];
      }
      lists.pairs = span.pair_end = pairs;
      span.address_end = lists.addresses.size();
      block_spans[b] = span;
    }
    if (mark) {
#pragma omp critical(rc_collision_touched_sectors)
      touched.push_back(std::move(mine));
    }
  }
  if (!record) return;

  record->program = ShippedStepProgram(StepProgramKind::kSactTest);
  record->step_kind = StepProgramKind::kSactTest;
  record->leaf = nullptr;
  record->leaf_kind = LeafProgramKind::kNone;
  record->regions.assign(1, TreeNodeRegion(base_address, node_bytes, node_count));
  record->node_bytes = node_bytes;
  record->scalar_bytes = sizeof(Scalar);
  // Prefix sums with the running sum in a register (reading each entry back
  // would wait on its store).
  record->fetch_offsets.assign(obbs.size() + 1, 0);
  std::uint64_t sum = 0;
  for (long i = 0; i < n; ++i) record->fetch_offsets[i + 1] = sum += (*outcomes)[i].nodes_visited;
  record->last_exits.clear();
  record->node_exits.clear();
  auto exits = std::make_shared<ExitProfile>();
  exits->offsets.resize(obbs.size() + 1);  // offsets[0] is 0 already
  std::uint32_t pairs = 0;
  for (long i = 0; i < n; ++i) exits->offsets[i + 1] = pairs += query_pairs[i];
  record->address_sample = sample;
  record->address_offsets.clear();
  if (!sample.KeepsAll()) record->address_offsets = KeptAddressOffsets(record->fetch_offsets, sample);
  std::vector<std::uint64_t> pair_start(static_cast<std::size_t>(blocks) + 1, 0), address_start(pair_start);
  // Whether every block's span already sits where the record wants it, in
  // the first thread's lists (one thread took every block, in order).
  bool in_place = true;
  for (long b = 0; b < blocks; ++b) {
    const BlockSpan& span = block_spans[b];
    in_place = in_place && span.lists == &thread_lists.front() && span.pair_begin == pair_start[b] &&
               span.address_begin == address_start[b];
    pair_start[b + 1] = pair_start[b] + (span.pair_end - span.pair_begin);
    address_start[b + 1] = address_start[b] + (span.address_end - span.address_begin);
  }
  if (in_place) {
    // The lists are the arrays: moved, not copied (their room past the
    // written pairs cut off).
    ThreadLists& t = thread_lists.front();
    t.variant.resize(pairs);
    t.passes.resize(pairs);
    t.addresses.resize(address_start.back());
    exits->variant = std::move(t.variant);
    exits->passes = std::move(t.passes);
    record->fetch_addresses = std::move(t.addresses);
  } else {
    exits->variant.resize(pairs);
    exits->passes.resize(pairs);
    record->fetch_addresses.resize(address_start.back());
#pragma omp parallel for schedule(static) if (blocks > 1)
    for (long b = 0; b < blocks; ++b) {
      const BlockSpan& span = block_spans[b];
      const ThreadLists& t = *span.lists;
      std::copy(t.variant.begin() + static_cast<long>(span.pair_begin),
                t.variant.begin() + static_cast<long>(span.pair_end),
                exits->variant.begin() + static_cast<long>(pair_start[b]));
      std::copy(t.passes.begin() + static_cast<long>(span.pair_begin), t.passes.begin() + static_cast<long>(span.pair_end),
                exits->passes.begin() + static_cast<long>(pair_start[b]));
      std::copy(t.addresses.begin() + static_cast<long>(span.address_begin),
                t.addresses.begin() + static_cast<long>(span.address_end),
                record->fetch_addresses.begin() + static_cast<long>(address_start[b]));
    }
  }
  record->tallied_exits = std::move(exits);
  record->touched_sectors = 0;
  if (mark) {
    for (std::size_t t = 1; t < touched.size(); ++t) touched.front().Merge(touched[t]);
    record->touched_sectors = touched.empty() ? 0 : touched.front().Count();
  }
  record->Validate();
}

template void CollideBatchRecorded(const FlatBoxTree<float>&, const std::vector<Obb<float>>&,
                                   const CollisionOptions<float>&, const AddressSample&, std::vector<TraversalOutcome>*,
                                   KernelRecord*, std::uint64_t);
template void CollideBatchRecorded(const FlatBoxTree<double>&, const std::vector<Obb<double>>&,
                                   const CollisionOptions<double>&, const AddressSample&,
                                   std::vector<TraversalOutcome>*, KernelRecord*, std::uint64_t);

bool KeepsSphereExitContract(const MicroProgram& program, std::string* why) {
  if (!program.has_loop()) return Fail(why, "program '" + program.name() + "' has no loop: section");
  for (int s = 0; s < kSectionCount; ++s)
    for (const MicroOp& op : program.section(static_cast<ProgramSection>(s)))
      if (InfoOf(op.opcode).sact)
        return Fail(why, "program '" + program.name() + "' line " + std::to_string(op.line) +
                             ": a SACT micro-op in a sphere program");
  if (program.ReturnIfCount(ProgramSection::kLoop) != 1)
    return Fail(why, "program '" + program.name() + "' needs exactly one loop RETURN_IF (#0: the sphere misses)");
  return true;
}

KernelRecord SphereKernelRecord(const CollisionBatch& batch, std::shared_ptr<const MicroProgram> program,
                                const AddressSample& sample) {
  if (batch.robot_model != CollisionRobotModel::kSpheres)
    throw std::invalid_argument("SphereKernelRecord: an OBB batch is priced by SactKernelRecord");
  if (!program) program = ShippedStepProgram(StepProgramKind::kSphereTest);
  std::string why;
  if (!KeepsSphereExitContract(*program, &why)) throw std::invalid_argument("SphereKernelRecord: " + why);
  return BuildRecord(batch, std::move(program), StepProgramKind::kSphereTest, sample, RecordedExits::kPerFetch,
                     [](const NodeVisit& v) { return v.overlaps() ? kNoExit : std::uint8_t{0}; });
}

}  // namespace rc
