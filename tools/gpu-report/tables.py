"""Writes the GPU report (Markdown) from the results that tools/gpu-report.sh collected in WORK:
machine.txt, PART/steps.tsv, the test logs, trs-bench CSVs, the figures and the render JSONs.
Python's standard library only, so that it runs on a GPU machine with nothing but python3.

Usage: python3 tables.py WORK > report.md
"""

import csv
import json
import math
import re
import sys
from pathlib import Path

PARTS = {
    "tests": "1. Vulkan tests, validation layer on",
    "bench": "2. trs-bench on the Vulkan backend",
    "figures": "3. The paper's Figures 8 to 14 on the Vulkan backend",
    "render": "4. trs-render: the Vulkan light sampler against the CPU's",
    "cpu": "5. The CPU backend on the same machine",
}
GOALS = {"smooth": 1.5, "sparse": 8.0}  # ms per frame of 1e8 samples on a GPU
GOAL_SPEEDUP = 20.0  # TRS over RS on sparse maps
GPU_TYPES = ("discrete GPU", "integrated GPU", "virtual GPU")


# ---------------------------------------------------------------------------------------------
# Reading

def read_machine(work):
    """machine.txt: `key: value` lines; `vulkan:` may repeat (one per device)."""
    machine = {"vulkan": []}
    path = work / "machine.txt"
    for line in path.read_text().splitlines() if path.exists() else []:
        key, _, value = line.partition(": ")
        if key == "vulkan":
            machine["vulkan"].append(value)
        else:
            machine[key] = value
    return machine


def read_steps(work, part):
    path = work / part / "steps.tsv"
    if not path.exists():
        return []
    return [dict(zip(("step", "status", "seconds"), line.split("\t")))
            for line in path.read_text().splitlines() if line]


def read_csv(path):
    """trs-bench's rows, measured or skipped for its budget (status "skipped", estimate_ms)."""
    if not path.exists():
        return []
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def read_json(path):
    try:
        return json.loads(path.read_text())
    except (OSError, ValueError):
        return None


def number(row, key):
    """The row's value, NaN where it has none (a skipped case has no times)."""
    if row.get("status") == "skipped":
        return math.nan
    try:
        value = float(row.get(key) or "nan")
    except ValueError:
        return math.nan
    return value


# ---------------------------------------------------------------------------------------------
# Formatting

def ms(value):
    if value is None or math.isnan(value):
        return ""
    if value < 10:
        return f"{value:.3g} ms"
    if value < 1000:
        return f"{value:.1f} ms"
    return f"{value / 1000:.3g} s"


def frame(row):
    """A measured frame time, or the budget rule's estimate of a skipped case."""
    if row.get("status") == "skipped":
        return f"skipped (est. {ms(float(row['estimate_ms']))})"
    return ms(number(row, "total_ms"))


def ratio(value):
    return "" if value is None or math.isnan(value) else f"{value:.3g}x"


def percent(value):
    return "" if math.isnan(value) else f"{100 * value:.3g}%"


def count(value):
    value = float(value)
    exponent = math.log10(value) if value > 0 else 0
    return f"1e{round(exponent)}" if exponent == round(exponent) else f"{value:.3g}"


def mesh_name(row):
    triangles = int(float(row["triangles"]))
    for unit, size in (("M", 1e6), ("k", 1e3)):
        if triangles >= size:
            return f"{row['mesh']}:{triangles / size:.3g}{unit}"
    return f"{row['mesh']}:{triangles}"


def table(header, rows):
    lines = ["| " + " | ".join(header) + " |", "|" + "|".join("---" for _ in header) + "|"]
    lines += ["| " + " | ".join(str(cell) for cell in row) + " |" for row in rows]
    return "\n".join(lines) + "\n"


def steps_note(steps):
    """What did not finish, in one line: cut at the deadline, skipped, or failed."""
    problems = [f"{s['step']} {s['status']}" for s in steps if s["status"] != "ok"]
    return ("Not complete: " + "; ".join(problems) + ".\n") if problems else ""


