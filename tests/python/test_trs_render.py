"""`import trs_render`: a render from Python equals trs-render's EXR for the same settings, bit for
bit, whether in one call or frame by frame; options are trs-render's, checked by its parser; and
submit() hands a stand-in sbatch the words it was given, running none of them."""

import importlib.util
import json
import os
import re
import subprocess
import sys
from pathlib import Path

import lightsampler
import numpy as np
import OpenImageIO as oiio
import pytest

import trs_render

TINY = dict(width=32, height=18, spp=3, max_depth=2, lights=2000, seed=5, quiet=True)
STAND_IN_SLURM = Path(__file__).resolve().parents[1] / "support" / "slurm"


def scene(scenes):
    return scenes / "neon-sign" / "neon-sign.gltf"


def read_exr(path):
    image = oiio.ImageInput.open(str(path))
    pixels = image.read_image("float")
    image.close()
    return pixels


def cli(exe, scene_file, out, **options):
    args = [exe, scene_file, "--out", out]
    for key, value in options.items():
        args += [f"--{key.replace('_', '-')}"] + ([] if value is True else [str(value)])
    subprocess.run(args, check=True, capture_output=True)


@pytest.mark.parametrize("strategy", ["ris", "trs", "tree", "uniform"])
def test_render_equals_the_command_line_bit_for_bit(tmp_path, trs_render_exe, scenes, strategy):
    cli(trs_render_exe, scene(scenes), tmp_path / "cli.exr", strategy=strategy, **TINY)
    image, stats = trs_render.render(scene(scenes), strategy=strategy, **TINY)
    assert image.shape == (18, 32, 3) and image.dtype == np.float32
    assert np.array_equal(image.view(np.uint32), read_exr(tmp_path / "cli.exr").view(np.uint32))
    assert stats["passes"] == 3 and stats["settings"]["strategy"] == strategy


def test_another_seed_gives_another_image(scenes):
    """The comparison above can fail: renders of two seeds differ."""
    a, _ = trs_render.render(scene(scenes), **TINY)
    b, _ = trs_render.render(scene(scenes), **{**TINY, "seed": 6})
    assert not np.array_equal(a, b)


def test_pass_by_pass_equals_one_render(scenes):
    options = {k: v for k, v in TINY.items() if k != "spp"}
    renderer = trs_render.Renderer(scene(scenes), **options)
    assert renderer.passes == 0 and not renderer.image.any()
    for _ in range(3):
        image = renderer.render_pass()
    assert renderer.passes == 3
    whole, stats = trs_render.render(scene(scenes), **TINY)
    assert np.array_equal(image.view(np.uint32), whole.view(np.uint32))
    assert renderer.variance.shape == renderer.emitter_fraction.shape == (18, 32)
    assert renderer.stats()["passes"] == 3 and set(renderer.stats()) >= set(stats) - {"frame_seconds"}


def test_the_earlier_names_of_a_pass_still_answer(scenes):
    """Scripts written when a pass was called a frame keep working, with the same values."""
    options = {k: v for k, v in TINY.items() if k != "spp"}
    renderer = trs_render.Renderer(scene(scenes), **options)
    renderer.render_frame()
    image = renderer.render_frames(2)
    assert renderer.frames == renderer.passes == 3
    whole, _ = trs_render.render(scene(scenes), **TINY)
    assert np.array_equal(image.view(np.uint32), whole.view(np.uint32))
    stats = renderer.stats()
    for earlier, key in [("frames", "passes"), ("sampler_ms_per_frame", "sampler_ms_per_pass"),
                         ("light_records_ms_per_frame", "light_records_ms_per_pass"),
                         ("lights_per_frame", "lights_per_pass"), ("sampler_passes_ms", "sampler_stages_ms")]:
        assert stats[earlier] == stats[key], earlier
    assert stats["setup_ms"]["first_frame"] == stats["setup_ms"]["first_pass"]


def test_stats_are_the_stats_json(tmp_path, trs_render_exe, scenes):
    cli(trs_render_exe, scene(scenes), tmp_path / "cli.exr", stats=tmp_path / "cli.json", **TINY)
    _, stats = trs_render.render(scene(scenes), **TINY)
    assert set(stats) == set(json.loads((tmp_path / "cli.json").read_text()))


def test_outputs_are_written_as_the_command_line_writes_them(tmp_path, scenes):
    image, _ = trs_render.render(scene(scenes), out=tmp_path / "a.exr", preview=str(tmp_path / "a.png"),
                                 stats=tmp_path / "a.json", **TINY)
    assert np.array_equal(read_exr(tmp_path / "a.exr"), image)
    assert (tmp_path / "a.png").read_bytes()[:4] == b"\x89PNG"
    assert json.loads((tmp_path / "a.json").read_text())["passes"] == 3


