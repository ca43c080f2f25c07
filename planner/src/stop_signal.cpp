#include "planner/stop_signal.hpp"

#include <csignal>

namespace planner {

namespace {

volatile std::sig_atomic_t g_signal = 0;

extern "C" void on_stop_signal(int sig)
{
  if (g_signal == 0) g_signal = sig;
  std::signal(sig, SIG_DFL);  // a second one kills at once (async-signal-safe)
}

}  // namespace

void install_stop_handlers()
{
  std::signal(SIGINT, on_stop_signal);
  std::signal(SIGTERM, on_stop_signal);
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
