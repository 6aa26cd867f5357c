#include "scene_io/frame_pattern.h"

#include <cctype>
#include <cstdio>
#include <stdexcept>

namespace trs {
namespace {

/// The pattern's text before and after its conversion, %% read as %; none when it does not have
/// exactly one integer conversion.
std::optional<std::pair<std::string, std::string>> split(const std::string& text) {
  std::string parts[2];
  int conversions = 0;
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text[i] != '%') {
      parts[std::min(conversions, 1)] += text[i];
      continue;
    }
    if (i + 1 < text.size() && text[i + 1] == '%') {
      parts[std::min(conversions, 1)] += '%';
      ++i;
      continue;
    }
    std::size_t j = i + 1;
    while (j < text.size() && std::isdigit(static_cast<unsigned char>(text[j]))) ++j;
    if (j == text.size() || text[j] != 'd' || j - i > 4) return std::nullopt;  // at most %099d
    ++conversions;
    i = j;
  }
  if (conversions != 1) return std::nullopt;
  return std::pair{parts[0], parts[1]};
}

}  // namespace

bool FramePattern::valid(const std::string& text) { return split(text).has_value(); }

FramePattern::FramePattern(std::string pattern) : pattern_(std::move(pattern)) {
  const auto parts = split(pattern_);
  if (!parts)
    throw std::invalid_argument("'" + pattern_ +
                                "' is no frame pattern: it needs one integer conversion (%d, %04d), "
                                "and %% for a percent sign");
  prefix_ = parts->first;
  suffix_ = parts->second;
}

std::string FramePattern::format(std::int64_t frame) const {
  const int size = std::snprintf(nullptr, 0, pattern_.c_str(), static_cast<long long>(frame));
  std::string name(std::size_t(size) + 1, '\0');
  std::snprintf(name.data(), name.size(), pattern_.c_str(), static_cast<long long>(frame));
  name.resize(std::size_t(size));
  return name;
}

std::optional<std::int64_t> FramePattern::frame_of(const std::string& name) const {
  if (name.size() <= prefix_.size() + suffix_.size() || name.compare(0, prefix_.size(), prefix_) != 0 ||
      name.compare(name.size() - suffix_.size(), suffix_.size(), suffix_) != 0)
    return std::nullopt;
  const std::string digits = name.substr(prefix_.size(), name.size() - prefix_.size() - suffix_.size());
  if (digits.size() > 15) return std::nullopt;
  for (const char c : digits)
    if (!std::isdigit(static_cast<unsigned char>(c))) return std::nullopt;
  const std::int64_t frame = std::stoll(digits);
  if (format(frame) != name) return std::nullopt;
  return frame;
}

}  // namespace trs