def test_preview_is_the_png_the_command_line_writes(tmp_path, scenes):
    image, _ = trs_render.render(scene(scenes), preview=tmp_path / "a.png", exposure=1.5, **TINY)
    png = oiio.ImageInput.open(str(tmp_path / "a.png"))
    written = png.read_image("uint8")
    png.close()
    assert np.array_equal(trs_render.preview(image, exposure=1.5), written)
    assert not np.array_equal(trs_render.preview(image), written)


# An OpenColorIO config whose one view shows the values as they are.
RAW_CONFIG = """ocio_profile_version: 2
roles: {default: lin_rec709, scene_linear: lin_rec709}
displays:
  Linear:
    - !<View> {name: Raw, colorspace: lin_rec709}
colorspaces:
  - !<ColorSpace> {name: lin_rec709}
"""


def test_preview_takes_the_display_transform_of_the_command_line(tmp_path, scenes, monkeypatch):
    config = tmp_path / "raw.ocio"
    config.write_text(RAW_CONFIG)
    image, stats = trs_render.render(scene(scenes), preview=tmp_path / "a.png", exposure=1.5, ocio_config=config,
                                     **TINY)
    assert stats["settings"]["view"] == "Raw"
    png = oiio.ImageInput.open(str(tmp_path / "a.png"))
    written = png.read_image("uint8")
    png.close()
    raw = np.rint(np.clip(image * 2.0 ** 1.5, 0.0, 1.0) * 255.0).astype(np.uint8)
    assert np.array_equal(written, raw)
    assert np.array_equal(trs_render.preview(image, exposure=1.5, ocio_config=config), raw)
    monkeypatch.setenv("OCIO", str(config))
    assert np.array_equal(trs_render.preview(image, exposure=1.5), raw)
    with pytest.raises(ValueError, match='raw.ocio: no view "Filmic"'):
        trs_render.preview(image, view="Filmic")
    with pytest.raises(TypeError, match="unexpected keyword argument 'spp'"):
        trs_render.preview(image, spp=3)


def test_a_warning_of_the_run_is_a_runtime_warning_in_its_own_words(tmp_path, scenes):
    config = tmp_path / "acescg.ocio"  # no linear Rec. 709 space: the renders' space is a guess
    config.write_text(RAW_CONFIG.replace("lin_rec709", "acescg"))
    with pytest.warns(RuntimeWarning, match="acescg.ocio: no colour space for linear Rec. 709") as warned:
        trs_render.render(scene(scenes), preview=tmp_path / "a.png", ocio_config=config, **TINY)
    assert not any(str(w.message).startswith("trs-render") for w in warned)


def test_a_sequence_gives_one_image_per_frame(scenes):
    frames = trs_render.render(scenes / "video-wall" / "video-wall.gltf", frames="0:1", **TINY)
    assert len(frames) == 2
    assert [stats["frame"] for _, stats in frames] == [0, 1]
    assert not np.array_equal(frames[0][0], frames[1][0])


def test_emitter_mask_marks_the_emitters_seen(scenes):
    mask = trs_render.emitter_mask(scene(scenes), width=64, height=36, spp=4)
    assert mask.shape == (36, 64) and mask.dtype == np.float32
    assert 0.0 <= mask.min() and mask.max() == 1.0 and 0.0 < mask.mean() < 0.5


@pytest.mark.parametrize("options, error, message", [
    (dict(spp=0), ValueError, "--width, --height and --spp must be at least 1"),
    (dict(strategy="nope"), ValueError, "--strategy: nope not in"),
    (dict(colour="red"), ValueError, "--colour"),
    (dict(candidates=8, strategy="trs"), ValueError, "--candidates belongs to --strategy ris"),
    (dict(plan=True, frames="0:1"), ValueError, "--plan prints trs-render commands"),
])
def test_bad_options_are_refused_with_the_command_line_message(scenes, options, error, message):
    with pytest.raises(error, match=message):
        trs_render.render(scene(scenes), **options)


def test_a_missing_vulkan_device_raises_lightsamplers_vulkan_unavailable(scenes):
    assert trs_render.VulkanUnavailable is lightsampler.VulkanUnavailable
    with pytest.raises(lightsampler.VulkanUnavailable):
        trs_render.render(scene(scenes), backend="vulkan", device="no such device", **TINY)


def test_the_python_tools_study_every_strategy_but_auto():
    """tools/common/trs_options.py, which the Python tools run trs-render with, against the
    renderer's own names."""
    path = Path(__file__).resolve().parents[2] / "tools" / "common" / "trs_options.py"
    spec = importlib.util.spec_from_file_location("trs_options", path)
    trs_options = importlib.util.module_from_spec(spec)
    sys.dont_write_bytecode = True  # no __pycache__ in the source tree
    spec.loader.exec_module(trs_options)
    assert sorted(trs_options.STRATEGIES) == sorted(set(trs_render.STRATEGIES) - {"auto"})
    assert "auto" in trs_render.STRATEGIES


