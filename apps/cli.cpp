#include "apps/cli.h"

#include <toml++/toml.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <set>
#include <sstream>
#include <vector>

#include "sim/error.h"
#include "sim/escaped.h"
#include "sim/format.h"

namespace gs::app {
namespace {

std::string scalar(const toml::node& n, const std::string& key) {
  if (auto s = n.value<std::string>()) return *s;
  if (n.is_boolean()) return *n.value<bool>() ? "true" : "false";
  if (n.is_integer()) return std::to_string(*n.value<std::int64_t>());
  if (n.is_floating_point()) return format_double(*n.value<double>());
  throw UserError("config file: key '" + key +
                  "' has a value that is not a number, string or bool");
}

// CLI11 2.1 reads config files for the top-level app only, and its TOML reader accepts almost
// anything; toml++ gives real syntax errors with a line number. Values from the file go into
// options the command line left unset, so flags win.
void apply_config_file(CLI::App& sub, const std::string& file) {
  toml::table root;
  try {
    root = toml::parse_file(file);
  } catch (const toml::parse_error& e) {
    throw UserError("--config " + file + ": malformed TOML at line " +
                    std::to_string(e.source().begin.line) + ": " + std::string(e.description()));
  }
  for (auto&& [k, node] : root) {
    const std::string key(k.str());
    CLI::Option* opt = sub.get_option_no_throw("--" + key);
    if (opt == nullptr) {  // a positional argument, such as movie's snapshot files
      opt = sub.get_option_no_throw(key);
      if (opt != nullptr && !opt->get_positional()) opt = nullptr;
    }
    if (opt == nullptr || key == "config")
      throw UserError("--config " + file + ": unknown key '" + key + "'");
    if (opt->count() > 0) continue;  // given on the command line
    // Input files named in the file are found from the file's own folder (settings_toml writes
    // them so), so that `--config DIR/movie.toml` works from any folder.
    const bool files = is_input_files(*opt);
    const std::filesystem::path from = std::filesystem::path(file).parent_path();
    auto value = [&](const toml::node& n) {
      std::string v = scalar(n, key);
      if (files && !v.empty() && std::filesystem::path(v).is_relative())
        v = (from / v).lexically_normal().string();
      return v;
    };
    if (auto* arr = node.as_array()) {
      if (arr->empty()) continue;  // the option's default: nothing
      for (auto&& el : *arr) opt->add_result(value(el));
    } else {
      opt->add_result(value(node));
    }
    try {
      opt->run_callback();
    } catch (const CLI::Error& e) {
      throw UserError("--config " + file + ": key '" + key + "': " + e.what());
    }
  }
}

// How a setting's values are typed in TOML: by what the option converts to (CLI11's INT, UINT,
// FLOAT, or anything else as text), not by how the text looks, so that a snapshot named 1e2
// stays the string "1e2".
enum class Kind { Integer, Float, Text };

Kind kind_of(const CLI::Option& opt) {
  const std::string full = opt.get_type_name();
  const std::string type = full.substr(0, full.find(':'));  // validators append ":what"
  if (type == "INT" || type == "UINT") return Kind::Integer;
  if (type == "FLOAT") return Kind::Float;
  return Kind::Text;
}

// One `key = value` line, formatted by toml++ with basic (escaped, one-line) strings. Floats
// are the exception: the linked toml++ writes 17 significant digits (0.1 as
// 0.10000000000000001), so they go in as format_double's shortest text that reads back to the
// same double, which is valid TOML (inf and nan included).
std::string toml_line(const std::string& key, Kind kind, const std::vector<std::string>& values,
                      bool list) {
  if (kind == Kind::Float) {
    std::string text;
    for (const std::string& v : values)
      text += (text.empty() ? "" : ", ") + format_double(std::strtod(v.c_str(), nullptr));
    // Our keys are flag names, bare TOML keys, so they need no quoting.
    GS_CHECK(key.find_first_not_of("abcdefghijklmnopqrstuvwxyz0123456789-_") == std::string::npos);
    return key + " = " + (list ? "[" + text + "]" : text) + "\n";
  }
  toml::array items;
  for (const std::string& v : values) {
    errno = 0;
    char* end = nullptr;
    const long long x = kind == Kind::Integer ? std::strtoll(v.c_str(), &end, 10) : 0;
    // An integer TOML cannot hold (a uint64 seed past 2^63) goes in as text, which the option
    // converts back when --config reads it.
    if (kind == Kind::Integer && errno == 0 && end != v.c_str() && *end == '\0')
      items.push_back(static_cast<std::int64_t>(x));
    else
      items.push_back(v);
  }
  toml::table t;
  if (list)
    t.insert(key, std::move(items));
  else
    t.insert(key, std::move(*items.get(0)));
  constexpr auto flags = toml::format_flags::allow_unicode_strings;
  std::ostringstream out;
  out << toml::toml_formatter(t, flags);
  return out.str() + "\n";
}

// A flag whose word the physics library parses (--initial, --kick-site, --medium): its one-line
// UserError becomes CLI11's validation error, so the flag exits 2 as any value out of range.
template <class T>
CLI::Option* add_word_option(CLI::App& sub, const std::string& name, T& target,
                             T (*parse)(const std::string&), const std::string& help) {
  return sub.add_option_function<std::string>(
      name,
      [&target, parse](const std::string& v) {
        try {
          target = parse(v);
        } catch (const UserError& e) {
          throw CLI::ValidationError(e.what());
        }
      },
      help);
}

}  // namespace

CLI::Option* input_files(CLI::Option* opt) {
  return opt->type_name(kInputFilesType);
}

bool is_input_files(const CLI::Option& opt) {
  return opt.get_type_name() == kInputFilesType;
}

std::string settings_toml(const CLI::App& sub, std::span<const std::string_view> left_out,
                          const std::filesystem::path& file_dir) {
  namespace fs = std::filesystem;
  // What says where and how to run, not what the results are.
  static const std::set<std::string> kLeftOut = {
      "--help", "--version", "--config", "--out", "--force", "--quiet", "--checkpoint-every"};
  std::string out;
  for (const CLI::Option* opt : sub.get_options()) {
    const std::string name = opt->get_name();
    if (kLeftOut.contains(name) ||
        std::find(left_out.begin(), left_out.end(), name) != left_out.end())
      continue;
    const std::string key = opt->get_positional() ? name : name.substr(2);
    if (opt->get_expected_max() == 0) {  // a flag: every one of ours defaults to false
      toml::table t;
      t.insert(key, opt->count() > 0 && opt->as<bool>());
      std::ostringstream line;
      line << toml::toml_formatter(t);
      out += line.str() + "\n";
      continue;
    }
    std::vector<std::string> values = opt->results();
    if (values.empty() && !opt->get_default_str().empty()) values = {opt->get_default_str()};
    if (values.empty()) continue;  // unset and without a default: the command decides
    if (is_input_files(*opt) && !file_dir.empty()) {
      // Relative to the file's folder; a path given absolute stays so (it works from anywhere).
      const fs::path base = fs::absolute(file_dir).lexically_normal();
      for (std::string& v : values)
        if (!v.empty() && fs::path(v).is_relative())
          v = fs::absolute(v).lexically_normal().lexically_relative(base).string();
    }
    const bool list = opt->get_items_expected_max() > 1 || values.size() > 1;
    out += toml_line(key, kind_of(*opt), values, list);
  }
  return out;
}

CLI::Validator whole_number() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        if (text.find_first_of("eE.") == std::string::npos) return {};
        char* end = nullptr;
        const double x = std::strtod(text.c_str(), &end);
        // 9.2e18 is where int64 ends; above it the digits would not be exact.
        if (end == text.c_str() || *end != '\0' || !std::isfinite(x) || x != std::floor(x) ||
            std::fabs(x) > 9.2e18)
          return text + " is not a whole number";
        text = std::to_string(static_cast<long long>(x));
        return {};
      },
      "", "whole number");
}

