#pragma once
// The outer frame of a tool's main(): the exit codes every hbos tool documents (0 done, 2 bad
// input or settings, 1 anything else that failed), with the message prefixed by the tool's name.

#include <hbos/error.hpp>

#include <exception>
#include <iostream>
#include <string_view>

namespace hbos::examples {

/// Calls `run()` (returning the exit code) and turns an escaping exception into a message on
/// stderr and exit 2 (hbos::InvalidArgument: bad input) or 1 (any other std::exception).
template <class Run>
int run_tool(std::string_view name, Run&& run) {
  try {
    return run();
  } catch (const hbos::InvalidArgument& e) {
    std::cerr << name << ": " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << name << ": " << e.what() << "\n";
    return 1;
  }
}

}  // namespace hbos::examples