def test_bad_scene_is_refused_with_its_name(tmp_path):
    with pytest.raises(ValueError, match="missing.gltf"):
        trs_render.render(tmp_path / "missing.gltf", **TINY)
    bad = tmp_path / "bad.gltf"
    bad.write_text("{ not json")
    with pytest.raises(ValueError, match="bad.gltf"):
        trs_render.Renderer(bad)


def test_a_renderer_refuses_the_options_of_a_run(scenes):
    with pytest.raises(ValueError, match="out belongs to trs_render.render()"):
        trs_render.Renderer(scene(scenes), out="x.exr")
    with pytest.raises(ValueError, match="view belongs to trs_render.render()"):
        trs_render.Renderer(scene(scenes), view="Filmic")


@pytest.fixture
def stand_in_sbatch(tmp_path, monkeypatch):
    """tests/support/slurm/sbatch first on the PATH: the folder where it records its calls."""
    record = tmp_path / "sbatch"
    record.mkdir()
    monkeypatch.setenv("PATH", f"{STAND_IN_SLURM}:{os.environ['PATH']}")
    monkeypatch.setenv("SBATCH_RECORD", str(record))
    return record


def submit(scenes, trs_render_exe, out, frames="0:1", **options):
    return trs_render.submit(scenes / "video-wall" / "video-wall.gltf", frames=frames, out=out, program=trs_render_exe,
                             **TINY, **options)


@pytest.mark.parametrize("words, named", [
    ("--partition=x; touch {canary}", '";" at character 14 is a shell operator'),
    ("--partition=x $(touch {canary})", '"$" at character 15 would expand in a shell'),
    ("--partition=x `touch {canary}`", '"`" at character 15 would expand in a shell'),
    ("--partition=x && touch {canary}", '"&" at character 15'),
    ('--comment="$(touch {canary})"', '"$" at character 12'),
    ("--partition=x\ntouch {canary}", "a control character (newline) at character 14"),
])
def test_submit_refuses_sbatch_words_a_shell_would_run(tmp_path, stand_in_sbatch, scenes, trs_render_exe, words,
                                                       named):
    with pytest.raises(ValueError, match=re.escape("--sbatch: " + named)):
        submit(scenes, trs_render_exe, tmp_path / "s" / "f.%04d.exr", sbatch=words.format(canary=tmp_path / "pwned"))
    assert sorted(p.name for p in tmp_path.iterdir()) == ["sbatch"]
    assert not list(stand_in_sbatch.iterdir())  # sbatch never ran


def test_submit_hands_quoted_sbatch_words_over_whole(tmp_path, stand_in_sbatch, scenes, trs_render_exe):
    canary = tmp_path / "pwned"
    job = submit(scenes, trs_render_exe, tmp_path / "s" / "f.%04d.exr",
                 sbatch=f"--comment='a b' '--comment=$(touch {canary})' --exclude=node[1-3]")
    assert job == "4242"
    args = (stand_in_sbatch / "0.args").read_text().split("\0")[:-1]
    assert args[-4:-1] == ["--comment=a b", f"--comment=$(touch {canary})", "--exclude=node[1-3]"]
    assert not canary.exists()


@pytest.mark.parametrize("folder", ["it's \"quoted\"", "$(touch {canary})", "`touch {canary}`"])
def test_the_batch_script_run_by_sh_renders_into_any_output_folder(tmp_path, stand_in_sbatch, scenes, trs_render_exe,
                                                                   folder):
    out = tmp_path / "o" / folder.format(canary=tmp_path / "pwned") / "f.%04d.exr"
    submit(scenes, trs_render_exe, out, frames="0:0")
    task = subprocess.run(["sh", stand_in_sbatch / "0.script"], capture_output=True, text=True,
                          env={**os.environ, "SLURM_ARRAY_TASK_ID": "0"})
    assert task.returncode == 0, task.stderr
    assert [p for p in (tmp_path / "o").rglob("*") if p.is_file()] == [out.parent / "f.0000.exr"]
    assert sorted(p.name for p in tmp_path.iterdir()) == ["o", "sbatch"]


def test_submit_refuses_a_path_with_a_control_character(tmp_path, stand_in_sbatch, scenes, trs_render_exe):
    with pytest.raises(ValueError, match=r"--out: .* holds a control character \(newline\)"):
        submit(scenes, trs_render_exe, tmp_path / "a\nb" / "f.%04d.exr")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["sbatch"]


def test_save_partial_belongs_to_a_run():
    with pytest.raises(ValueError, match="save_partial belongs to trs_render.render()"):
        trs_render.Renderer(Path("unused.gltf"), save_partial=True)
