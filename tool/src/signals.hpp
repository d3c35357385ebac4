#pragma once
// The signals a long-running command (mote node, mote play) answers: SIGINT and SIGTERM end it,
// SIGUSR1 and SIGUSR2 are requests to a running node. The handlers only set flags; the command's
// own loop reads them.

namespace mote::tool {

/// Installs the handlers (once per process).
void install_signal_flags();
/// SIGINT or SIGTERM arrived.
[[nodiscard]] bool stop_signalled() noexcept;
/// SIGUSR1 arrived since the last call (cleared by reading).
[[nodiscard]] bool take_usr1() noexcept;
/// SIGUSR2 arrived since the last call (cleared by reading).
[[nodiscard]] bool take_usr2() noexcept;

}  // namespace mote::tool
