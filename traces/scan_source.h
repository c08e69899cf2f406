#pragma once
// Laser records one at a time, so that a run holds the record it is on, not
// the whole trace: memory does not grow with the length of the log.
//
// A source opened from a file (OpenTraceStream, trace_reader.h) has read the
// whole file once already, to validate it and count its records, so every
// bad-input error is raised before a run starts and writes anything; the run
// then reads it again, record by record.
#include <cstddef>
#include <memory>
#include <string>

#include "traces/sensor_trace.h"

namespace rc {

class ScanSource {
 public:
  virtual ~ScanSource() = default;
  virtual const std::string& source_path() const = 0;
  virtual const std::string& format() const = 0;
  // Fixed for the whole trace and known before the first record.
  virtual const LaserGeometry& geometry() const = 0;
  // Laser records in the trace.
  virtual std::size_t size() const = 0;
  // The next record; false after the last. Throws InputError if the file
  // changed since it was validated.
  virtual bool Next(LaserScan& scan) = 0;
  // Back to the first record.
  virtual void Rewind() = 0;
};

// Over a trace already in memory (tests, MRPT rawlogs, the generated demo).
// Borrows `trace`, which must outlive the source.
class InMemoryScanSource final : public ScanSource {
 public:
  explicit InMemoryScanSource(const SensorTrace& trace) : trace_(trace) {}
  const std::string& source_path() const override { return trace_.source_path; }
  const std::string& format() const override { return trace_.format; }
  const LaserGeometry& geometry() const override { return trace_.geometry; }
  std::size_t size() const override { return trace_.scans.size(); }
  bool Next(LaserScan& scan) override {
    if (next_ >= trace_.scans.size()) return false;
    scan = trace_.scans[next_++];
    return true;
  }
  void Rewind() override { next_ = 0; }

 private:
  const SensorTrace& trace_;
  std::size_t next_ = 0;
};

// Owns the trace it serves.
class OwningScanSource final : public ScanSource {
 public:
  explicit OwningScanSource(SensorTrace trace) : trace_(std::move(trace)), view_(trace_) {}
  const std::string& source_path() const override { return view_.source_path(); }
  const std::string& format() const override { return view_.format(); }
  const LaserGeometry& geometry() const override { return view_.geometry(); }
  std::size_t size() const override { return view_.size(); }
  bool Next(LaserScan& scan) override { return view_.Next(scan); }
  void Rewind() override { view_.Rewind(); }

 private:
  SensorTrace trace_;
  InMemoryScanSource view_;
};

}  // namespace rc
