#include "common/atomic_file.h"

#include <cstdio>
#include <stdexcept>
#include <unistd.h>

namespace rc {

AtomicFile::AtomicFile(std::string path)
    : path_(std::move(path)), temp_path_(path_ + ".tmp" + std::to_string(::getpid())) {
  out_.open(temp_path_, std::ios::binary | std::ios::trunc);
  if (!out_) throw std::runtime_error("cannot open '" + path_ + "' for writing");
}

AtomicFile::~AtomicFile() {
  if (!committed_) {
    out_.close();
    std::remove(temp_path_.c_str());
  }
}

void AtomicFile::Commit() {
  out_.flush();
  if (!out_) throw std::runtime_error("write error on '" + path_ + "'");
  out_.close();
  if (std::rename(temp_path_.c_str(), path_.c_str()) != 0)
    throw std::runtime_error("cannot move output into place at '" + path_ + "'");
  committed_ = true;
}

}  // namespace rc
