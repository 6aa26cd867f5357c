#pragma once
// File names with a frame number in them, printf style ("screen.%04d.png"): the images of an
// emissive texture's sequence, and the images of a rendered sequence.

#include <cstdint>
#include <optional>
#include <string>

namespace trs {

class FramePattern {
 public:
  /// Whether `text` has exactly one integer conversion (%d, %4d, %04d) and no other but %%.
  static bool valid(const std::string& text);

  /// Throws std::invalid_argument, saying what a pattern needs, when `pattern` is not valid().
  explicit FramePattern(std::string pattern);

  const std::string& pattern() const { return pattern_; }
  /// The name of frame `frame`.
  std::string format(std::int64_t frame) const;
  /// The frame a name is of, when it is one of the pattern's names (as format() writes it:
  /// "007" is not a name of "%d"); frames are not negative.
  std::optional<std::int64_t> frame_of(const std::string& name) const;

 private:
  std::string pattern_;
  std::string prefix_, suffix_;  ///< around the conversion, %% read as %
};

}  // namespace trs
