"""Commands handed to Slurm: one job array a command per task, or one job, through the `sbatch`
on the PATH, run without a shell (trs-study --submit slurm; trs-render --submit has its own, in
C++, held to the same rules).

sbatch's options go on its command line. The batch script holds the commands alone, quoted: an
array task runs its command from a `case` on $SLURM_ARRAY_TASK_ID. sbatch reads the script at
submission, and it is removed after. The user's options for sbatch (--sbatch) are split into
words by shell_words(), which expands nothing and runs nothing."""
import json
import os
import shlex
import subprocess
import tempfile
from pathlib import Path


class SubmitError(RuntimeError):
    """sbatch refused the job or could not be run, or a command cannot go into a batch script."""


class ShellWordsError(ValueError):
    """A text that shell_words() refuses: the character at fault and its position (from 1), why in
    the message."""

    def __init__(self, text, index, why):
        self.character, self.position = text[index], index + 1
        super().__init__(described(text, index) + why)


OPERATORS = ";|&<>()"
EXPANDING = "$`"
ESCAPED_IN_DOUBLE_QUOTES = '\\"$`'
OPERATOR_WHY = " is a shell operator, and no shell reads these words: quote it to pass it on"
EXPANDING_WHY = (" would expand in a shell, and no shell reads these words: nothing is expanded, so give the "
                 "value itself (or quote it to pass it on)")
CONTROL_WHY = ": these words are one line of options"
CONTROL_NAMES = {"\n": "newline", "\t": "tab", "\r": "carriage return"}


def is_control(c):
    return ord(c) < 0x20 or ord(c) == 0x7F


def described(text, index):
    """text[index] for a message: the character (or "a control character (NAME)") and its position."""
    c = text[index]
    name = f"a control character ({CONTROL_NAMES.get(c, f'0x{ord(c):02x}')})" if is_control(c) else f'"{c}"'
    return f"{name} at character {index + 1}"


def shell_words(text):
    """`text` split into words by POSIX sh's quoting, nothing expanded or run, as trs-render splits
    --sbatch (tools/trs-render/shell_words.h; both are held to tests/support/shell_words.json):
    single quotes keep what they hold; within double quotes a backslash escapes \\ " $ and `
    alone; outside quotes it escapes any character; unquoted spaces and tabs separate words.
    Raises ShellWordsError where a shell would do more than quote: an unquoted ; | & < > ( ), a
    $ or ` outside single quotes, a control character (but the tab between words), an
    unterminated quote, a backslash that ends the text."""
    words, word, in_word, quote, opened = [], "", False, None, 0
    i = 0
    while i < len(text):
        c = text[i]
        if is_control(c) and not (quote is None and c == "\t"):
            raise ShellWordsError(text, i, CONTROL_WHY)
        if quote == "'":
            if c == "'":
                quote = None
            else:
                word += c
        elif quote == '"':
            if c == '"':
                quote = None
            elif c == "\\" and i + 1 < len(text) and text[i + 1] in ESCAPED_IN_DOUBLE_QUOTES:
                i += 1
                word += text[i]
            elif c in EXPANDING:
                raise ShellWordsError(text, i, EXPANDING_WHY)
            else:
                word += c
        elif c in " \t":
            if in_word:
                words.append(word)
            word, in_word = "", False
        else:
            in_word = True
            if c in "'\"":
                quote, opened = c, i
            elif c == "\\":
                if i + 1 == len(text):
                    raise ShellWordsError(text, i, " escapes nothing: it ends the text")
                i += 1
                if is_control(text[i]):
                    raise ShellWordsError(text, i, CONTROL_WHY)
                word += text[i]
            elif c in OPERATORS:
                raise ShellWordsError(text, i, OPERATOR_WHY)
            elif c in EXPANDING:
                raise ShellWordsError(text, i, EXPANDING_WHY)
            else:
                word += c
        i += 1
    if quote is not None:
        raise ShellWordsError(text, opened, " opens a quote that is never closed")
    if in_word:
        words.append(word)
    return words


def control_character(text):
    """Where `text` holds a control character (below 0x20, or 0x7f), which a command line of a
    script cannot hold safely: "a control character (newline) at character N"; None where none."""
    return next((described(text, i) for i, c in enumerate(text) if is_control(c)), None)


def printable(text):
    """`text` for a message: in double quotes, its control characters escaped."""
    return json.dumps(str(text), ensure_ascii=False)


def output_pattern(log_pattern):
    """`log_pattern` as sbatch's --output takes it: the folder's % doubled (Slurm reads %A, %a and
    the like as replacement symbols, %% as %), the file name's symbols kept. A backslash anywhere
    would turn the symbols off and give every task's log one name: refused."""
    folder, name = Path(log_pattern).parent, Path(log_pattern).name
    if "\\" in str(log_pattern):
        raise SubmitError(f"{printable(folder)} holds a backslash, which makes Slurm write every task's log to "
                          "one file (its --output patterns take none)")
    return str(folder).replace("%", "%%") + "/" + name


def batch_script(commands, name, array):
    """The batch script of job `name`'s `commands` (lists of words): with `array`, each an array
    task's, else the one command of a job."""
    for word in (w for command in commands for w in command):
        problem = control_character(word)
        if problem:
            raise SubmitError(f"{printable(word)} holds {problem}, which a batch script cannot hold safely")
    if not array:
        return f"#!/bin/sh\nexec {shlex.join(commands[0])}\n"
    lines = ["#!/bin/sh", 'case "$SLURM_ARRAY_TASK_ID" in']
    lines += [f"  {i}) exec {shlex.join(c)} ;;" for i, c in enumerate(commands)]
    lines += ["esac", f'echo "{name}: no task $SLURM_ARRAY_TASK_ID in this job array" >&2', "exit 1", ""]
    return "\n".join(lines)


def submit(commands, name, log_pattern, options=(), sbatch_words=(), dependency=None, wait=False):
    """Submits `commands` (an array, or one job for one command whose log pattern has no %a);
    returns the job id. `options` are sbatch options for this job alone (`--exclusive`),
    `sbatch_words` the user's (shell_words() of --sbatch), which come later and so win;
    `dependency` is sbatch's (`afterok:12,afterany:13`). With `wait`, returns once the job has
    ended, and raises SubmitError if it failed."""
    array = len(commands) > 1 or "%a" in str(log_pattern)
    words = ["sbatch", "--parsable"] + (["--wait"] if wait else []) + [f"--job-name={name}",
                                                                        f"--output={output_pattern(log_pattern)}"]
    words += [f"--array=0-{len(commands) - 1}"] if array else []
    words += [f"--dependency={dependency}"] if dependency else []
    words += [*options, *sbatch_words]
    script_text = batch_script(commands, name, array)
    Path(log_pattern).parent.mkdir(parents=True, exist_ok=True)
    with tempfile.NamedTemporaryFile("w", suffix=".sh", prefix=f".{name}-", dir=Path(log_pattern).parent,
                                     delete=False) as script:
        script.write(script_text)
    try:
        result = subprocess.run(words + [script.name], capture_output=True, text=True)
    except FileNotFoundError:
        raise SubmitError("cannot run sbatch: no sbatch on the PATH, is Slurm installed?")
    finally:
        os.unlink(script.name)
    job = result.stdout.strip().split(";")[0]
    if not job:
        raise SubmitError(f"sbatch submitted nothing (status {result.returncode}): {result.stderr.strip()}")
    if wait and result.returncode != 0:
        raise SubmitError(f"Slurm job {job} failed (sbatch status {result.returncode}); logs: {log_pattern}")
    return job
