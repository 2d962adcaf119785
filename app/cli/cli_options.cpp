// Option declarations the commands share (app/cli/cli_options.h).
#include "app/cli/cli_options.h"

#include <cstdlib>

#include "generators/params.h"

namespace sylva {

CLI::Option* add_float_option(CLI::App* app, const std::string& name, float& value, const std::string& help, float lo,
                              float hi) {
  // Read as CLI11 reads a float (strtold, then the float's range: 1e39 is infinite too). Text that
  // is no number at all is left to CLI11's conversion, which says so.
  const CLI::Validator finite(
      [](std::string& text) {
        char* end = nullptr;
        const float v = float(std::strtold(text.c_str(), &end));
        if (end == text.c_str() || *end) return std::string();
        return finite_refusal("", v);
      },
      "", "FINITE");
  CLI::Option* o = app->add_option(name, value, help)->check(finite);
  if (lo > -FLT_MAX || hi < FLT_MAX) o->check(CLI::Range(lo, hi));
  return o;
}

}  // namespace sylva
