#pragma once
// The exact state of the engine as a stream of plain bytes, read back in the order written. The
// physics saves and loads itself through these two interfaces and knows nothing of the file
// that holds them: io/checkpoint.h is the file (header, checksum, atomic commit). Only saving
// and loading go through the virtual bytes(); the engine's hot loop never does.
#include <cstdint>
#include <string>
#include <type_traits>
#include <vector>

namespace gs {

// What a stream was saved from, checked before any state is read into an engine.
struct StateIdentity {
  int dim = 0;
  std::uint64_t particles = 0;
};

class StateWriter {
 public:
  virtual ~StateWriter() = default;
  virtual void bytes(const void* p, std::size_t n) = 0;
  // T is plain data: numbers, or structs of them and of fixed-size Eigen vectors.
  template <class T>
  void value(const T& v) {
    static_assert(!std::is_pointer_v<T>);
    bytes(&v, sizeof v);
  }
  template <class T, class A>
  void vector(const std::vector<T, A>& v) {
    value(static_cast<std::uint64_t>(v.size()));
    bytes(v.data(), v.size() * sizeof(T));
  }
  void string(const std::string& s) {
    value(static_cast<std::uint64_t>(s.size()));
    bytes(s.data(), s.size());
  }
};

class StateReader {
 public:
  virtual ~StateReader() = default;
  virtual const StateIdentity& identity() const = 0;
  // Refuses (UserError naming the source) a read past the end.
  virtual void bytes(void* p, std::size_t n) = 0;
  template <class T>
  T value() {
    T v;
    bytes(&v, sizeof v);
    return v;
  }
  template <class T>
  void value(T& v) {
    bytes(&v, sizeof v);
  }
  template <class T, class A>
  void vector(std::vector<T, A>& v) {
    const auto n = value<std::uint64_t>();
    if (n > remaining() / sizeof(T)) corrupt();
    v.resize(n);
    bytes(v.data(), n * sizeof(T));
  }
  std::string string() {
    const auto n = value<std::uint64_t>();
    if (n > remaining()) corrupt();
    std::string s(n, '\0');
    bytes(s.data(), n);
    return s;
  }
  // For loaders: refuses the stream (as corrupt) unless `ok`.
  void expect(bool ok) const {
    if (!ok) corrupt();
  }

 protected:
  virtual std::size_t remaining() const = 0;
  [[noreturn]] virtual void corrupt() const = 0;
};

}  // namespace gs
