#include "planner/stop_signal.hpp"

#include <unistd.h>

#include <csignal>
#include <initializer_list>

namespace planner {

namespace {

volatile std::sig_atomic_t g_signal = 0;

extern "C" void on_stop_signal(int sig)
{
  if (g_signal == 0) g_signal = sig;
  std::signal(sig, SIG_DFL);  // a second one kills at once (async-signal-safe)
  // A process blocked where no loop polls the flag (a TraCI read from a frozen SUMO, or one
  // waiting for the other clients of --num-clients) ignored the request for ever: SIGALRM
  // (default: terminate) ends it kStopGraceS later unless it has exited by then.
  std::signal(SIGALRM, SIG_DFL);
  ::alarm(kStopGraceS);
}

}  // namespace

void install_stop_handlers()
{
  // A signal ignored at start stays ignored (the Unix convention: nohup, `cmd &` in a
  // script without job control): the caller asked for the run not to be stopped by it.
  for (int sig : {SIGINT, SIGTERM})
    if (std::signal(sig, on_stop_signal) == SIG_IGN) std::signal(sig, SIG_IGN);
}

int stop_signal() { return g_signal; }

void request_stop(int sig) { g_signal = sig; }

void reset_stop_signal() { g_signal = 0; }

const char* signal_name(int sig)
{
  switch (sig) {
    case SIGINT: return "SIGINT";
    case SIGTERM: return "SIGTERM";
    default: return "a signal";
  }
}

}  // namespace planner
