#include "image_sequence.h"

#include <algorithm>
#include <stdexcept>
#include <system_error>

#include "scene_io/file_error.h"
#include "scene_io/image_output.h"
#include "texture_decode.h"

namespace tracer {

ImageSequence read_image_sequence(const std::filesystem::path& document, const std::string& pattern,
                                  std::uint32_t width, std::uint32_t height, const std::string& what) {
  const std::filesystem::path relative(pattern);
  const std::string context = what + ": frames pattern '" + pattern + "'";
  if (!trs::FramePattern::valid(relative.filename().string()))
    throw trs::FileError(document, context + " must have one integer conversion (%d, %04d) in its file name");
  // A scene named by its bare file name has no parent: its folder is the working directory.
  std::filesystem::path folder = document.parent_path() / relative.parent_path();
  if (folder.empty()) folder = ".";
  ImageSequence sequence{folder, trs::FramePattern(relative.filename().string()), 0, 0};
  std::vector<std::int64_t> frames;
  std::error_code error;
  for (const auto& entry : std::filesystem::directory_iterator(sequence.directory, error))
    if (const auto frame = sequence.names.frame_of(entry.path().filename().string())) frames.push_back(*frame);
  if (error) throw trs::FileError(document, context + ": cannot list " + sequence.directory.string());
  if (frames.empty()) throw trs::FileError(document, context + ": no file matches it");
  std::sort(frames.begin(), frames.end());
  sequence.first = frames.front();
  sequence.last = frames.back();
  for (std::size_t i = 1; i < frames.size(); ++i) {
    if (frames[i] == frames[i - 1] + 1) continue;
    throw trs::FileError(document, context + ": frame " + std::to_string(frames[i - 1] + 1) + " is missing (" +
                                       sequence.file(frames[i - 1] + 1).filename().string() + ", between frames " +
                                       std::to_string(sequence.first) + " and " + std::to_string(sequence.last) + ")");
  }
  for (const std::int64_t frame : frames) {
    const auto [w, h] = trs::image_size(sequence.file(frame));
    if (w != width || h != height)
      throw trs::FileError(sequence.file(frame), "frame " + std::to_string(frame) + " of " + what + " is " +
                                                     std::to_string(w) + " x " + std::to_string(h) +
                                                     ", and its poster image " + std::to_string(width) + " x " +
                                                     std::to_string(height));
  }
  return sequence;
}

std::vector<glm::vec3> read_sequence_frame(const Texture& texture, std::int64_t frame) {
  const std::filesystem::path file = texture.frames->file(texture.frames->image_frame(frame));
  trs::Image pixels = trs::read_image(file);
  // The sizes were checked when the scene was read; a file replaced since is checked again.
  if (pixels.width != texture.width || pixels.height != texture.height)
    throw trs::FileError(file, "is no longer " + std::to_string(texture.width) + " x " +
                                   std::to_string(texture.height) + ", the size of its sequence");
  return linear_texels(std::move(pixels), true, file, "");
}

}  // namespace tracer
