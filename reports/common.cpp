#include "reports/common.h"

#include <algorithm>
#include <cmath>
#include <array>
#include <fmt/format.h>

namespace chutelab::reports {

std::string ConditionRow::speed_label() const {
  return station ? fmt::format("{:.4g} m/s", station->belt_speed) : std::string();
}

std::string ConditionRow::flow_label() const {
  return station ? fmt::format("{:.4g} t/h", station->mass_flow * 3.6) : std::string();
}

namespace {
// Okabe & Ito's colour-blind-safe palette; the measured data are always near-black.
constexpr std::array<std::string_view, 6> kColours = {"#0072B2", "#D55E00", "#009E73",
                                                      "#CC79A7", "#E69F00", "#56B4E9"};
constexpr std::array<Shape, 6> kShapes = {Shape::circle,  Shape::square,        Shape::triangle_up,
                                          Shape::diamond, Shape::triangle_down, Shape::cross};

std::size_t model_index(const std::vector<std::string>& models, const std::string& m) {
  return static_cast<std::size_t>(std::find(models.begin(), models.end(), m) - models.begin());
}
}  // namespace

std::string Context::colour(const std::string& model) const {
  return std::string(kColours[model_index(models, model) % kColours.size()]);
}

Shape Context::shape(const std::string& model) const {
  return kShapes[model_index(models, model) % kShapes.size()];
}

Context make_context(const ReportInput& in) {
  Context c{in, {}, {}, 0, {}};
  c.models = in.baseline->models;
  if (in.with_effects)
    for (const auto& m : in.with_effects->models)
      if (std::find(c.models.begin(), c.models.end(), m) == c.models.end()) c.models.push_back(m);

  // Conditions as the results list them (the dataset's order), then sorted for display.
  // (Hash look-ups: a report of 10 000 conditions must not cost their square.)
  std::vector<std::string> names;
  std::unordered_set<std::string> seen;
  auto add = [&](const std::string& n) {
    if (seen.insert(n).second) names.push_back(n);
  };
  for (const auto& p : in.baseline->predictions) add(p.condition);
  for (const auto& cmp : in.baseline->comparisons) add(cmp.condition);
  std::unordered_map<std::string, const Station*> stations;
  if (in.dataset)
    for (const auto& s : in.dataset->stations) stations.emplace(s.condition, &s);
  for (const auto& n : names) {
    const auto it = stations.find(n);
    c.conditions.push_back({n, it == stations.end() ? nullptr : it->second});
  }
  if (c.conditions.size() > kMaxShownConditions) {
    // The worst |E/u| (or |relative error| without an uncertainty) of each condition, before and
    // after effects: the conditions a reader must see are those where the models fail most.
    std::unordered_map<std::string, double> worst;
    for (const auto* r : {in.baseline, in.with_effects})
      if (r)
        for (const auto& cmp : r->comparisons) {
          double m = 0.0;
          if (auto z = cmp.normalised_error()) m = std::abs(*z);
          else if (auto e = cmp.relative_error()) m = std::abs(*e);
          if (!std::isfinite(m)) m = 1e300;
          auto& w = worst[cmp.condition];
          w = std::max(w, m);
        }
    std::vector<std::size_t> order(c.conditions.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
      return worst[c.conditions[a].name] > worst[c.conditions[b].name];
    });
    order.resize(kMaxShownConditions);
    std::sort(order.begin(), order.end());  // back to the dataset's order before the display sort
    std::vector<ConditionRow> kept;
    for (std::size_t i : order) kept.push_back(c.conditions[i]);
    c.conditions_left_out = c.conditions.size() - kept.size();
    c.conditions = std::move(kept);
  }
  std::stable_sort(c.conditions.begin(), c.conditions.end(),
                   [](const ConditionRow& a, const ConditionRow& b) {
                     if (!a.station || !b.station) return a.station && !b.station;
                     if (a.station->belt_speed != b.station->belt_speed)
                       return a.station->belt_speed < b.station->belt_speed;
                     return a.station->mass_flow < b.station->mass_flow;
                   });
  for (std::size_t i = 0; i < c.conditions.size(); ++i) c.slot.emplace(c.conditions[i].name, i);
  return c;
}

