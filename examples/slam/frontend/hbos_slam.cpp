// hbos-slam: the mini-SLAM front end with a reprojection-residual screen. All the work is in
// frontend/slam_command.cpp, where tests reach it.
#include "frontend/slam_command.hpp"

#include <iostream>

int main(int argc, char** argv) {
  return hbos::slam::run_slam_command(argc, argv, std::cout, std::cerr);
}
