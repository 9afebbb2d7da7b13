#pragma once
/// \file
/// An on/off setting on the command line: `--name` turns it on, `--no-name` off, and the help
/// says which the default is. CLI11 prints a negated flag as `--no-name{false}` (the value the
/// negation stores), which reads like the default and hides the real one.

#include <CLI/CLI.hpp>

#include <string>

namespace hbos::examples {

/// Adds `--<name>,!--no-<name>` bound to `value`, whose current value is the default the help
/// names ("... (default: on)").
inline CLI::Option* add_switch(CLI::App& app, const std::string& name, bool& value,
                               const std::string& description) {
  return app.add_flag("--" + name + ",!--no-" + name, value,
                      description + (value ? " (default: on)" : " (default: off)"));
}

}  // namespace hbos::examples