namespace {

std::string quoted(const std::string& text) {
  return "'" + escaped(text, 40) + "'";
}

// Why CLI11's conversion of `text` to a number of this kind would not give the number typed,
// or "" when it would (or when the text is no number at all: CLI11 refuses that itself).
std::string number_text_problem(const std::string& text, Kind kind, bool is_unsigned) {
  if (text.empty()) return "an empty value is not a number";
  const std::size_t first = text.find_first_not_of(" \t");
  const bool negative = first != std::string::npos && text[first] == '-';
  char* end = nullptr;
  errno = 0;
  if (kind == Kind::Integer) {
    if (is_unsigned && negative) return quoted(text) + " is negative; it must be 0 or more";
    if (is_unsigned)
      (void)std::strtoull(text.c_str(), &end, 0);
    else
      (void)std::strtoll(text.c_str(), &end, 0);
    if (errno == ERANGE && *end == '\0')
      return quoted(text) + " is out of range (more than 64 bits)";
    return {};
  }
  const double x = std::strtod(text.c_str(), &end);
  if (errno == ERANGE && *end == '\0' && (std::isinf(x) || x == 0))
    return quoted(text) + " is out of range (a double holds magnitudes from 5e-324 to 1.8e308)";
  return {};
}

// The bound of non_negative() and positive(): refuses numbers below (or at) 0, saying so.
CLI::Validator lower_bound(bool strict) {
  return CLI::Validator(
      [strict](std::string& text) -> std::string {
        char* end = nullptr;
        const double x = std::strtod(text.c_str(), &end);
        if (end == text.c_str() || *end != '\0') return {};  // not a number: CLI11 says so
        if (std::isnan(x)) return text + " is not a number";
        if (strict ? x > 0 : x >= 0) return {};
        return text + (strict ? " is not positive" : " is negative; it must be 0 or more");
      },
      strict ? "POSITIVE" : "NONNEGATIVE", strict ? "positive" : "non-negative");
}

}  // namespace

