#pragma once
// A one-line progress bar on stderr, shown only when stderr is a terminal
// (never in logs, CI or pipes).
#include <chrono>
#include <cstddef>
#include <string>

namespace rc {

class ProgressBar {
 public:
  ProgressBar(std::string label, bool enabled);
  ~ProgressBar();
  void Update(std::size_t done, std::size_t total);
  static bool StderrIsTerminal();

 private:
  std::string label_;
  bool enabled_;
  bool drawn_ = false;
  std::chrono::steady_clock::time_point start_;
  std::chrono::steady_clock::time_point last_draw_;
};

}  // namespace rc
