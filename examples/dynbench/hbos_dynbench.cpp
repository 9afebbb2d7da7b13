// hbos-dynbench: the dynamic-scene benchmark (see docs/results.md).
#include "dynbench/dynbench_command.hpp"

#include <iostream>

int main(int argc, char** argv) {
  return hbos::dynbench::run_dynbench_command(argc, argv, std::cout, std::cerr);
}
