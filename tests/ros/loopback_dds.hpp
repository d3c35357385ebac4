#pragma once
/// \file
/// The DDS setup every ros/ test shares: Cyclone on the loopback interface with unicast
/// discovery (CI machines may have no multicast, and loopback has none), on a domain id of this
/// process's own so that tests running side by side do not see each other.

#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <functional>
#include <string>
#include <thread>

namespace mote::ros::testing {

/// CYCLONEDDS_URI for loopback with unicast discovery among up to 30 participants.
inline const char* kLoopbackConfig =
    "<CycloneDDS><Domain id=\"any\"><General><Interfaces><NetworkInterface address=\"127.0.0.1\"/>"
    "</Interfaces><AllowMulticast>false</AllowMulticast></General><Discovery>"
    "<ParticipantIndex>auto</ParticipantIndex><MaxAutoParticipantIndex>30</MaxAutoParticipantIndex>"
    "<Peers><Peer address=\"127.0.0.1\"/></Peers></Discovery></Domain></CycloneDDS>";

/// Sets CYCLONEDDS_URI to the loopback config and returns a domain id (1-200) for this process.
inline int use_loopback_domain() {
  setenv("CYCLONEDDS_URI", kLoopbackConfig, 1);
  return 1 + static_cast<int>(getpid() % 200);
}

/// Polls `done` every 10 ms until it holds or `timeout` passes; returns its last value. Tests
/// check values, not timing: the timeout is generous for a loaded 2-core machine.
inline bool eventually(const std::function<bool()>& done,
                       std::chrono::milliseconds timeout = std::chrono::seconds(20)) {
  const auto end = std::chrono::steady_clock::now() + timeout;
  while (!done()) {
    if (std::chrono::steady_clock::now() > end) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return true;
}

}  // namespace mote::ros::testing
