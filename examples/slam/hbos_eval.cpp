// hbos-eval: trajectory evaluation with the TUM RGB-D benchmark's conventions (ATE, Sim(3) ATE,
// RPE, share tracked, plots). All the work is in eval/eval_command.cpp, where tests reach it.
#include "eval/eval_command.hpp"

#include <iostream>

int main(int argc, char** argv) {
  return hbos::slam::run_eval_command(argc, argv, std::cout, std::cerr);
}