QuantityName quantity_name(std::string_view n) {
  QuantityName out;
  out.name = std::string(n);
  if (auto q = parse_quantity(n)) {
    const auto& i = info(*q);
    out.symbol = std::string(i.symbol);
    out.label = std::string(i.label);
    out.unit = std::string(i.unit);
    out.scale = i.to_boundary;
    out.q = q;
    return out;
  }
  // "trajectory_<boundary>_y_mm": the harness's name for measured stream points.
  constexpr std::string_view pre = "trajectory_", post = "_y_mm";
  if (n.starts_with(pre) && n.ends_with(post) && n.size() > pre.size() + post.size()) {
    const auto b = n.substr(pre.size(), n.size() - pre.size() - post.size());
    out.symbol = fmt::format("y_{}", b);
    out.label = fmt::format("{} stream boundary, y", b);
    out.unit = "mm";
    out.scale = 1e3;
    return out;
  }
  for (const auto& [pq, scale] : validation::plate_quantities())
    if (n == pq) {
      out.symbol = pq.substr(0, pq.rfind('_'));
      out.label = "plate map: " + out.symbol;
      out.unit = pq.substr(pq.find('_', pq.find('_') + 1) + 1);
      out.scale = scale;
      return out;
    }
  out.symbol = out.name;
  out.label = out.name;
  return out;
}

std::vector<std::string> compared_quantities(const validation::ValidationResult& r) {
  std::vector<std::string> order;
  for (Quantity q : kAllQuantities) order.emplace_back(name(q));
  for (Boundary b : kAllBoundaries) order.push_back(fmt::format("trajectory_{}_y_mm", name(b)));
  std::vector<std::string> seen;
  for (const auto& c : r.comparisons)
    if (std::find(seen.begin(), seen.end(), c.quantity) == seen.end()) seen.push_back(c.quantity);
  std::vector<std::string> out;
  for (const auto& q : order)
    if (std::find(seen.begin(), seen.end(), q) != seen.end()) out.push_back(q);
  for (const auto& q : seen)  // anything the vocabulary does not know yet goes last
    if (std::find(order.begin(), order.end(), q) == order.end()) out.push_back(q);
  return out;
}

Lookup::Lookup(const validation::ValidationResult& r) {
  for (const auto& c : r.comparisons) map_[{c.condition, c.model, c.quantity}].push_back(&c);
}

const validation::Comparison* Lookup::one(const std::string& condition, const std::string& model,
                                          const std::string& quantity) const {
  const auto& v = all(condition, model, quantity);
  return v.empty() ? nullptr : v.front();
}

const std::vector<const validation::Comparison*>& Lookup::all(const std::string& condition,
                                                              const std::string& model,
                                                              const std::string& quantity) const {
  auto it = map_.find({condition, model, quantity});
  return it == map_.end() ? none_ : it->second;
}

const validation::Measurement* find_measurement(const validation::Dataset& d,
                                                const std::string& condition, Quantity q) {
  for (const auto& m : d.measurements)
    if (m.condition == condition && m.quantity == q) return &m;
  return nullptr;
}

// ---- Table rendering ---------------------------------------------------------------------------

std::string table_html(const Table& t) {
  std::string o = "<div class=\"table-wrap\">\n<table class=\"data\"";
  if (!t.id.empty()) o += fmt::format(" id=\"{}\"", esc(t.id));
  o += ">\n";
  if (!t.caption.empty()) o += fmt::format("<caption>{}</caption>\n", esc(t.caption));
  o += "<thead>\n";
  const bool groups = std::any_of(t.columns.begin(), t.columns.end(),
                                  [](const Column& c) { return !c.group.empty(); });
  if (groups) {
    o += "<tr class=\"group\">";
    for (std::size_t i = 0; i < t.columns.size();) {
      std::size_t j = i + 1;
      while (j < t.columns.size() && t.columns[j].group == t.columns[i].group) ++j;
      const auto& c = t.columns[i];
      const std::string g = c.group_html.empty() ? esc(c.group) : c.group_html;
      if (j - i > 1) o += fmt::format("<th colspan=\"{}\">{}</th>", j - i, g);
      else o += fmt::format("<th>{}</th>", g);
      i = j;
    }
    o += "</tr>\n";
  }
  o += "<tr>";
  for (const auto& c : t.columns)
    o += fmt::format("<th{}>{}</th>", c.left ? " class=\"left\"" : "", c.html.empty() ? esc(c.text) : c.html);
  o += "</tr>\n</thead>\n<tbody>\n";
  for (const auto& row : t.rows) {
    o += "<tr>";
    for (const auto& cell : row) {
      std::string cls = cell.left ? "left" : "num";
      if (cell.fail) cls += " fail";
      else if (cell.beyond) cls += " beyond";
      std::string body = cell.html.empty() ? esc(cell.text) : cell.html;
      if (cell.strong) body = "<strong>" + body + "</strong>";
      if (cell.fail) body += fmt::format(" <span class=\"mark\">{}</span>", kFailMark);
      o += fmt::format("<td class=\"{}\"{}>{}</td>", cls,
                       cell.tip.empty() ? "" : fmt::format(" title=\"{}\"", esc(cell.tip)), body);
    }
    o += "</tr>\n";
  }
  o += "</tbody>\n</table>\n</div>\n";
  for (const auto& n : t.notes) o += fmt::format("<p class=\"table-note\">{}</p>\n", esc(n));
  return o;
}

