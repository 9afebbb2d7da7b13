#pragma once
/// \file
/// `hbos-score fit DATA -o MODEL`: fits a model (default mode or PyOD's) on a CSV or .npy file
/// and saves it as a model file (docs/data_science.md), to be applied later by
/// `hbos-score score MODEL DATA` (score_command.hpp).

namespace hbos::cli {

/// Runs `hbos-score fit` on its own arguments (argv[0] = "fit"). Exit 0 on success, 2 on bad
/// options or input (the message names the file, line, field or value), 1 when the model file
/// cannot be written.
int fit_command(int argc, char** argv);

}  // namespace hbos::cli
