#pragma once
// check(condition): a broken promise of the code under fuzzing. Says which (the condition and
// the line), then aborts, so that libFuzzer records the input as a finding.

#include <cstdio>
#include <cstdlib>

#define check(condition)                                                                        \
  ((condition) ? (void)0                                                                        \
               : (std::fprintf(stderr, "broken promise: %s (line %d)\n", #condition, __LINE__), \
                  std::abort()))