std::string table_markdown(const Table& t) {
  std::string o;
  if (!t.caption.empty()) o += fmt::format("**{}**\n\n", md_esc(t.caption));
  o += "|";
  for (const auto& c : t.columns)
    o += fmt::format(" {} |", md_esc(c.group.empty() || !c.group_in_markdown ? c.text
                                                                              : fmt::format("{} {}", c.group, c.text)));
  o += "\n|";
  for (const auto& c : t.columns) o += c.left ? "---|" : "---:|";
  o += "\n";
  bool any_fail = false, any_beyond = false;
  for (const auto& row : t.rows) {
    o += "|";
    for (std::size_t k = 0; k < row.size(); ++k) {
      const auto& cell = row[k];
      std::string body = md_esc(cell.text);
      if (cell.fail) {
        body = fmt::format("**{} {}**", body, kFailMark);
        any_fail = true;
      } else if (cell.strong) {
        body = fmt::format("**{}**", body);
      }
      if (cell.beyond && !cell.fail) {
        body += std::string(" ") + std::string(kBeyondMark);
        any_beyond = true;
      }
      o += fmt::format(" {} |", body);
    }
    o += "\n";
  }
  o += "\n";
  for (const auto& n : t.notes) o += md_esc(n) + "\n\n";
  if (any_fail)
    o += fmt::format("{} = outside tolerance; every such value, with its limit, is listed under \"Outside "
                     "tolerance\".\n\n",
                     kFailMark);
  if (any_beyond)
    o += fmt::format("{} = the value is more than 2 u_val from the measurement (|E/u_val| > 2).\n\n", kBeyondMark);
  return o;
}

std::optional<Table> merge_before_after(const Table& before, const Table& after, std::string_view before_label,
                                        std::string_view after_label, std::string_view what) {
  const auto& bc = before.columns;
  if (bc.size() != after.columns.size() || before.rows.size() != after.rows.size() || before.rows.empty())
    return std::nullopt;
  for (std::size_t j = 0; j < bc.size(); ++j)
    if (bc[j].group != after.columns[j].group || bc[j].text != after.columns[j].text) return std::nullopt;
  for (std::size_t i = 0; i < before.rows.size(); ++i) {
    const auto &rb = before.rows[i], &ra = after.rows[i];
    if (rb.size() != bc.size() || ra.size() != bc.size()) return std::nullopt;
    for (std::size_t j = 0; j < std::min(before.key_columns, bc.size()); ++j)
      if (rb[j].text != ra[j].text) return std::nullopt;
  }
  Table t;
  t.id = before.id;
  t.caption = before.caption + " — before and after";
  t.key_columns = before.key_columns;
  t.rows.resize(before.rows.size());
  bool split = false;
  for (std::size_t j = 0; j < bc.size(); ++j) {
    bool same = true;
    for (std::size_t i = 0; i < before.rows.size() && same; ++i) {
      const Cell &b = before.rows[i][j], &a = after.rows[i][j];
      same = b.text == a.text && b.fail == a.fail;
    }
    if (same) {
      t.columns.push_back(bc[j]);
      for (std::size_t i = 0; i < before.rows.size(); ++i) t.rows[i].push_back(before.rows[i][j]);
      continue;
    }
    split = true;
    for (const auto* side : {&before, &after}) {
      Column col = bc[j];
      const std::string_view label = side == &before ? before_label : after_label;
      col.text += fmt::format(" {}", label);
      if (!col.html.empty()) col.html += fmt::format(" {}", esc(label));
      t.columns.push_back(std::move(col));
      for (std::size_t i = 0; i < before.rows.size(); ++i) t.rows[i].push_back(side->rows[i][j]);
    }
  }
  for (const auto* side : {&before, &after})
    for (const auto& n : side->notes)
      if (std::find(t.notes.begin(), t.notes.end(), n) == t.notes.end()) t.notes.push_back(n);
  if (split)
    t.notes.push_back(fmt::format("{}; a column marked neither \"{}\" nor \"{}\" is the same in both.", what,
                                  before_label, after_label));
  return t;
}

}  // namespace chutelab::reports
