// RADKIT_DCHECK(cond): an internal invariant, checked in Debug builds (NDEBUG not defined) and
// compiled out otherwise, so hot loops pay nothing in Release. A failed check is a bug in
// radkit, never bad input: input errors throw InputError with a message for the user.
#pragma once

#include <cstdio>
#include <cstdlib>

namespace radkit::detail {

[[noreturn]] inline void dcheckFailed(const char* file, int line, const char* condition) {
  std::fprintf(stderr, "%s:%d: internal check failed: %s\n", file, line, condition);
  std::fflush(stderr);
  std::abort();
}

}  // namespace radkit::detail

#ifndef NDEBUG
#define RADKIT_DCHECK(condition)      \
  ((condition) ? static_cast<void>(0) \
               : ::radkit::detail::dcheckFailed(__FILE__, __LINE__, #condition))
#else
// The condition stays compiled (its names are still checked) but is never evaluated.
#define RADKIT_DCHECK(condition) static_cast<void>(false && (condition))
#endif
