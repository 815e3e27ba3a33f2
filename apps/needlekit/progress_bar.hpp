// A progress bar on stderr for long runs: redrawn in place when stderr is a terminal, otherwise one line per quarter
// so that logs stay short.
#pragma once
#include <string>

namespace needlekit::cli {

class ProgressBar {
public:
  explicit ProgressBar(std::string label);
  ~ProgressBar();
  ProgressBar(const ProgressBar&) = delete;
  ProgressBar& operator=(const ProgressBar&) = delete;

  // Shows the fraction done, in [0, 1].
  void update(double fraction);
  // Shows 100 % and ends the line.
  void finish();

private:
  std::string label_;
  bool terminal_;
  int shown_percent_ = -1;  // terminal: the last percentage drawn
  int shown_quarter_ = 0;   // log: the last quarter printed (1..4)
  bool line_open_ = false;  // terminal: the bar is drawn and the line not ended
};

}  // namespace needlekit::cli