# ---------------------------------------------------------------------------------------------
# The device

def vulkan_device(work, machine):
    """(name, type, driver) of the device the Vulkan runs used: the one trs-bench names."""
    used = None
    for log in sorted((work / "bench").glob("*.log")):
        match = re.search(r"^backend vulkan on (.+)$", log.read_text(errors="replace"), re.M)
        if match:
            used = match.group(1)
            break
    devices = []
    for line in machine["vulkan"]:  # trs-bench --list-devices: "0: NAME (TYPE; driver DRIVER)"
        match = re.match(r"\d+: (.*) \((discrete GPU|integrated GPU|virtual GPU|CPU|other)"
                         r"(?:; driver (.*?))?(; unsuitable: .*)?\)$", line)
        if match and (match.group(1) == used or (used is None and not match.group(4))):
            devices.append((match.group(1), match.group(2), match.group(3) or ""))
    # Without a trs-bench log, the device the library picks by default: a GPU before the others.
    devices.sort(key=lambda d: d[1] not in GPU_TYPES)
    return devices[0] if devices else (used or "unknown", "unknown", "")


def heading(work, machine):
    name, kind, driver = vulkan_device(work, machine)
    if kind in GPU_TYPES:
        first = f"# GPU report: {name}"
    else:
        first = (f"# GPU report: no GPU found; the Vulkan runs used {name} ({kind}), "
                 "whose times say nothing about a GPU")
    nvidia = machine.get("nvidia-smi")
    lines = [first, "",
             f"- **Device:** {name} ({kind}); Vulkan driver {driver or 'unknown'}"
             + (f"; nvidia-smi: {nvidia}" if nvidia else ""),
             f"- **Commit:** {machine.get('commit', 'unknown')}",
             f"- **Date:** {machine.get('date', 'unknown')}",
             f"- **CPU:** {machine.get('cpu', 'unknown')}, {machine.get('cores', '?')} threads; "
             f"memory {machine.get('memory', 'unknown')}",
             f"- **Run:** `{machine.get('command', '')}`"]
    return "\n".join(lines) + "\n"


def parts_table(work):
    rows = []
    for part, title in PARTS.items():
        steps = read_steps(work, part)
        if not steps:
            rows.append((title, "not run", ""))
            continue
        failed = [s for s in steps if s["status"].startswith("failed")]
        unfinished = [s for s in steps if s["status"] in ("cut", "skipped")]
        status = "cut short" if unfinished else ("finished, with failures" if failed else "finished")
        rows.append((title, status, f"{sum(int(s['seconds']) for s in steps)} s"))
    return "## Parts\n\n" + table(("part", "status", "time"), rows)


# ---------------------------------------------------------------------------------------------
# 1. Tests

def test_results(log_text):
    passed = len(re.findall(r"^\[       OK \] ", log_text, re.M))
    failed = sorted(set(re.findall(r"^\[  FAILED  \] (\S+)", log_text, re.M)))
    skipped = len(re.findall(r"^\[  SKIPPED \] ", log_text, re.M))
    messages = re.findall(r"^lightsampler: (Vulkan (?:error|warning): .*)$", log_text, re.M)
    no_layer = "validation requested but" in log_text
    return passed, failed, skipped, messages, no_layer


def section_tests(work):
    steps = read_steps(work, "tests")
    if not steps:
        return ""
    rows, details = [], []
    for step in steps:
        log = work / "tests" / f"{step['step']}.log"
        text = log.read_text(errors="replace") if log.exists() else ""
        passed, failed, skipped, messages, no_layer = test_results(text)
        layer = "layer not installed" if no_layer else str(len(messages))
        rows.append((step["step"], step["status"], passed, len(failed), skipped, layer, f"{step['seconds']} s"))
        if failed:
            details.append(f"- {step['step']} failed: " + ", ".join(failed))
        for message in sorted(set(messages))[:5]:
            details.append(f"- {step['step']}: `{message[:300]}`")
    text = table(("binary", "status", "passed", "failed", "skipped", "validation messages", "time"), rows)
    text += ("\nA validation message fails the test it comes from, except in the tests that provoke "
             "one on purpose (VulkanTest.ValidationReportsMisuse).\n")
    return text + ("\n" + "\n".join(details) + "\n" if details else "")


