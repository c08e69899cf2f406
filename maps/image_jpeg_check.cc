#include "maps/image_jpeg_check.h"

#include <csetjmp>
#include <cstdio>  // jpeglib.h uses FILE and size_t without including their headers
#include <fstream>
#include <iterator>

#include <jerror.h>
#include <jpeglib.h>

#include "common/input_error.h"
#include "maps/grid_size_limits.h"

namespace rc {
namespace {

// libjpeg's error manager, extended: the first error or warning is kept
// here, and libjpeg returns to the setjmp of the stage that was running.
// Plain data: longjmp skips no destructor of it.
struct QuietErrors {
  jpeg_error_mgr pub;  // first: libjpeg's cinfo->err points at it
  std::jmp_buf resume;
  const char* stage;  // the InputError's field
  int code;           // libjpeg's message code (jerror.h)
  char message[JMSG_LENGTH_MAX];
};

QuietErrors* ErrorsOf(j_common_ptr cinfo) { return reinterpret_cast<QuietErrors*>(cinfo->err); }

// Keeps the message instead of printing it.
void KeepMessage(j_common_ptr cinfo) {
  QuietErrors* errors = ErrorsOf(cinfo);
  (*cinfo->err->format_message)(cinfo, errors->message);
  errors->code = cinfo->err->msg_code;
}

// error_exit: back to the running stage's setjmp. Only libjpeg's C frames
// lie between, so nothing is left undestroyed.
[[noreturn]] void Stop(j_common_ptr cinfo) {
  (*cinfo->err->output_message)(cinfo);
  std::longjmp(ErrorsOf(cinfo)->resume, 1);
}

// A warning (level -1) is what OpenCV would let libjpeg print before it
// patched the image, so it stops the check too; trace messages (0 and up)
// are dropped.
void OnMessage(j_common_ptr cinfo, int level) {
  if (level < 0) Stop(cinfo);
}

// The two stages run libjpeg under a setjmp. They construct no C++ object,
// so a longjmp back into them skips no destructor. Each returns false when
// libjpeg stopped; `errors` says why.

// Through jpeg_read_header: SOI to the first scan header.
bool ReadHeader(j_decompress_ptr cinfo, QuietErrors* errors, const unsigned char* data, unsigned long size) {
  errors->stage = "header";
  if (setjmp(errors->resume)) return false;
  jpeg_create_decompress(cinfo);
  jpeg_mem_src(cinfo, data, size);
  jpeg_read_header(cinfo, TRUE);
  return true;
}

// Every scanline, into one row that is overwritten, then the end.
bool DecodeScans(j_decompress_ptr cinfo, QuietErrors* errors) {
  errors->stage = "scan data";
  if (setjmp(errors->resume)) return false;
  jpeg_start_decompress(cinfo);
  // libjpeg's own pool, freed by jpeg_destroy_decompress.
  JSAMPARRAY row = (*cinfo->mem->alloc_sarray)(reinterpret_cast<j_common_ptr>(cinfo), JPOOL_IMAGE,
                                               cinfo->output_width * cinfo->output_components, 1);
  while (cinfo->output_scanline < cinfo->output_height)
    if (jpeg_read_scanlines(cinfo, row, 1) == 0) break;  // only a suspending source returns 0; ours never does
  errors->stage = "EOI";
  jpeg_finish_decompress(cinfo);
  return true;
}

// jpeg_destroy_decompress on every way out, errors included; safe on a
// struct jpeg_create_decompress did not finish (it checks cinfo->mem).
struct DecompressGuard {
  jpeg_decompress_struct* cinfo;
  ~DecompressGuard() { jpeg_destroy_decompress(cinfo); }
};

InputError Refusal(const std::string& path, const jpeg_decompress_struct& cinfo, const QuietErrors& errors,
                   const std::string& data) {
  // Where libjpeg was reading from: its source advances a whole marker
  // segment item or MCU at a time (the decoders read ahead through local
  // copies), so the defect lies at or after this byte; extraneous bytes,
  // found at the marker after them, just before it.
  std::size_t from = 0;
  if (cinfo.src) {
    const auto* begin = reinterpret_cast<const unsigned char*>(data.data());
    const unsigned char* next = cinfo.src->next_input_byte;
    // (On running out, the source warns before it substitutes its fake EOI.)
    if (next >= begin && next <= begin + data.size()) from = static_cast<std::size_t>(next - begin);
  }
  const bool cut = errors.code == JWRN_JPEG_EOF || errors.code == JERR_INPUT_EOF || errors.code == JERR_INPUT_EMPTY;
  return InputError(path, 0, errors.stage,
                    std::string(cut ? "truncated: " : "") + errors.message + " (libjpeg was reading from byte " +
                        std::to_string(from) + " of " + std::to_string(data.size()) + ")");
}

}  // namespace

void CheckJpegImage(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, 0, "", "cannot open image file");
  const std::string data{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  if (in.bad()) throw InputError(path, 0, "", "cannot read image file");

  QuietErrors errors{};
  jpeg_decompress_struct cinfo{};
  cinfo.err = jpeg_std_error(&errors.pub);
  errors.pub.error_exit = Stop;
  errors.pub.emit_message = OnMessage;
  errors.pub.output_message = KeepMessage;
  const DecompressGuard guard{&cinfo};

  if (!ReadHeader(&cinfo, &errors, reinterpret_cast<const unsigned char*>(data.data()), data.size()))
    throw Refusal(path, cinfo, errors, data);
  // The grid has a cell per pixel. Checked before jpeg_start_decompress,
  // which allocates for the size (a progressive file: all its
  // coefficients, 2 bytes per pixel and component).
  CheckMapSize(path, 0, "header", static_cast<long>(cinfo.image_width), static_cast<long>(cinfo.image_height));
  // At 1/8 scale and in grey libjpeg still decodes every coefficient of
  // every block, where all its scan data warnings come from, but runs a
  // DC-only inverse DCT and converts no colour. (CMYK and YCCK cannot be
  // turned grey; they keep their own colour space.)
  cinfo.scale_num = 1;
  cinfo.scale_denom = 8;
  if (cinfo.jpeg_color_space == JCS_YCbCr) cinfo.out_color_space = JCS_GRAYSCALE;
  cinfo.do_fancy_upsampling = FALSE;
  cinfo.do_block_smoothing = FALSE;
  if (!DecodeScans(&cinfo, &errors)) throw Refusal(path, cinfo, errors, data);
}

}  // namespace rc
