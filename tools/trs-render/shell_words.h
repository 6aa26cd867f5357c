#pragma once
// Shell words without a shell. --sbatch's text is split into words as POSIX sh splits them, but
// nothing is expanded or run: the words reach sbatch as an argument vector. The other way, the
// words of a command are quoted for the batch script and for --plan's lines, which sh reads.

#include <cstddef>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace trs {

/// A text that split_shell_words() refuses: the character at fault and its position (from 1, in
/// characters of UTF-8 text), and why, in what().
class ShellWordsError : public std::invalid_argument {
 public:
  ShellWordsError(char character, std::size_t position, const std::string& why);
  char character;
  std::size_t position;
};

/// `text` split into words by POSIX sh's quoting: single quotes keep what they hold; within
/// double quotes a backslash escapes \ " $ and ` alone; outside quotes it escapes any character;
/// unquoted spaces and tabs separate words. Nothing is expanded (brackets, * ? ~ = are
/// characters like any other). Throws ShellWordsError where a shell would do more than quote: an
/// unquoted ; | & < > ( ), a $ or ` outside single quotes, a control character (but the tab
/// between words), an unterminated quote, a backslash that ends the text.
std::vector<std::string> split_shell_words(std::string_view text);

/// A shell word: as it is when it is safe, in single quotes otherwise.
std::string shell_quoted(const std::string& word);

/// Where `text` holds a control character (below 0x20, or 0x7f), which a command line of a
/// script cannot hold safely: "a control character (newline) at character N"; none where it holds
/// none.
std::optional<std::string> control_character(std::string_view text);

/// `text` for a message: in double quotes, its control characters as \n, \t, \r or \xNN.
std::string printable(std::string_view text);

}  // namespace trs
