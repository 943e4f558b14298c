// rill-trace's checks of option values: number and file-name validators for CLI11 that name
// the problem in words, and the parsers of --size and --grid, whose errors name the option.
#pragma once

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

namespace trace_cli {

// A number option's check: "'x' is not an integer", else whether it is out of [lo, hi].
CLI::Validator number_in(double lo, double hi, bool integer);
// A file option's check: an empty name would otherwise read as the option not given.
CLI::Validator file_name();
// A setting's check where an empty value would otherwise read as the option not given.
CLI::Validator non_empty();
// Adds non_empty() to every option of app and of its subcommands that takes a value, the
// positional ones too: CLI11 reads `--frames ''` as the option not given, a silent default.
void refuse_empty_values(CLI::App& app);

// "WxH" (1..16384 per side, at most 2^25 pixels) into w and h; throws rt::SceneError.
void parse_size(const std::string& s, int& w, int& h);
// `s` itself where parse_size takes it, else its error: with add_parsed_option, a bad size is
// a command-line error (exit status 2) for every command, as the command line is read.
std::string checked_size(const std::string& s);
// --grid: "auto" (or empty) is 0, else voxels per axis in 1..512; throws rt::SceneError.
int parse_grid(const std::string& s);
// "a,b,,c" -> {a, b, c}.
std::vector<std::string> split_list(const std::string& s);

// An option whose text `parse` turns into out's type (an enum, a size, a number or a word)
// while CLI11 reads the command line: the parse function's error (std::invalid_argument,
// rt::SceneError) becomes the command line's, with its message.
template <class T, class Parse>
CLI::Option* add_parsed_option(CLI::App* app, const std::string& name, T& out, Parse parse,
                               const std::string& description) {
  return app->add_option_function<std::string>(
      name,
      [&out, parse](const std::string& text) {
        try {
          out = parse(text);
        } catch (const CLI::Error&) {
          throw;
        } catch (const std::exception& e) {
          throw CLI::ValidationError(e.what());
        }
      },
      description);
}

}  // namespace trace_cli