# ---------------------------------------------------------------------------------------------
# 2. trs-bench

def pass_ms(row, name):
    return number(row, f"{name}_ms")


def sampling_table(rows):
    """The layout of docs/benchmarks.md: TRS beside RS per mesh, map and target."""
    trs = [r for r in rows if r["experiment"] == "sampling" and r["method"] == "trs"]
    rs = {(r["mesh"], r["triangles"], r["map"], r["target"]): r
          for r in rows if r["experiment"] == "sampling" and r["method"] == "rs"}
    out = []
    for r in trs:
        other = rs.get((r["mesh"], r["triangles"], r["map"], r["target"]))
        t = number(r, "total_ms")
        out.append((mesh_name(r), r["map"], count(r["target"]), percent(number(r, "acceptance")),
                    ms(pass_ms(r, "counting")), ms(pass_ms(r, "realization")), frame(r),
                    ratio(number(r, "floor_multiple")), frame(other) if other else "",
                    speedup(other, t) if other else ""))
    header = ("mesh", "map", "target", "acceptance", "counting", "realization", "trs frame",
              "x floor", "rs frame", "speed-up")
    return table(header, out) if out else "No case finished.\n"


def speedup(rs_row, trs_ms):
    """RS's frame over TRS's; from the budget rule's estimate (marked ~) where RS was skipped."""
    if rs_row.get("status") == "skipped":
        return "~" + ratio(float(rs_row["estimate_ms"]) / trs_ms)
    return ratio(number(rs_row, "total_ms") / trs_ms)


def goals(rows):
    """The GPU goals at 1e8 samples, from the frames that keep their counts."""
    lines = []
    for r in rows:
        if r["experiment"] != "sampling" or r["method"] != "trs" or float(r["target"]) != 1e8:
            continue
        if r["map"] not in GOALS:
            continue
        t = number(r, "total_ms")
        if math.isnan(t):
            continue
        verdict = "met" if t <= GOALS[r["map"]] else "not met"
        line = f"- {mesh_name(r)}, {r['map']}: {ms(t)} (goal {GOALS[r['map']]} ms): {verdict}"
        if r["map"] == "sparse":
            rs = [o for o in rows if o["method"] == "rs" and o["mesh"] == r["mesh"]
                  and o["triangles"] == r["triangles"] and o["map"] == "sparse"
                  and float(o["target"]) == 1e8]
            if rs:
                text = speedup(rs[0], t)
                factor = float(text.strip("~x"))
                line += (f"; TRS {text} faster than RS (goal {GOAL_SPEEDUP:g}x): "
                         + ("met" if factor >= GOAL_SPEEDUP else "not met"))
        lines.append(line)
    return ("Goals at 1e8 samples:\n\n" + "\n".join(lines) + "\n") if lines else ""


def pivot(rows, row_key, column_key, value, header_first):
    """A table with one row per row_key and one column per column_key (in first-seen order)."""
    columns, cells, order = [], {}, []
    for r in rows:
        rk, ck = row_key(r), column_key(r)
        if ck not in columns:
            columns.append(ck)
        if rk not in cells:
            cells[rk] = {}
            order.append(rk)
        cells[rk][ck] = value(r)
    body = [(*rk, *(cells[rk].get(c, "") for c in columns)) for rk in order]
    return table((*header_first, *columns), body) if body else "No case finished.\n"


