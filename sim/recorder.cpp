#include "sim/recorder.h"

#include <algorithm>
#include <cmath>

#include "sim/error.h"

namespace gs {

Recorder::Recorder(const PhysicsConfig& c) : config_(c) {
  columns_ = {"t",          "t_paper",    "active", "energy",   "radius_rms", "speed_rms",
              "anisotropy", "collisions", "events", "overlaps", "px"};
  if (c.dim >= 2) columns_.push_back("py");
  if (c.dim >= 3) columns_.push_back("pz");
  if (c.initial == Initial::Thermal) {
    columns_.push_back("pressure");
    columns_.push_back("collision_rate");
  }
}

std::vector<double> Recorder::row(const Simulation& sim, Sample* sample) {
  const Sample s = sim.sample();
  if (sample) *sample = s;
  std::vector<double> r = {s.t,
                           config_.paper_time(s.t),
                           static_cast<double>(s.active),
                           s.energy,
                           s.radius_rms,
                           s.speed_rms,
                           s.anisotropy,
                           static_cast<double>(s.collisions),
                           static_cast<double>(s.events),
                           static_cast<double>(sim.stats().overlaps)};
  for (int k = 0; k < config_.dim; ++k) r.push_back(s.momentum[k]);
  if (config_.initial == Initial::Thermal) {
    const double n = static_cast<double>(config_.particles);
    const double volume = std::pow(config_.box(), config_.dim);
    const double dt = s.t - last_t_;
    const double dvir = sim.stats().virial - last_virial_;
    const double dcoll = static_cast<double>(s.collisions - last_collisions_);
    // Virial pressure: P V = N T + (1 / (d dt)) sum over collisions of impulse * contact
    // distance, with N T = 2 E / d for unit masses (Allen & Tildesley, sec. 3.6).
    const double pressure = (2.0 * s.energy + (dt > 0 ? dvir / dt : 0.0)) / (config_.dim * volume);
    r.push_back(dt > 0 ? pressure : std::nan(""));
    r.push_back(dt > 0 ? 2.0 * dcoll / (n * dt) : std::nan(""));
  }
  last_t_ = s.t;
  last_virial_ = sim.stats().virial;
  last_collisions_ = s.collisions;
  GS_CHECK(r.size() == columns_.size());
  return r;
}

void Recorder::save(StateWriter& out) const {
  out.value(last_t_);
  out.value(last_virial_);
  out.value(last_collisions_);
}

void Recorder::load(StateReader& in) {
  in.value(last_t_);
  in.value(last_virial_);
  in.value(last_collisions_);
}

std::vector<double> log_times(double t_min, double t_max, int per_decade) {
  GS_CHECK(t_min > 0 && per_decade > 0);
  std::vector<double> t;
  for (int j = static_cast<int>(std::ceil(std::log10(t_min) * per_decade - 1e-9));; ++j) {
    const double x = std::pow(10.0, static_cast<double>(j) / per_decade);
    if (x >= t_max * (1 - 1e-12)) break;
    t.push_back(x);
  }
  t.push_back(t_max);
  return t;
}

std::vector<double> linear_times(double dt, double t_max) {
  GS_CHECK(dt > 0);
  std::vector<double> t;
  for (long k = 1; k * dt < t_max * (1 - 1e-12); ++k) t.push_back(static_cast<double>(k) * dt);
  t.push_back(t_max);
  return t;
}

std::vector<double> merge_times(std::vector<double> a, const std::vector<double>& b) {
  a.insert(a.end(), b.begin(), b.end());
  std::sort(a.begin(), a.end());
  std::vector<double> out;
  for (double x : a)
    if (out.empty() || x - out.back() > 1e-12 * std::max(1.0, std::abs(x))) out.push_back(x);
  return out;
}

}  // namespace gs
