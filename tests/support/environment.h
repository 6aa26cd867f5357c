#pragma once
// Environment variables set (or unset) for one scope, and for the processes started in it, which
// inherit the test's environment.

#include <cstdlib>
#include <optional>
#include <string>

namespace trs_test {

class ScopedEnvironment {
 public:
  /// Sets `name` to `value`, or unsets it when `value` is null.
  ScopedEnvironment(const char* name, const char* value) : name_(name) {
    if (const char* old = std::getenv(name)) previous_ = old;
    set(value);
  }
  ScopedEnvironment(const ScopedEnvironment&) = delete;
  ScopedEnvironment& operator=(const ScopedEnvironment&) = delete;
  /// Restores the value from before.
  ~ScopedEnvironment() { set(previous_ ? previous_->c_str() : nullptr); }

  void set(const char* value) {
    if (value)
      setenv(name_, value, 1);
    else
      unsetenv(name_);
  }

 private:
  const char* name_;
  std::optional<std::string> previous_;
};

}  // namespace trs_test
