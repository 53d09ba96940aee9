#include "app/option_checks.h"

#include <fmt/format.h>


#include "app/flag_names.h"
#include "core/input_error.h"

namespace chutelab::app {
namespace {

bool has_rule(CLI::Option* opt) {
  try {
    opt->get_validator("chutelab-rule");
    return true;
  } catch (const CLI::OptionNotFound&) {
    return false;
  }
}

bool plain_integer(const std::string& s) {
  std::size_t i = (!s.empty() && (s[0] == '-' || s[0] == '+')) ? 1 : 0;
  if (i == s.size()) return false;
  for (; i < s.size(); ++i)
    if (s[i] < '0' || s[i] > '9') return false;
  return true;
}

// The validator owns the flag's name: a rule made here for one option views it.
CLI::Validator validator(options::NumberRule rule, std::string description, std::string flag) {
  return CLI::Validator(
      [rule, flag = std::move(flag)](std::string& s) mutable -> std::string {
        rule.key = flag;
        try {
          const double v = rule.check(std::string_view(s));
          if (rule.whole && !plain_integer(s)) s = fmt::format("{:.0f}", v);
        } catch (const InputError& e) {
          return problem_said(e);
        }
        return {};
      },
      std::move(description), "chutelab-rule");
}

}  // namespace

CLI::Option* with_rule(CLI::Option* opt, const options::NumberRule& rule) {
  return opt->transform(validator(rule, rule.describe(), opt->get_name()));
}

void check_every_option(CLI::App& app) {
  for (CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; })) {
    for (CLI::Option* opt : sub->get_options([](CLI::Option*) { return true; })) {
      if (opt->get_type_size() == 0 || has_rule(opt)) continue;  // a flag, or checked already
      std::string type = opt->get_type_name();
      type = type.substr(0, type.find(':'));
      if (type == "FLOAT") {
        opt->check(validator(options::NumberRule{}, "", opt->get_name()));
      } else if (type == "INT") {
        options::NumberRule r;
        r.whole = true;
        opt->transform(validator(r, "", opt->get_name()));
      } else if (type == "UINT") {
        options::NumberRule r;
        r.whole = true;
        r.lo = 0.0;
        opt->transform(validator(r, "", opt->get_name()));
      } else {
        opt->check(CLI::Validator(
            [](std::string& s) -> std::string {
              return s.empty() ? std::string("is empty; give a value or leave the option out") : std::string();
            },
            "", "chutelab-non-empty"));
      }
    }
  }
}

}  // namespace chutelab::app