def section_bench(work):
    steps = read_steps(work, "bench")
    if not steps:
        return ""
    d = work / "bench"
    out = [steps_note(steps)] if steps_note(steps) else []
    sampling = read_csv(d / "sampling.csv")
    out += ["### Sampling, counts kept between frames\n",
            "TRS and plain rejection sampling (RS); frame times are medians; `x floor` is the "
            "frame over the time to write its samples.\n", sampling_table(sampling), goals(sampling)]
    out += ["### Sampling, every frame counting (`--recount`, an animated texture)\n",
            sampling_table(read_csv(d / "sampling-recount.csv"))]
    counting = [r for r in read_csv(d / "counting.csv") if r["experiment"] == "sampling"]
    out += ["### Counting paths\n", "Counting pass, every frame counting.\n",
            pivot(counting, lambda r: (mesh_name(r), r["map"]), lambda r: r["engine"],
                  lambda r: ms(pass_ms(r, "counting")), ("mesh", "map"))]
    ablation = [r for r in read_csv(d / "ablation.csv") if r["experiment"] == "ablation"]
    full = {(r["mesh"], r["triangles"], r["map"], r["target"]): number(r, "total_ms")
            for r in ablation if r["variant"] == "full"}
    out += ["### Ablation (the paper's Figure 14)\n",
            "Frame time of the sampler as designed (`full`) and of each version that differs from "
            "it by one change, every frame counting; in brackets, the time over `full`'s.\n",
            pivot(ablation, lambda r: (r["variant"],),
                  lambda r: f"{mesh_name(r)} {r['map']} {count(r['target'])}",
                  lambda r: f"{frame(r)} "
                            f"({ratio(number(r, 'total_ms') / full.get((r['mesh'], r['triangles'], r['map'], r['target']), math.nan))})",
                  ("variant",))]
    scans = [r for r in read_csv(d / "scan.csv") if r["experiment"] == "scan"]
    out += ["### Scans\n", "Scan pass of TRS frames that stop after it.\n",
            pivot(scans, lambda r: (mesh_name(r), r["map"]), lambda r: r["scan"],
                  lambda r: ms(pass_ms(r, "scan")), ("mesh", "map"))]
    slivers = [r for r in read_csv(d / "sliver.csv") if r["experiment"] == "sliver"]
    ordinary = {(r["variant"], r["target"]): number(r, "total_ms") for r in slivers if r["mesh"] == "ordinary"}
    out += ["### Slivers of density\n",
            "One triangle whose one lit texel covers a fraction of it, beside the same triangle "
            "fully lit (`ordinary`); in brackets, the time over the ordinary triangle's.\n",
            pivot(slivers, lambda r: (r["mesh"], r["variant"]), lambda r: count(r["target"]),
                  lambda r: f"{frame(r)} "
                            f"({ratio(number(r, 'total_ms') / ordinary.get((r['variant'], r['target']), math.nan))})",
                  ("triangle", "rule"))]
    refine = [r for path in sorted(d.glob("refine-*.csv")) for r in read_csv(path)
              if r["experiment"] == "sampling"]
    out += ["### The subdivision (`--refine`)\n",
            "Realization time and acceptance of TRS frames at each `--refine` setting.\n",
            pivot(refine, lambda r: (mesh_name(r), r["map"], count(r["target"])), lambda r: r["refine"],
                  lambda r: f"{ms(pass_ms(r, 'realization'))}, {percent(number(r, 'acceptance'))}",
                  ("mesh", "map", "target"))]
    return "\n".join(out)


# ---------------------------------------------------------------------------------------------
# 3. Figures

def section_figures(work):
    steps = read_steps(work, "figures")
    if not steps:
        return ""
    rows, images = [], []
    for step in steps:
        png = work / "figures" / f"{step['step']}.png"
        rows.append((step["step"], step["status"], f"{step['seconds']} s", "yes" if png.exists() else "no"))
        if png.exists():
            images.append(f"![{step['step']}](figures/{png.name})")
    note = ""
    if steps and not images and any(s["status"] == "ok" for s in steps):
        note = ("No PNG: the machine's python3 has no matplotlib. The CSVs are in data.tar.gz; "
                "`tools/figures --plot-only --out figures` draws them.\n")
    return (table(("figure", "status", "time", "PNG"), rows) + note + "\n"
            + "\n".join(images) + ("\n" if images else ""))


