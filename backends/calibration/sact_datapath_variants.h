#pragma once
// SACT datapath variants the parameters cannot express: more SACT units
// per intersection unit set, so that several axes of one test run at once
// (paper: "fully parallel SACT (6 box + 9 edge units)" and "two of each
// SACT unit"). The shipped design (robocore_backend.h) has one unit of each
// kind and tests the 15 axes one after another.
//
// The smallest model that reuses the priced datapath unchanged: a variant
// is a list of ROUNDS, each a set of axes tested at the same time on
// separate units. It becomes a step program (LOAD, PRE, then per round one
// SACT micro-op on the round's slowest unit kind followed by RETURN_IF #r,
// then PUSH) and every node's recorded exit is remapped from "axis k
// separated" to "round r, the one holding axis k, separated". The existing
// section timing then prices it: PRE, then one unit latency per round
// reached, CTRL-folded exits, chained packets; the cache replay is the same
// traversal's.
//
// Assumptions (none from the paper, which gives only the ratios):
//  * a round takes the latency of its slowest unit (the units are the same
//    4-stage pipelines, started together on the pre-processed frame);
//  * CTRL picks the lowest separating axis of a round in no extra cycles
//    (the shipped model's ctrl_exit_cycles = 0 assumption), so the answer
//    and the axis reported stay the shipped test's;
//  * each unit instance takes one packet per round, so a round occupies one
//    slot of its unit kind per set: the throughput bound counts rounds;
//  * the fully parallel design tests all 15 axes in one round (the edge
//    axes need only the pre-processed frame, not the box-normal results);
//  * energy is not compared: the program counts one SACT micro-op per round,
//    while the hardware computes every axis of the round (more than the
//    shipped early-exit design). Area is not modelled.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "robocore/datapath_params.h"
#include "robocore/kernel_record.h"

namespace rc {

struct SactDatapathVariant {
  std::string name;
  std::vector<std::vector<int>> rounds;  // axes 0..14 (sact.h order), each exactly once, in test order
};

// All 15 axes in one round: 6 Box-Normal + 9 Edge x Edge units.
SactDatapathVariant FullyParallelSact();
// `copies` units of each kind: the box-normal axes in groups of `copies`,
// then the edge axes in groups of `copies` (copies = 1: the shipped design).
SactDatapathVariant SactUnitCopies(int copies);

// The variant's step program on a datapath with these latencies (a round
// runs on its slowest unit kind). Throws std::invalid_argument if the
// rounds do not hold each axis exactly once.
std::shared_ptr<const MicroProgram> VariantProgram(const SactDatapathVariant& variant,
                                                   const OpUnitLatencies& latencies);

// The variant's record of the same traversal: same fetches, the variant's
// program, exits remapped axis -> round (kNoExit stays).
KernelRecord VariantRecord(const KernelRecord& shipped_sact_record, const SactDatapathVariant& variant,
                           const OpUnitLatencies& latencies);

}  // namespace rc
