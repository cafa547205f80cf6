#include "apps/suggest.h"

#include <algorithm>
#include <cctype>
#include <numeric>

namespace gs::app {
namespace {

std::string did_you_mean(std::string_view word, const std::vector<std::string>& candidates) {
  const auto n = nearest(word, candidates);
  return n ? "; did you mean '" + *n + "'?" : "";
}

std::vector<std::string> subcommand_names(CLI::App& app) {
  std::vector<std::string> names;
  for (const CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; }))
    names.push_back(sub->get_name());
  return names;
}

std::vector<std::string> flag_names(const CLI::App& app) {
  std::vector<std::string> names;
  for (const CLI::Option* o : app.get_options()) {
    for (const std::string& l : o->get_lnames()) names.push_back("--" + l);
    for (const std::string& s : o->get_snames()) names.push_back("-" + s);
  }
  return names;
}

CLI::App* find_subcommand(CLI::App& app, const std::string& name) {
  for (CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; }))
    if (sub->check_name(name)) return sub;
  return nullptr;
}

bool is_number(const std::string& w) {
  return w.size() > 1 && (std::isdigit(static_cast<unsigned char>(w[1])) || w[1] == '.');
}

}  // namespace

std::size_t edit_distance(std::string_view a, std::string_view b) {
  // Three rows of the dynamic programme: the transposition looks two rows back.
  std::vector<std::size_t> back2(b.size() + 1), back(b.size() + 1), row(b.size() + 1);
  std::iota(back.begin(), back.end(), std::size_t{0});
  for (std::size_t i = 1; i <= a.size(); ++i) {
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t cost = a[i - 1] == b[j - 1] ? 0 : 1;
      row[j] = std::min({back[j] + 1, row[j - 1] + 1, back[j - 1] + cost});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
        row[j] = std::min(row[j], back2[j - 2] + 1);
    }
    std::swap(back2, back);
    std::swap(back, row);
  }
  return back[b.size()];
}

std::optional<std::string> nearest(std::string_view word,
                                   const std::vector<std::string>& candidates) {
  const std::string_view bare = word.substr(std::min(word.find_first_not_of('-'), word.size()));
  const std::size_t limit = std::max<std::size_t>(1, bare.size() / 3);
  std::optional<std::string> best;
  std::size_t best_d = limit + 1;
  for (const std::string& c : candidates) {
    const std::size_t d = edit_distance(word, c);
    if (d < best_d) best = c, best_d = d;
  }
  return best;
}

std::string explain_parse_error(CLI::App& app, const std::vector<std::string>& args,
                                const CLI::ParseError& error) {
  CLI::App* at = &app;  // the (sub)command the words so far have chosen
  for (const std::string& w : args) {
    if (w == "--") break;
    const bool flag = w.size() > 1 && w[0] == '-' && !is_number(w);
    const std::string where = at == &app ? "" : " for '" + at->get_name() + "'";
    if (flag) {
      const std::string name = w.substr(0, w.find('='));
      if (at->get_option_no_throw(name) == nullptr)
        return "unknown flag '" + name + "'" + where + did_you_mean(name, flag_names(*at));
      continue;
    }
    if (at != &app) continue;  // a value or a positional argument of the subcommand
    at = find_subcommand(app, w);
    if (at == nullptr)
      return "unknown subcommand '" + w + "'" + did_you_mean(w, subcommand_names(app));
  }
  if (at == &app && dynamic_cast<const CLI::RequiredError*>(&error) != nullptr) {
    std::string list;
    for (const std::string& n : subcommand_names(app)) list += (list.empty() ? "" : ", ") + n;
    return "a subcommand is required: " + list + " (grainshock --help)";
  }
  return error.what();
}

}  // namespace gs::app
