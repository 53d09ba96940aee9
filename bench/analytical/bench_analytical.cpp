// Times the analytical path the way users meet it: one condition as `estimate` computes it, a
// whole `validate` of a dataset, and a whole `diagnose` (all singles and pairs). Reports medians.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <vector>

#include "analytical/transfer_station.h"
#include "validation/dataset.h"
#include "validation/diagnosis.h"
#include "validation/harness.h"

using namespace chutelab;
using Clock = std::chrono::steady_clock;

template <class F>
double median_seconds(int repeats, F f) {
  std::vector<double> t;
  for (int i = 0; i < repeats; ++i) {
    const auto a = Clock::now();
    f();
    t.push_back(std::chrono::duration<double>(Clock::now() - a).count());
  }
  std::sort(t.begin(), t.end());
  return t[t.size() / 2];
}

int main(int argc, char** argv) {
  const std::string root = argc > 1 ? argv[1] : ".";
  const auto rig = validation::read_dataset(root + "/datasets/grima2010", validation::MeasurementsRequired::no);
  const auto hidden = validation::read_dataset(root + "/datasets/hidden-effect");
  // The analytical path only: an expensive model (the DEM) would time a simulation, not this.
  // Filtering on expensive() keeps a future analytical model in and a future simulation out.
  std::vector<validation::ModelPtr> models;
  for (auto& m : validation::make_models(validation::model_names()))
    if (!m->expensive()) models.push_back(std::move(m));

  // estimate: the chain plus the analytical models' predictions for one condition (what `estimate`
  // computes).
  double worst = 0.0;
  for (const auto& st : rig.stations) {
    const int n = 2000;
    const double s = median_seconds(5, [&] {
      for (int i = 0; i < n; ++i) {
        auto a = analytical::analyse_transfer(st);
        for (const auto& m : models) (void)m->predict(st, {}, {{}, false});
        if (a.korzen.normal_force < 0) std::puts("");  // keep the work observable
      }
    }) / n;
    std::printf("estimate %-6s %8.2f us per condition\n", st.condition.c_str(), s * 1e6);
    worst = std::max(worst, s);
  }
  const double val = median_seconds(21, [&] { (void)validation::validate(hidden, models); });
  const double diag = median_seconds(5, [&] { (void)validation::diagnose(hidden, models); });
  std::printf("estimate_worst_us=%.2f validate_8_conditions_ms=%.2f diagnose_all_singles_pairs_ms=%.1f\n",
              worst * 1e6, val * 1e3, diag * 1e3);
}
