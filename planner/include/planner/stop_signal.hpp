#pragma once
// SIGINT / SIGTERM as a request to stop: the handler only records the signal; long loops
// (rtlacam-sumo's tick loop, the lifelong runners) poll stop_signal() and end through
// their normal end path, so every output is written and SUMO is closed. The apps then
// exit 128 + signal (130 / 143). A second signal kills the process at once (the handler
// is reset to the default after the first), and so does SIGALRM kStopGraceS seconds after
// the first if the process is still there (blocked where nothing polls: a frozen SUMO).
namespace planner {

constexpr unsigned kStopGraceS = 30;

// Installs the handler for SIGINT and SIGTERM, except for one ignored at start (nohup, a
// background job of a script: it stays ignored).
void install_stop_handlers();

// 0, or the first stop signal received since install / reset.
int stop_signal();

// Sets the stop request as the handler would (tests; a caller that stops a run itself).
void request_stop(int sig);

// Clears a recorded request.
void reset_stop_signal();

// "SIGINT", "SIGTERM", or "a signal".
const char* signal_name(int sig);

}  // namespace planner
