// A progress bar on stderr for long runs: redrawn in place when stderr is a terminal, otherwise one line per quarter
// so that logs stay short.
//
// It is also where the CLI's long loops stop on Ctrl-C / SIGTERM: update() and finish(), called on the thread that
// made the bar, throw needlekit::Interrupted once an interrupt was requested (core/interrupt.hpp). Calls from worker
// threads only draw (an exception must not leave a worker thread); their callers check interrupt_requested().
#pragma once
#include <string>
#include <thread>

namespace needlekit::cli {

class ProgressBar {
public:
  explicit ProgressBar(std::string label);
  ~ProgressBar();
  ProgressBar(const ProgressBar&) = delete;
  ProgressBar& operator=(const ProgressBar&) = delete;

  // Shows the fraction done, in [0, 1]; throws Interrupted as above.
  void update(double fraction);
  // Shows 100 % and ends the line; throws Interrupted as above.
  void finish();
  // Ends the bar's line so that a message can be printed on its own; the next update draws the bar again.
  void break_line();

private:
  std::string label_;
  bool terminal_;
  std::thread::id owner_ = std::this_thread::get_id();
  int shown_percent_ = -1;  // terminal: the last percentage drawn
  int shown_quarter_ = 0;   // log: the last quarter printed (1..4)
  bool line_open_ = false;  // terminal: the bar is drawn and the line not ended
};

}  // namespace needlekit::cli
