#include "traces/trace_reader.h"

#include <fstream>

#include "common/text_fields.h"
#include "traces/record_fields.h"
#include "traces/rowild_log_reader.h"

namespace rc {
namespace {

constexpr std::size_t kRowildFields = 183;

// Messages CARMEN's logger documents; enough to recognise a CARMEN log by its
// first message without mistaking other upper-case text for one.
bool IsKnownCarmenMessage(std::string_view token) {
  static const char* const kNames[] = {"PARAM",       "SYNC",        "ODOM",      "TRUEPOS",   "FLASER",    "RLASER",
                                       "LASER3",      "LASER4",      "RAWLASER1", "RAWLASER2", "RAWLASER3", "RAWLASER4",
                                       "ROBOTLASER1", "ROBOTLASER2", "NMEAGGA",   "NMEARMC"};
  for (const char* name : kNames)
    if (token == name) return true;
  return false;
}

}  // namespace

std::string DetectTraceFormat(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path, 0, "", "cannot open trace file");
  LineReader reader(in, path);
  std::string line;
  while (reader.Next(line)) {
    const auto fields = SplitFields(line);
    if (fields.empty()) continue;
    if (fields[0][0] == '#') return "carmen";
    if (fields[0] == "O" || fields[0] == "L") return "cmu";
    if (IsKnownCarmenMessage(fields[0])) return "carmen";
    if (fields.size() == kRowildFields) {
      for (std::size_t i = 0; i < fields.size(); ++i)
        if (!LooksNumeric(fields[i]))
          reader.Fail("field " + std::to_string(i + 1),
                      "looks like a RoWild log (183 fields) but '" + std::string(fields[i]) + "' is not a number");
      return "rowild";
    }
    reader.Fail("format", "cannot tell the trace format from this line (" + std::to_string(fields.size()) +
                              " fields starting with '" + std::string(fields[0]) +
                              "'); expected CMU O/L records, CARMEN messages or RoWild's 183 numbers; "
                              "name the format explicitly");
  }
  throw InputError(path, 0, "format", "the file is empty: no records to detect a format from");
}

namespace {

void CheckOptions(const TraceReadOptions& options) {
  const std::string& requested = options.format;
  if (requested != "auto" && requested != "cmu" && requested != "rowild" && requested != "carmen")
    throw UsageError("unknown trace format '" + requested + "' (expected auto, cmu, rowild or carmen)");
  if (options.expected_beam_count < 0)
    throw UsageError("expected beam count must be >= 0 (0 = take it from the format)");
  LaserGeometry unused;
  ApplyLaserOffset(options, unused);
}

std::string RecordKind(const std::string& format) {
  if (format == "cmu") return "L records";
  if (format == "rowild") return "laser records";
  return "FLASER or ROBOTLASER1 records";
}

// Opens the format's record stream, with the mount override applied.
std::unique_ptr<LaserRecordStream> OpenStream(const std::string& path, const std::string& format,
                                              const TraceReadOptions& options) {
  CmuLogOptions cmu = options.cmu;
  CarmenLogOptions carmen = options.carmen;
  if (options.laser_offset_forward_m)
    cmu.laser_offset_forward_m = carmen.laser_offset_forward_m = options.laser_offset_forward_m;
  if (format == "cmu") return std::make_unique<CmuLogStream>(path, cmu);
  if (format == "rowild") return std::make_unique<RowildLogStream>(path);
  return std::make_unique<CarmenLogStream>(path, carmen);
}

void CheckBeamCount(const std::string& path, const std::string& format, const TraceReadOptions& options,
                    const LaserGeometry& geometry, long first_line) {
  if (options.expected_beam_count != 0 && geometry.beam_count != options.expected_beam_count)
    throw InputError(path, first_line, "beam count",
                     "the " + format + " trace has " + std::to_string(geometry.beam_count) +
                         " beams per scan, expected " + std::to_string(options.expected_beam_count));
}

class FileScanSource final : public ScanSource {
 public:
  FileScanSource(std::string path, std::string format, const TraceReadOptions& options, TraceReadStats* stats)
      : path_(std::move(path)), format_(std::move(format)), options_(options) {
    // The validation pass: every record parsed and checked, none kept.
    std::unique_ptr<LaserRecordStream> stream = OpenStream(path_, format_, options_);
    LaserScan scan;
    long first_line = 0;
    while (stream->Next(scan)) {
      if (size_ == 0) first_line = scan.source_line;
      ++size_;
    }
    RequireLaserRecords(path_, size_, RecordKind(format_));
    geometry_ = stream->geometry();
    ApplyLaserOffset(options_, geometry_);
    CheckBeamCount(path_, format_, options_, geometry_, first_line);
    if (stats) *stats = stream->stats();
    Rewind();
  }

  const std::string& source_path() const override { return path_; }
  const std::string& format() const override { return format_; }
  const LaserGeometry& geometry() const override { return geometry_; }
  std::size_t size() const override { return size_; }

  bool Next(LaserScan& scan) override {
    if (!stream_->Next(scan)) {
      if (served_ != size_) Changed(scan.source_line);
      return false;
    }
    if (++served_ > size_ || stream_->geometry().beam_count != geometry_.beam_count) Changed(scan.source_line);
    return true;
  }

  void Rewind() override {
    stream_ = OpenStream(path_, format_, options_);
    served_ = 0;
  }

 private:
  [[noreturn]] void Changed(long line) const {
    throw InputError(path_, line, "",
                     "the file changed while it was being read (it held " + std::to_string(size_) +
                         " laser records when it was opened)");
  }

  std::string path_, format_;
  TraceReadOptions options_;
  LaserGeometry geometry_;
  std::size_t size_ = 0;
  std::size_t served_ = 0;
  std::unique_ptr<LaserRecordStream> stream_;
};

}  // namespace

void ApplyLaserOffset(const TraceReadOptions& options, LaserGeometry& geometry) {
  if (!options.laser_offset_forward_m) return;
  const double offset = *options.laser_offset_forward_m;
  if (!(offset >= 0.0 && offset <= 10.0)) throw UsageError("--laser-offset must be in [0, 10] m");
  geometry.offset_forward_m = offset;
}

SensorTrace ReadTrace(const std::string& path, const TraceReadOptions& options, TraceReadStats* stats) {
  CheckOptions(options);
  const std::string format = options.format == "auto" ? DetectTraceFormat(path) : options.format;
  std::unique_ptr<LaserRecordStream> stream = OpenStream(path, format, options);
  SensorTrace trace;
  trace.source_path = path;
  trace.format = format;
  LaserScan scan;
  while (stream->Next(scan)) trace.scans.push_back(std::move(scan));
  RequireLaserRecords(trace, RecordKind(format));
  trace.geometry = stream->geometry();
  ApplyLaserOffset(options, trace.geometry);
  CheckBeamCount(path, format, options, trace.geometry, trace.scans.front().source_line);
  if (stats) *stats = stream->stats();
  return trace;
}

std::unique_ptr<ScanSource> OpenTraceStream(const std::string& path, const TraceReadOptions& options,
                                            TraceReadStats* stats) {
  CheckOptions(options);
  const std::string format = options.format == "auto" ? DetectTraceFormat(path) : options.format;
  return std::make_unique<FileScanSource>(path, format, options, stats);
}

}  // namespace rc
