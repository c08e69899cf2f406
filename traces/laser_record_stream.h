#pragma once
// A reader of one trace format, record by record (cmu_log_reader.h,
// rowild_log_reader.h, carmen_log_reader.h). Each reader's Read* function
// collects its stream into a SensorTrace; OpenTraceStream (trace_reader.h)
// serves it to a run one record at a time.
#include "traces/sensor_trace.h"
#include "traces/trace_read_stats.h"

namespace rc {

class LaserRecordStream {
 public:
  virtual ~LaserRecordStream() = default;
  // The next laser record; false at the end of the file. Throws InputError
  // (file, line, field) at the first malformed line.
  virtual bool Next(LaserScan& scan) = 0;
  // Valid once the first record has been returned (the mount of CMU and
  // CARMEN logs is measured on it).
  virtual const LaserGeometry& geometry() const = 0;
  // What the stream has seen so far; laser_records counts returned records.
  virtual const TraceReadStats& stats() const = 0;
};

}  // namespace rc
