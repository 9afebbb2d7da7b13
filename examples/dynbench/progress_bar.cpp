#include "dynbench/progress_bar.hpp"

#include <fmt/format.h>

#include <ostream>

namespace hbos::dynbench {

namespace {

std::string duration_text(double seconds) {
  const auto s = static_cast<long>(seconds + 0.5);
  return s >= 60 ? fmt::format("{}m{:02d}s", s / 60, s % 60) : fmt::format("{}s", s);
}

}  // namespace

ProgressBar::ProgressBar(std::ostream* out, bool terminal, int total)
    : out_(out), terminal_(terminal), total_(total), start_(std::chrono::steady_clock::now()) {}

void ProgressBar::status(const std::string& what) {
  const std::lock_guard<std::mutex> lock(mutex_);
  draw(what);
}

void ProgressBar::advance(const std::string& what) {
  const std::lock_guard<std::mutex> lock(mutex_);
  ++done_;
  if (what.rfind("resumed", 0) != 0) ++run_;
  draw(what);
}

void ProgressBar::finish() {
  const std::lock_guard<std::mutex> lock(mutex_);
  if (out_ != nullptr && terminal_) {
    *out_ << "\n";
    out_->flush();
  }
}

void ProgressBar::draw(const std::string& what) {
  if (out_ == nullptr) return;
  const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  constexpr int kWidth = 24;
  const int filled = total_ > 0 ? done_ * kWidth / total_ : kWidth;
  std::string bar(static_cast<std::size_t>(filled), '#');
  bar.resize(kWidth, '.');
  std::string left;
  if (run_ > 0 && done_ < total_) {
    left = ", ~" + duration_text(elapsed / run_ * (total_ - done_)) + " left";
  }
  std::string line = fmt::format("hbos-dynbench [{}] {}/{} cells {}{} | {}", bar, done_, total_,
                                 duration_text(elapsed), left, what);
  if (terminal_) {
    constexpr std::size_t kColumns = 118;
    if (line.size() > kColumns) line.resize(kColumns);
    line.resize(kColumns, ' ');
    *out_ << "\r" << line;
  } else {
    *out_ << line << "\n";
  }
  out_->flush();
}

}  // namespace hbos::dynbench