# ---------------------------------------------------------------------------------------------
# 4. Renders

def relmse(report):
    return "" if not report else f"{report['overall']['relmse']:.4g}"


def verdict(report):
    if not report or "worst_tile_sigmas" not in report:
        return ""
    return f"{'pass' if report['pass'] else 'FAIL'} ({report['worst_tile_sigmas']:.2f} sigmas)"


def section_render(work):
    steps = read_steps(work, "render")
    if not steps:
        return ""
    d = work / "render"
    scenes = sorted({p.name.split(".")[0] for p in d.glob("*.cpu.json")})
    rows = []
    for scene in scenes:
        agree = read_json(d / f"{scene}.agree.json")
        for backend in ("cpu", "vulkan"):
            stats = read_json(d / f"{scene}.{backend}.json")
            if not stats:
                continue
            frame = 1000 * stats["render_seconds"] / max(stats["passes"], 1)
            rows.append((scene, backend, stats.get("light_sampler", ""), f"{stats['lights_per_pass']:.3g}",
                         ms(stats["sampler_ms_median"]), ms(stats["light_records_ms_per_pass"]), ms(frame),
                         relmse(read_json(d / f"{scene}.{backend}.full-reference.json")),
                         relmse(read_json(d / f"{scene}.{backend}.small-reference.json")),
                         verdict(read_json(d / f"{scene}.{backend}.small-reference.json")),
                         verdict(agree) if backend == "vulkan" else ""))
    header = ("scene", "backend", "light sampler", "lights/frame", "sampler/frame (median)",
              "records/frame", "frame", "relMSE lit, scene reference", "relMSE lit, test reference",
              "test reference, tile test", "Vulkan against CPU, tile test")
    return (steps_note(steps)
            + "`trs` with each backend's light sampler. Times from each scene's render.toml "
              "settings; relMSE over the lit pixels against the scene's shipped reference "
              "(where it has one), and at the test settings (tests/render/reference_settings.cmake) "
              "against tests/render/references. A tile test passes when no 8 x 8 tile lies more "
              "than 6 standard errors from the other image.\n\n"
            + table(header, rows))


# ---------------------------------------------------------------------------------------------
# 5. CPU

def section_cpu(work):
    steps = read_steps(work, "cpu")
    if not steps:
        return ""
    cpu = read_csv(work / "cpu" / "sampling.csv")
    gpu = {(r["mesh"], r["triangles"], r["map"], r["target"], r["method"]): number(r, "total_ms")
           for r in read_csv(work / "bench" / "sampling.csv") if r["experiment"] == "sampling"}
    rows = []
    for r in cpu:
        if r["experiment"] != "sampling":
            continue
        t = number(r, "total_ms")
        g = gpu.get((r["mesh"], r["triangles"], r["map"], r["target"], r["method"]), math.nan)
        rows.append((mesh_name(r), r["map"], count(r["target"]), r["method"], frame(r), ms(g), ratio(t / g)))
    return (steps_note(steps) + "Frame times, counts kept between frames, beside the Vulkan "
            "backend's from part 2.\n\n"
            + table(("mesh", "map", "target", "method", "cpu frame", "vulkan frame", "cpu / vulkan"), rows))


def main():
    work = Path(sys.argv[1])
    machine = read_machine(work)
    sections = {"tests": section_tests, "bench": section_bench, "figures": section_figures,
                "render": section_render, "cpu": section_cpu}
    out = [heading(work, machine), parts_table(work)]
    for part, title in PARTS.items():
        body = sections[part](work)
        out.append(f"## {title}\n\n" + (body or "Not run.\n"))
    sys.stdout.write("\n".join(out))


if __name__ == "__main__":
    main()