void check_number_text(CLI::App& app) {
  for (CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; }))
    for (CLI::Option* opt : sub->get_options()) {
      const Kind kind = kind_of(*opt);
      if (opt->get_expected_max() == 0 || kind == Kind::Text) continue;
      const bool is_unsigned = opt->get_type_name().rfind("UINT", 0) == 0;
      opt->check(CLI::Validator(
          [kind, is_unsigned](std::string& text) {
            return number_text_problem(text, kind, is_unsigned);
          },
          "", "number text"));
    }
}

CLI::Validator non_negative() { return lower_bound(false); }
CLI::Validator positive() { return lower_bound(true); }

CLI::Validator png_name() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        std::string tail = text.size() >= 4 ? text.substr(text.size() - 4) : "";
        std::transform(tail.begin(), tail.end(), tail.begin(),
                       [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
        if (tail == ".png") return {};
        return "'" + text + "' does not end in .png (only PNG is written)";
      },
      "FILE.png", "PNG name");
}

void parse_settings_file(CLI::App& app, const std::string& command,
                         const std::filesystem::path& file) {
  try {
    app.parse(std::vector<std::string>{file.string(), "--config", command});  // argv reversed
  } catch (const CLI::ParseError& e) {
    throw UserError(file.string() + ": " + e.what());
  }
}

void add_config_option(CLI::App& sub) {
  auto file = std::make_shared<std::string>();
  sub.add_option("--config", *file, "TOML file of flag = value lines; command-line flags win")
      ->check(CLI::ExistingFile);
  sub.parse_complete_callback([&sub, file] {
    if (!file->empty()) apply_config_file(sub, *file);
  });
}

