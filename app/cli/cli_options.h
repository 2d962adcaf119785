// Option declarations the commands share (app/cli/cli.cpp, cli_textures.cpp).
#pragma once

#include <cfloat>
#include <string>

#include <CLI/CLI.hpp>

namespace sylva {

// A float option, its value checked as finite first (finite_refusal, generators/params.h) and then
// against [lo, hi]: CLI::Range alone passes NaN, since each comparison with it is false. Every float
// option of the CLI is declared through this, so "--seconds-per-step nan" is refused by name before
// anything is read or written (tests/cli/cli_numbers_test.cpp runs each FLOAT option of --help).
CLI::Option* add_float_option(CLI::App* app, const std::string& name, float& value, const std::string& help,
                              float lo = -FLT_MAX, float hi = FLT_MAX);

}  // namespace sylva
