// Small helpers every library shares: a number in a message, seconds since a time point.
// Header-only, so solvers/ and bsdf/, which link nothing of radkit's, can use them.
#pragma once

#include <chrono>
#include <cstdio>
#include <string>

namespace radkit {

/// A number as printf's %.<digits>g: "0.5", "1e+06"; for messages and reports.
inline std::string formatNumber(double v, int digits = 6) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*g", digits, v);
  return buf;
}

/// One number through a printf format with one conversion ("%.1f s"); for messages.
inline std::string formatValue(const char* format, double v) {
  char buf[128];
  std::snprintf(buf, sizeof buf, format, v);  // NOLINT(cert-err33-c): the length is bounded
  return buf;
}

using Clock = std::chrono::steady_clock;

/// Wall seconds since t0.
inline double secondsSince(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

}  // namespace radkit
