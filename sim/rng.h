#pragma once
// Random streams keyed by (seed, realisation, purpose), as in HOOMD-blue: every consumer draws
// from its own stream, so adding draws in one place never shifts the numbers of another, and a
// realisation is reproducible bit for bit whatever thread runs it. The generator is xoshiro256**
// (Blackman & Vigna 2018) seeded through splitmix64; the distributions are written here rather
// than taken from <random>, whose algorithms differ between standard libraries.
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <numbers>

namespace gs {

enum class Stream : std::uint64_t {
  Positions = 1,
  Velocities = 2,
  Kick = 3,
  Bootstrap = 4,
  Medium = 5,  // the unbounded medium: one stream per cell, keyed further by the cell's coordinates
  Shuffle = 6  // directions redrawn for the anisotropy of an isotropic cloud, keyed by the sample
};

// Where the seeding of a stream has got to after (seed, realisation, purpose) and some keys: the
// streams of many cells share the mixing of their common keys (those of one block share all but
// the last coordinate), so it can be done once and extended by the last key per cell. A stream
// seeded from it is the stream the keyed Rng constructor gives for the same keys.
class RngSeed {
 public:
  RngSeed() = default;  // unseeded: a place in an array, to be assigned
  RngSeed(std::uint64_t seed, std::uint64_t realisation, Stream purpose) : x_(seed) {
    x_ = splitmix(x_) ^ (realisation * 0x9E3779B97F4A7C15ULL);
    x_ = splitmix(x_) ^ (static_cast<std::uint64_t>(purpose) * 0xD1B54A32D192ED03ULL);
  }
  // One more key (a cell coordinate), mixed in by one splitmix step.
  RngSeed then(std::int64_t key) const {
    RngSeed next = *this;
    next.x_ = splitmix(next.x_) ^ (static_cast<std::uint64_t>(key) * 0x8CB92BA72F3D8DD7ULL);
    return next;
  }

 private:
  friend class Rng;
  static std::uint64_t splitmix(std::uint64_t& x) {
    std::uint64_t z = (x += 0x9E3779B97F4A7C15ULL);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    return z ^ (z >> 31);
  }
  std::uint64_t x_ = 0;
};

class Rng {
 public:
  explicit Rng(RngSeed from) {
    for (auto& w : s_) w = RngSeed::splitmix(from.x_);
  }
  Rng(std::uint64_t seed, std::uint64_t realisation, Stream purpose)
      : Rng(RngSeed(seed, realisation, purpose)) {}

  // A sub-stream of (seed, realisation, purpose) keyed further by integers (a cell's coordinates):
  // each key is mixed in by one more splitmix step, so distinct keys give unrelated streams.
  template <std::size_t K>
  Rng(std::uint64_t seed, std::uint64_t realisation, Stream purpose,
      const std::array<std::int64_t, K>& key)
      : Rng(with_keys(RngSeed(seed, realisation, purpose), key)) {}

  std::uint64_t next() {
    const std::uint64_t result = rotl(s_[1] * 5, 7) * 9;
    const std::uint64_t t = s_[1] << 17;
    s_[2] ^= s_[0];
    s_[3] ^= s_[1];
    s_[1] ^= s_[2];
    s_[0] ^= s_[3];
    s_[2] ^= t;
    s_[3] = rotl(s_[3], 45);
    return result;
  }

  // Uniform in [0, 1) with 53 random bits.
  double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }

  // Uniform integer in [0, n), n > 0 (Lemire's multiply-shift; the bias is below 2^-64 * n).
  std::uint64_t below(std::uint64_t n) {
    return static_cast<std::uint64_t>((static_cast<unsigned __int128>(next()) * n) >> 64);
  }

  // Standard normal by the Box-Muller transform (one value per call, deterministic).
  double normal() {
    const double u1 = 1.0 - uniform();  // (0, 1]: log is finite
    const double u2 = uniform();
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * std::numbers::pi * u2);
  }

 private:
  static std::uint64_t rotl(std::uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }
  template <std::size_t K>
  static RngSeed with_keys(RngSeed s, const std::array<std::int64_t, K>& key) {
    for (const std::int64_t k : key) s = s.then(k);
    return s;
  }
  std::uint64_t s_[4];
};

}  // namespace gs
