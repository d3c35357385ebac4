#include "signals.hpp"

#include <atomic>
#include <csignal>

namespace mote::tool {
namespace {

// Lock-free atomics are async-signal-safe (C++17 [support.signal]).
std::atomic<bool> g_stop{false};
std::atomic<bool> g_usr1{false};
std::atomic<bool> g_usr2{false};

extern "C" void on_signal(int signal) {
  if (signal == SIGUSR1) {
    g_usr1.store(true);
  } else if (signal == SIGUSR2) {
    g_usr2.store(true);
  } else {
    g_stop.store(true);
  }
}

}  // namespace

void install_signal_flags() {
  struct sigaction action {};
  action.sa_handler = on_signal;
  sigemptyset(&action.sa_mask);
  for (const int s : {SIGINT, SIGTERM, SIGUSR1, SIGUSR2}) sigaction(s, &action, nullptr);
}

bool stop_signalled() noexcept { return g_stop.load(); }
bool take_usr1() noexcept { return g_usr1.exchange(false); }
bool take_usr2() noexcept { return g_usr2.exchange(false); }

}  // namespace mote::tool
