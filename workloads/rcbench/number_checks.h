#pragma once
// CLI11 checks for numeric options, shared by every subcommand so that a
// value a run cannot use is refused the same way everywhere (exit 2, with
// the option's name) instead of being silently replaced by a default: CLI11's
// own PositiveNumber lets NaN through (NaN <= 0 is false), and its range
// message prints the whole double range.
#include <CLI/CLI.hpp>

namespace rc {

// A finite number > 0 (a cell size, a reach).
const CLI::Validator& FinitePositive();
// A finite number (a pose coordinate).
const CLI::Validator& Finite();

}  // namespace rc
