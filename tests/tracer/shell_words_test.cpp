// --sbatch's words: split_shell_words() against tests/support/shell_words.json, the table that
// trs-study's splitter (tools/common/slurm.py) is held to as well; shell_quoted() read back by sh.

#include <gtest/gtest.h>
#include <stdio.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "shell_words.h"

namespace {

nlohmann::json cases() {
  std::ifstream in(TRS_SHELL_WORDS_CASES);
  return nlohmann::json::parse(in).at("cases");
}

TEST(ShellWords, SplitsAsTheTableSays) {
  for (const nlohmann::json& c : cases()) {
    const std::string text = c.at("text");
    SCOPED_TRACE(trs::printable(text));
    if (c.contains("words")) {
      EXPECT_EQ(trs::split_shell_words(text), c.at("words").get<std::vector<std::string>>());
      continue;
    }
    try {
      const std::vector<std::string> words = trs::split_shell_words(text);
      ADD_FAILURE() << "not refused: " << words.size() << " words";
    } catch (const trs::ShellWordsError& e) {
      EXPECT_EQ(std::string(1, e.character), c.at("refused").get<std::string>()) << e.what();
      EXPECT_EQ(e.position, c.at("at").get<std::size_t>()) << e.what();
      EXPECT_NE(std::string(e.what()).find(" at character " + std::to_string(e.position)), std::string::npos) << e.what();
    }
  }
}

TEST(ShellWords, TheRefusalSaysWhy) {
  const auto why = [](const std::string& text) {
    try {
      trs::split_shell_words(text);
    } catch (const trs::ShellWordsError& e) {
      return std::string(e.what());
    }
    return std::string("not refused");
  };
  EXPECT_EQ(why("--partition=x; touch pwned"),
            "\";\" at character 14 is a shell operator, and no shell reads these words: quote it to pass it on");
  EXPECT_NE(why("--comment=$HOME").find("\"$\" at character 11 would expand in a shell"), std::string::npos);
  EXPECT_NE(why("--comment=$HOME").find("nothing is expanded"), std::string::npos);
  EXPECT_EQ(why("--hold\n"), "a control character (newline) at character 7: these words are one line of options");
  EXPECT_EQ(why("--comment='a"), "\"'\" at character 11 opens a quote that is never closed");
}

/// `words` quoted and read back by sh: the words as they were.
std::vector<std::string> through_sh(const std::vector<std::string>& words) {
  std::string command = "printf '%s\\n'";
  for (const std::string& w : words) command += " " + trs::shell_quoted(w);
  FILE* pipe = popen(command.c_str(), "r");  // a command of quoted words: what the tests check
  std::vector<std::string> lines(1);
  for (int c; (c = fgetc(pipe)) != EOF;) {
    if (c == '\n')
      lines.emplace_back();
    else
      lines.back().push_back(char(c));
  }
  pclose(pipe);
  lines.pop_back();
  return lines;
}

TEST(ShellWords, AQuotedWordIsReadBackAsItWas) {
  const std::vector<std::string> words = {"plain", "a b", "it's", "$(touch pwned)", "`touch pwned`", "\"q\"",
                                          "back\\slash", "*", "~", "a;b|c&d", "", "naïve"};
  EXPECT_EQ(through_sh(words), words);
  EXPECT_EQ(trs::shell_quoted("--out=f.%04d.exr"), "--out=f.%04d.exr");
}

}  // namespace