void add_physics_options(CLI::App& sub, PhysicsConfig& c) {
  sub.add_option("--dim", c.dim, "Dimension d (1, 2 or 3)")->capture_default_str();
  sub.add_option("--particles", c.particles, "Number of particles N (2e6 is accepted)")
      ->transform(whole_number())
      ->capture_default_str();
  sub.add_option("--density", c.density, "Number density n (diameter 1)")->capture_default_str();
  sub.add_option("--restitution", c.restitution, "Coefficient of restitution r in [0, 1]")
      ->capture_default_str();
  sub.add_option("--cutoff", c.cutoff,
                 "delta: collisions with normal relative speed below it are elastic")
      ->capture_default_str();
  sub.add_option("--speed", c.speed, "Speed v0 of the kicked particle")->capture_default_str();
  sub.add_option("--seed", c.seed, "Master random seed")->capture_default_str();
  sub.add_option("--realisation", c.realisation, "Realisation index (selects random streams)")
      ->capture_default_str();
  sub.add_option("--t-max", c.t_max, "Final time in units of diameter / v0")->capture_default_str();
  add_word_option(sub, "--initial", c.initial, parse_initial,
                  "kick: one particle moves; thermal: a Maxwell gas")
      ->option_text("kick|thermal (kick)");
  add_word_option(sub, "--kick-site", c.kick_site, parse_kick_site,
                  "Which particle of the box is kicked: random or the one nearest the centre "
                  "(the unbounded medium, the same everywhere, kicks the one nearest its origin)")
      ->option_text("random|centre (random)");
  add_word_option(sub, "--medium", c.medium, parse_medium,
                  "box: N particles in a periodic box; unbounded: the gas at rest made where the "
                  "front arrives, N the most it may make (the default for kicks in 2D and 3D)")
      ->option_text("box|unbounded (unbounded for kicks in 2D, 3D)");
  sub.add_option("--temperature", c.temperature, "Temperature of the thermal initial state")
      ->capture_default_str();
  sub.add_option("--lattice", c.lattice, "1D only: lattice spacing a instead of random positions")
      ->capture_default_str();
}

void apply_medium_default(CLI::App& sub, PhysicsConfig& c, bool box) {
  CLI::Option* medium = sub.get_option("--medium");
  if (medium->count() > 0) return;
  c.medium = box ? Medium::Box : default_medium(c);
  medium->default_str(to_string(c.medium));
}

CLI::Option* add_output_options(CLI::App& sub, std::string& out, bool& force, bool& quiet) {
  auto* o = sub.add_option("--out", out, "Output folder (must not exist or be empty)");
  if (!out.empty()) o->capture_default_str();
  sub.add_flag("--force", force, "Write into an existing non-empty output folder");
  sub.add_flag("--quiet", quiet, "Nothing on stderr but errors");
  return o;
}

void add_checkpoint_minutes_option(CLI::App& sub, double& minutes) {
  auto* every = sub.add_option_function<double>(
      "--checkpoint-every", [&minutes](double seconds) { minutes = seconds / 60; },
      "Wall seconds between two writes of each running realisation's state (into "
      "realisations/in_flight), from which resume goes on after a kill (at least 50 times the "
      "last write's duration apart); 0: never");
  every->check(CLI::NonNegativeNumber)
      ->option_text("SECONDS (" + format_number(60 * minutes) + ")");
  sub.add_option("--checkpoint-minutes", minutes,
                 "The same in minutes (deprecated: use --checkpoint-every SECONDS)")
      ->capture_default_str()
      ->excludes(every);
}

void deprecated_checkpoint_minutes(const CLI::App& sub, bool quiet) {
  if (!quiet && sub.get_option("--checkpoint-minutes")->count() > 0 &&
      sub.get_option("--config")->count() == 0)
    std::fprintf(stderr,
                 "grainshock: note: --checkpoint-minutes is deprecated; use --checkpoint-every "
                 "SECONDS\n");
}

}  // namespace gs::app
