#include "shell_words.h"

#include <cstdio>

namespace trs {
namespace {

bool is_control(char c) { return (unsigned char)c < 0x20 || c == 0x7f; }

/// The position of byte `i` of UTF-8 `text` in characters, from 1 (continuation bytes are not
/// counted), as Python counts it.
std::size_t character_position(std::string_view text, std::size_t i) {
  std::size_t position = 0;
  for (std::size_t k = 0; k <= i; ++k) position += ((unsigned char)text[k] & 0xC0) != 0x80;
  return position;
}

std::string control_name(char c) {
  switch (c) {
    case '\n': return "newline";
    case '\t': return "tab";
    case '\r': return "carriage return";
    default: {
      char hex[8];
      std::snprintf(hex, sizeof hex, "0x%02x", (unsigned char)c);
      return hex;
    }
  }
}

/// Byte `i` of `text` for a message: the character (or "a control character (NAME)") and its
/// position.
std::string described(std::string_view text, std::size_t i) {
  const char c = text[i];
  std::string name = is_control(c) ? "a control character (" + control_name(c) + ")" : std::string{'"', c, '"'};
  return name.append(" at character ").append(std::to_string(character_position(text, i)));
}

/// The refusal of byte `i` of `text`, `why` following its description.
ShellWordsError refused(std::string_view text, std::size_t i, const std::string& why) {
  return ShellWordsError(text[i], character_position(text, i), described(text, i) + why);
}

constexpr std::string_view kOperators = ";|&<>()";
constexpr std::string_view kExpanding = "$`";
constexpr std::string_view kEscapedInDoubleQuotes = "\\\"$`";

const char* const kOperatorWhy = " is a shell operator, and no shell reads these words: quote it to pass it on";
const char* const kExpandingWhy =
    " would expand in a shell, and no shell reads these words: nothing is expanded, so give the value itself "
    "(or quote it to pass it on)";
const char* const kControlWhy = ": these words are one line of options";

}  // namespace

ShellWordsError::ShellWordsError(char character, std::size_t position, const std::string& why)
    : std::invalid_argument(why), character(character), position(position) {}

std::vector<std::string> split_shell_words(std::string_view text) {
  enum class Quote { none, single, double_ };
  std::vector<std::string> words;
  std::string word;
  bool in_word = false;
  Quote quote = Quote::none;
  std::size_t opened = 0;  // the quote's byte
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (is_control(c) && !(quote == Quote::none && c == '\t')) throw refused(text, i, kControlWhy);
    if (quote == Quote::single) {
      if (c == '\'')
        quote = Quote::none;
      else
        word += c;
    } else if (quote == Quote::double_) {
      if (c == '"')
        quote = Quote::none;
      else if (c == '\\' && i + 1 < text.size() && kEscapedInDoubleQuotes.find(text[i + 1]) != std::string_view::npos)
        word += text[++i];
      else if (kExpanding.find(c) != std::string_view::npos)
        throw refused(text, i, kExpandingWhy);
      else
        word += c;
    } else if (c == ' ' || c == '\t') {
      if (in_word) words.push_back(std::move(word));
      word.clear();
      in_word = false;
    } else {
      in_word = true;
      if (c == '\'' || c == '"') {
        quote = c == '\'' ? Quote::single : Quote::double_;
        opened = i;
      } else if (c == '\\') {
        if (i + 1 == text.size()) throw refused(text, i, " escapes nothing: it ends the text");
        if (is_control(text[++i])) throw refused(text, i, kControlWhy);
        word += text[i];
      } else if (kOperators.find(c) != std::string_view::npos) {
        throw refused(text, i, kOperatorWhy);
      } else if (kExpanding.find(c) != std::string_view::npos) {
        throw refused(text, i, kExpandingWhy);
      } else {
        word += c;
      }
    }
  }
  if (quote != Quote::none) throw refused(text, opened, " opens a quote that is never closed");
  if (in_word) words.push_back(std::move(word));
  return words;
}

std::string shell_quoted(const std::string& word) {
  if (!word.empty() && word.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-.,/:=%+@") ==
                           std::string::npos)
    return word;
  std::string out = "'";
  for (const char c : word) {
    if (c == '\'')
      out.append("'\\''");
    else
      out.push_back(c);
  }
  out.push_back('\'');
  return out;
}

std::optional<std::string> control_character(std::string_view text) {
  for (std::size_t i = 0; i < text.size(); ++i)
    if (is_control(text[i])) return described(text, i);
  return std::nullopt;
}

std::string printable(std::string_view text) {
  std::string out = "\"";
  for (const char c : text) {
    if (!is_control(c))
      out += c;
    else if (c == '\n')
      out += "\\n";
    else if (c == '\t')
      out += "\\t";
    else if (c == '\r')
      out += "\\r";
    else
      out += "\\x" + control_name(c).substr(2);
  }
  return out + "\"";
}

}  // namespace trs
