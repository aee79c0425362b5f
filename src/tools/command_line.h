// Copyright (c) 2026, obstacle_tracker developers. BSD-3-Clause.
//
// What the command-line tools share in reading their arguments with CLI11: --help prints the help
// on standard output and exits with 0; a usage error (unknown option, missing value, bad number)
// prints "TOOL: message" and the help on standard error and exits with the tool's usage-error
// code (2 for every tool). An option given twice keeps its last value.
#pragma once

#include <cstdio>
#include <iostream>
#include <exception>
#include <optional>
#include <string>

#include <CLI/CLI.hpp>

#include <opencv2/core/types.hpp>

namespace obstacle_tracker {
namespace tools {

// Call before adding options: the defaults every tool's options share.
inline void setToolDefaults(CLI::App& app) {
  app.option_defaults()->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
}

// Reports a usage error found after parsing (a value out of range, options that exclude each
// other) like the parser's own: "TOOL: message" and the help on standard error. Returns code.
inline int usageError(const CLI::App& app, const std::string& message, int code = 2) {
  std::cerr << app.get_name() << ": " << message << "\n" << app.help();
  return code;
}

// Parses the command line into app. Returns nothing when the tool is to run, otherwise the code
// to exit with: 0 after --help, usage_error_code after a usage error (both already printed).
inline std::optional<int> parseCommandLine(CLI::App& app, int argc, const char* const* argv,
                                           int usage_error_code = 2) {
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp&) {
    std::cout << app.help();
    return 0;
  } catch (const CLI::ParseError& e) {
    return usageError(app, e.what(), usage_error_code);
  }
  return std::nullopt;
}

// A check for unsigned 64-bit options (seeds): a decimal number within the type's range. CLI11
// alone would read a number past the range as the largest value, and 0x10 as hexadecimal.
inline CLI::Validator decimalUnsigned64() {
  return CLI::Validator(
      [](std::string& v) -> std::string {
        std::size_t used = 0;
        try {
          (void)std::stoull(v, &used);
        } catch (const std::exception&) {
          used = 0;
        }
        if (!v.empty() && used == v.size()) return std::string();
        return "wants a decimal integer that fits in 64 bits, got '" + v + "'";
      },
      "", "DECIMAL_UINT64");
}

// "WxH" (separator one of `separators`) as a size; false when v is not two integers so joined.
inline bool parseSize(const std::string& v, const char* separators, cv::Size* size) {
  const std::size_t x = v.find_first_of(separators);
  if (x == std::string::npos) return false;
  int w = 0, h = 0;
  if (!CLI::detail::lexical_cast(v.substr(0, x), w) || !CLI::detail::lexical_cast(v.substr(x + 1), h)) {
    return false;
  }
  *size = cv::Size(w, h);
  return true;
}

// Exit code after a tool's standard output is complete: 0, or 1 with "TOOL: error: cannot write
// the output" when it could not all be written (a full disk, a closed pipe). Output sits in the
// streams' buffers until the flush, so without this a failed write exits with 0.
inline int finishStandardOutput(const char* tool) {
  std::cout.flush();
  const bool stdio_ok = std::fflush(stdout) == 0 && !std::ferror(stdout);
  if (std::cout && stdio_ok) return 0;
  std::cerr << tool << ": error: cannot write the output\n";
  return 1;
}

}  // namespace tools
}  // namespace obstacle_tracker
