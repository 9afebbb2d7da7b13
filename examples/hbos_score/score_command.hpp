#pragma once
/// \file
/// `hbos-score score MODEL DATA`: scores the rows of a CSV or .npy file with a saved model (PyOD's
/// `decision_function(X_test)`), writing one line per row: `score` for a default-mode model,
/// `score,label` for a PyOD-mode model (label 1 = outlier: score > the saved threshold_).

namespace hbos::cli {

/// Runs `hbos-score score` on its own arguments (argv[0] = "score"). Exit codes as fit_command.
int score_command(int argc, char** argv);

}  // namespace hbos::cli
