#include "core/atomic_output.hpp"

#include <unistd.h>
#include <fstream>
#include <stdexcept>
#include <system_error>

namespace cdem {

AtomicOutput::AtomicOutput(std::filesystem::path target) : target_(std::move(target)) {
  if (target_.has_parent_path() && !std::filesystem::exists(target_.parent_path()))
    std::filesystem::create_directories(target_.parent_path());
  temp_ = target_;
  temp_ += ".tmp" + std::to_string(::getpid());
}

AtomicOutput::~AtomicOutput() {
  if (!committed_) {
    std::error_code ec;
    std::filesystem::remove(temp_, ec);
  }
}

void AtomicOutput::commit() {
  std::filesystem::rename(temp_, target_);
  committed_ = true;
}

void write_text_atomically(const std::filesystem::path& target, const std::string& text) {
  AtomicOutput out(target);
  {
    std::ofstream f(out.temp_path(), std::ios::binary);
    f << text;
    f.flush();
    if (!f) throw std::runtime_error("cannot write " + target.string());
  }
  out.commit();
}

}  // namespace cdem
