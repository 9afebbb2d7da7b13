#pragma once
// Running a command-line tool from a test as a user would (through the shell, output captured in
// files), and the small file helpers such tests need.

#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace hbos::test {

struct Run {
  int exit_code = -1;  // -1: killed by a signal
  std::string out;
  std::string err;
};

inline std::string slurp(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

inline void spit(const std::filesystem::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

/// A shell word: single-quoted, with embedded single quotes escaped.
inline std::string quoted(const std::string& word) {
  std::string out = "'";
  for (const char c : word) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

/// Runs `exe` with `args`, standard input from `input`, standard output and error captured in
/// `out` and `err` (files of the caller's choosing, so concurrent tests do not share them).
inline Run run_process(const std::string& exe, const std::vector<std::string>& args,
                       const std::string& input, const std::filesystem::path& out,
                       const std::filesystem::path& err) {
  std::string command = quoted(exe);
  for (const std::string& arg : args) command += " " + quoted(arg);
  command += " < " + quoted(input) + " > " + quoted(out.string()) + " 2> " + quoted(err.string());
  const int status = std::system(command.c_str());
  Run r;
  if (status != -1 && WIFEXITED(status)) r.exit_code = WEXITSTATUS(status);
  r.out = slurp(out);
  r.err = slurp(err);
  return r;
}

}  // namespace hbos::test
