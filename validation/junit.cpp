#include "validation/junit.h"

#include <cmath>
#include <fmt/format.h>
#include <map>
#include <tuple>

#include "core/markup.h"
#include "core/number.h"
#include "validation/output_files.h"

namespace chutelab::validation {
namespace {

std::string xml_escape(const std::string& s) { return markup_escape(s, Markup::xml_attribute); }
// Text content keeps its line breaks.
std::string xml_text(const std::string& s) { return markup_escape(s, Markup::xml_text); }

std::string unit_of(const Comparison& c) {
  return c.q ? std::string(info(*c.q).unit) : std::string("mm");
}

std::string describe(const Tolerance& t, const std::string& unit) {
  std::vector<std::string> parts;
  if (t.relative) parts.push_back(fmt::format("|relative error| <= {} %", message_number(100.0 * *t.relative)));
  if (t.normalised) parts.push_back(fmt::format("|E|/u_val <= {}", message_number(*t.normalised)));
  if (t.absolute) parts.push_back(fmt::format("|error| <= {} {}", message_number(*t.absolute), unit));
  return fmt::format("{}", fmt::join(parts, " and "));
}

std::string value(double si, double scale, const std::string& unit) {
  return fmt::format("{} {}", message_number(si * scale), unit);
}

// One line per compared value: what the CI view shows under the test case.
std::string detail(const Comparison& c) {
  const std::string u = unit_of(c);
  std::string o;
  if (c.boundary) o += fmt::format("x = {} mm: ", message_number(c.x * 1e3));
  o += fmt::format("measured {}", value(c.measured, c.scale, u));
  if (c.uncertainty) o += fmt::format(" (u_D {})", value(*c.uncertainty, c.scale, u));
  o += fmt::format(", predicted {}", value(*c.predicted, c.scale, u));
  if (c.prediction_uncertainty) o += fmt::format(" (u_num {})", value(*c.prediction_uncertainty, c.scale, u));
  o += fmt::format(", error {}", value(c.error(), c.scale, u));
  if (auto rel = c.relative_error(); rel && !is_height(c.quantity))
    o += fmt::format(", relative error {:+.2f} %", 100.0 * *rel);
  if (auto z = c.normalised_error()) o += fmt::format(", E/u_val {:+.2f}", *z);
  if (c.verdict.checked) o += c.verdict.passed ? ": within tolerance" : fmt::format(": FAILED, {}", c.verdict.limit);
  return o;
}

struct Case {
  std::string condition, quantity;
  std::vector<const Comparison*> values;
};

struct Suite {
  std::string model;
  std::vector<Case> cases;
  int failures = 0, skipped = 0;
};

// One suite per model, one case per condition x quantity with a tolerance.
std::vector<Suite> suites_of(const ValidationResult& r, const Tolerances* tol) {
  std::vector<Suite> suites;
  for (const auto& m : r.models) {
    Suite s;
    s.model = m;
    std::map<std::pair<std::string, std::string>, std::size_t> index;
    for (const auto& c : r.comparisons) {
      if (c.model != m || !tol || !tol->find(c.model, c.quantity)) continue;
      auto [it, fresh] = index.emplace(std::pair{c.condition, c.quantity}, s.cases.size());
      if (fresh) s.cases.push_back({c.condition, c.quantity, {}});
      s.cases[it->second].values.push_back(&c);
    }
    if (!s.cases.empty()) suites.push_back(std::move(s));
  }
  return suites;
}

// `judged` false: every case <skipped>, its message what the values would have given.
std::string suite_xml(Suite& s, const ValidationResult& r, const Tolerances& tol, const std::string& dataset,
                      bool judged, const std::string& label, int& outside) {
  std::string cases;
  const std::string klass = fmt::format("chutelab.{}.{}{}", dataset, xml_escape(s.model),
                                        judged ? std::string() : "." + xml_escape(label));
  for (const auto& k : s.cases) {
    const Tolerance& t = *tol.find(s.model, k.quantity);
    const std::string unit = unit_of(*k.values.front());
    const std::string name = fmt::format("{} {}", k.condition, k.quantity);
    cases += fmt::format("    <testcase name=\"{}\" classname=\"{}\">\n", xml_escape(name), klass);
    std::vector<const Comparison*> predicted, failed;
    for (const Comparison* c : k.values) {
      if (!c->predicted) continue;
      predicted.push_back(c);
      if (c->verdict.checked && !c->verdict.passed) failed.push_back(c);
    }
    const std::string limit = describe(t, unit);
    std::string lines;
    for (const Comparison* c : predicted) lines += detail(*c) + "\n";
    // The message carries the worst value; the text lists every compared value.
    std::string msg;
    if (!failed.empty()) {
      const Comparison* worst = failed.front();
      for (const Comparison* c : failed)
        if (std::abs(c->error()) > std::abs(worst->error())) worst = c;
      msg = fmt::format("{}: measured {}, predicted {}, error {}; limit {}", k.quantity,
                        value(worst->measured, worst->scale, unit), value(*worst->predicted, worst->scale, unit),
                        value(worst->error(), worst->scale, unit), worst->verdict.limit);
      if (worst->boundary) msg += fmt::format(" at x = {} mm", message_number(worst->x * 1e3));
      if (failed.size() > 1) msg += fmt::format(" ({} of {} points outside)", failed.size(), predicted.size());
    }
    if (!judged) {
      ++s.skipped;
      if (!failed.empty()) ++outside;
      const std::string would = predicted.empty() ? fmt::format("{} does not predict {}", s.model, k.quantity)
                                : failed.empty()  ? std::string("within tolerance")
                                                  : "outside tolerance: " + msg;
      cases += fmt::format("      <skipped message=\"{}\"/>\n",
                           xml_escape(fmt::format("not judged ({}, beside the acceptance): {}", label, would)));
      if (!predicted.empty())
        cases += fmt::format("      <system-out>tolerance: {}\n{}</system-out>\n", xml_text(limit), xml_text(lines));
    } else if (predicted.empty()) {
      ++s.skipped;
      cases += fmt::format("      <skipped message=\"{}\"/>\n",
                           xml_escape(fmt::format("{} does not predict {}; tolerance {} not checked", s.model,
                                                  k.quantity, limit)));
    } else if (!failed.empty()) {
      ++s.failures;
      cases += fmt::format("      <failure message=\"{}\" type=\"tolerance\">tolerance: {}\n{}</failure>\n",
                           xml_escape(msg), xml_text(limit), xml_text(lines));
    } else {
      cases += fmt::format("      <system-out>tolerance: {}\n{}</system-out>\n", xml_text(limit), xml_text(lines));
    }
    cases += "    </testcase>\n";
  }
  const int n = static_cast<int>(s.cases.size());
  std::string body = fmt::format(
      "  <testsuite name=\"{}.{}{}\" tests=\"{}\" failures=\"{}\" errors=\"0\" skipped=\"{}\">\n", dataset,
      xml_escape(s.model), judged ? std::string() : "." + xml_escape(label), n, s.failures, s.skipped);
  body += "    <properties>\n";
  body += fmt::format("      <property name=\"dataset\" value=\"{}\"/>\n", dataset);
  body += fmt::format("      <property name=\"model\" value=\"{}\"/>\n", xml_escape(s.model));
  body += fmt::format("      <property name=\"tolerances\" value=\"{}\"/>\n", xml_escape(tol.file()));
  body += fmt::format("      <property name=\"judged\" value=\"{}\"/>\n",
                      judged ? "yes: the acceptance" : "no: beside the acceptance");
  for (const auto& e : r.effects)
    body += fmt::format("      <property name=\"effect\" value=\"{}\"/>\n", xml_escape(e));
  return body + "    </properties>\n" + cases + "  </testsuite>\n";
}

}  // namespace

std::string junit_xml(const ValidationResult& r, const Tolerances* tol, JunitSummary* out_summary,
                      const ValidationResult* beside, const std::string& beside_label) {
  JunitSummary sum;
  // The folder the user gave, as the report's title and validate's first line name it.
  const std::string dataset = xml_escape(r.dataset_folder.empty() ? r.dataset_name : r.dataset_folder);
  std::string body;
  int unused = 0;
  for (auto& s : suites_of(r, tol)) {
    body += suite_xml(s, r, *tol, dataset, true, "", unused);
    sum.tests += static_cast<int>(s.cases.size());
    sum.failures += s.failures;
    sum.skipped += s.skipped;
  }

  // Nothing checked is not a pass: one test case in error says why.
  if (sum.tests == sum.skipped) {
    const std::string why =
        !tol ? "no tolerances given (the dataset has no tolerances.toml and none were given): nothing was checked"
             : fmt::format("no tolerance in {} applies to a value these models predict ({}): nothing was checked",
                           tol->file(), fmt::format("{}", fmt::join(r.models, ", ")));
    ++sum.tests;
    ++sum.errors;
    body += fmt::format(
        "  <testsuite name=\"{}\" tests=\"1\" failures=\"0\" errors=\"1\" skipped=\"0\">\n"
        "    <testcase name=\"acceptance\" classname=\"chutelab.{}\">\n"
        "      <error message=\"{}\" type=\"nothing-checked\"/>\n"
        "    </testcase>\n"
        "  </testsuite>\n",
        dataset, dataset, xml_escape(why));
  }
  if (beside && tol)
    for (auto& s : suites_of(*beside, tol)) {
      body += suite_xml(s, *beside, *tol, dataset, false, beside_label, sum.beside_outside);
      sum.beside += static_cast<int>(s.cases.size());
    }
  if (out_summary) *out_summary = sum;
  return fmt::format(
             "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
             "<testsuites name=\"chutelab validate {}\" tests=\"{}\" failures=\"{}\" errors=\"{}\" "
             "skipped=\"{}\">\n",
             dataset, sum.tests + sum.beside, sum.failures, sum.errors, sum.skipped + sum.beside) +
         body + "</testsuites>\n";
}

}  // namespace chutelab::validation
