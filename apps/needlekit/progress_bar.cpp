#include "progress_bar.hpp"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <fmt/format.h>

#include "needlekit/core/interrupt.hpp"

namespace needlekit::cli {
namespace {
constexpr int kBarWidth = 40;
}

ProgressBar::ProgressBar(std::string label) : label_(std::move(label)), terminal_(::isatty(STDERR_FILENO) == 1) {}

ProgressBar::~ProgressBar() {
  if (line_open_) std::fputc('\n', stderr);  // an error message after an interrupted bar starts on its own line
}

void ProgressBar::update(double fraction) {
  if (std::this_thread::get_id() == owner_) throw_if_interrupted();
  const int percent = static_cast<int>(std::clamp(fraction, 0.0, 1.0) * 100);
  if (terminal_) {
    if (percent == shown_percent_) return;
    shown_percent_ = percent;
    const int filled = percent * kBarWidth / 100;
    fmt::print(stderr, "\r{} [{}{}] {:3d}%", label_, std::string(filled, '#'), std::string(kBarWidth - filled, '.'),
               percent);
    std::fflush(stderr);
    line_open_ = true;
    return;
  }
  const int quarter = percent / 25;
  if (quarter <= shown_quarter_) return;
  shown_quarter_ = quarter;
  fmt::print(stderr, "{}: {}%\n", label_, quarter * 25);
}

void ProgressBar::break_line() {
  if (!line_open_) return;
  std::fputc('\n', stderr);
  line_open_ = false;
  shown_percent_ = -1;
}

void ProgressBar::finish() {
  update(1.0);
  if (line_open_) {
    std::fputc('\n', stderr);
    line_open_ = false;
  }
}

}  // namespace needlekit::cli
