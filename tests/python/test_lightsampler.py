"""`import lightsampler`: the samples equal the C++ library's (trs-sample's) bit for bit, views
keep their frame alive, bad input is refused with a message that names it."""

import gc
import subprocess

import numpy as np
import OpenImageIO as oiio
import pytest

import lightsampler as ls
from conftest import vulkan_or_skip

SEED = 7
COUNT = 20000


def mesh():
    """Four triangles of a bent strip with uneven areas; UVs on a 1/8 lattice, which an OBJ's
    1 - v stores exactly."""
    positions = np.array([[0.0, 0.0, 0.0], [1.3, 0.1, 0.0], [0.1, 0.9, 0.2], [1.2, 1.1, 0.7],
                          [2.1, 0.3, 1.1], [2.5, 1.4, 1.3]], np.float32)
    uvs = np.array([[0.0, 0.0], [0.5, 0.0], [0.0, 0.5], [0.5, 0.625], [1.0, 0.125], [1.0, 1.0]], np.float32)
    indices = np.array([[0, 1, 2], [1, 3, 2], [1, 4, 3], [4, 5, 3]], np.uint32)
    return positions, uvs, indices


def density(height=16, width=32):
    return np.random.default_rng(3).random((height, width), dtype=np.float32) * 400.0


def write_inputs(tmp_path, positions, uvs, indices, texels):
    obj = tmp_path / "mesh.obj"
    lines = [f"v {x!r} {y!r} {z!r}" for x, y, z in positions.astype(float)]
    lines += [f"vt {u!r} {1.0 - v!r}" for u, v in uvs.astype(float)]
    lines += ["f " + " ".join(f"{i + 1}/{i + 1}" for i in tri) for tri in indices]
    obj.write_text("\n".join(lines) + "\n")
    exr = tmp_path / "density.exr"
    out = oiio.ImageOutput.create(str(exr))
    assert out.open(str(exr), oiio.ImageSpec(texels.shape[1], texels.shape[0], 1, "float"))
    assert out.write_image(texels[:, :, None])
    out.close()
    return obj, exr


def read_ply(path):
    data = path.read_bytes()
    end = data.index(b"end_header\n") + len(b"end_header\n")
    vertex = np.dtype([("x", "<f4"), ("y", "<f4"), ("z", "<f4"), ("u", "<f4"), ("v", "<f4"),
                       ("triangle", "<u4"), ("b1", "<f4"), ("b2", "<f4")])
    return np.frombuffer(data[end:], vertex)


def bits(a):
    return np.ascontiguousarray(a).view(np.uint32)


def canonical(samples):
    """Samples sorted by triangle, then by the bits of b1 and b2."""
    return samples[np.lexsort((bits(samples["b2"]), bits(samples["b1"]), samples["triangle"]))]


@pytest.mark.parametrize("backend", ["cpu", "vulkan"])
@pytest.mark.parametrize("method", ["trs", "rs", "naive", "frs"])
def test_samples_equal_the_cpp_samples_bit_for_bit(tmp_path, trs_sample, backend, method):
    if backend == "vulkan":
        vulkan_or_skip()
    positions, uvs, indices = mesh()
    texels = density()
    obj, exr = write_inputs(tmp_path, positions, uvs, indices, texels)
    ply = tmp_path / "samples.ply"
    subprocess.run([trs_sample, obj, exr, "--count", str(COUNT), "--seed", str(SEED), "--method", method,
                    "--backend", backend, "--out", ply], check=True, capture_output=True)
    cpp = read_ply(ply)

    # trs-sample's --refine auto weighs its subdivision for the frame it draws, --count samples.
    frame = ls.Sampler(positions, uvs, indices, [texels], backend=backend, frame_samples=COUNT).generate(
        seed=SEED, target_count=COUNT, method=method)
    assert len(frame) == len(cpp) > 0.9 * COUNT
    ours = np.empty(len(frame), cpp.dtype)
    ours["triangle"], ours["b1"], ours["b2"] = frame.triangles, frame.b1, frame.b2
    points = frame.positions()
    for axis, name in enumerate("xyz"):
        ours[name] = points[:, axis]
    if frame.scan_used == "unordered":
        # The GPU's unordered scan lays the triangles' runs of samples out in the order its
        # atomics come, which differs from run to run: the same samples, in another order.
        ours, cpp = canonical(ours), canonical(cpp)
    assert np.array_equal(ours["triangle"], cpp["triangle"])
    for name in ["b1", "b2", "x", "y", "z"]:
        assert np.array_equal(bits(ours[name]), bits(cpp[name])), name


def test_another_seed_gives_other_samples():
    """The comparison above can fail: frames of two seeds differ."""
    positions, uvs, indices = mesh()
    s = ls.Sampler(positions, uvs, indices, [density()], backend="cpu")
    a, b = s.generate(seed=SEED, target_count=COUNT), s.generate(seed=SEED + 1, target_count=COUNT)
    n = min(len(a), len(b))
    assert not np.array_equal(bits(a.b1[:n]), bits(b.b1[:n]))


def test_views_keep_their_frame_alive():
    positions, uvs, indices = mesh()
    s = ls.Sampler(positions, uvs, indices, [density()], backend="cpu")
    frame = s.generate(seed=1, target_count=COUNT)
    triangles, b1, counts = frame.triangles, frame.b1, frame.counts
    kept = triangles.copy(), b1.copy(), counts.copy()
    del frame
    gc.collect()
    # Frames freed go back to the sampler for reuse: had the views not kept theirs, these would
    # write into the memory the views read.
    for seed in range(2, 6):
        s.generate(seed=seed, target_count=COUNT)
    assert np.array_equal(triangles, kept[0])
    assert np.array_equal(bits(b1), bits(kept[1]))
    assert np.array_equal(counts, kept[2])
    with pytest.raises(ValueError, match="read-only"):
        b1[0] = 0.5


def test_frame_outputs():
    positions, uvs, indices = mesh()
    texels = density()
    s = ls.Sampler(positions, uvs, indices, [texels], backend="cpu")
    f = s.generate(seed=2, target_count=COUNT)
    assert f.triangles.dtype == np.uint32 and f.b1.dtype == np.float32
    assert f.counts.dtype == np.uint64 and f.counts.shape == (4,) and f.counts.sum() == len(f)
    assert np.array_equal(np.bincount(f.triangles, minlength=4), f.counts)
    assert f.expected_counts.shape == (4,) and np.isclose(f.expected_counts.sum(), f.expected_total)
    assert f.positions().shape == (len(f), 3) and f.uvs().shape == (len(f), 2)
    normals = f.normals()
    assert np.allclose(np.linalg.norm(normals, axis=1), 1.0, atol=1e-6)
    assert 0.0 < f.acceptance <= 1.0 and f.exhausted == 0
    assert {"counting", "scan", "realization"} <= set(f.pass_ms)
    assert f.method == "trs" and f.sample_count == len(f)


def test_density_reads_the_texel_of_the_point():
    positions, uvs, indices = mesh()
    texels = density()
    s = ls.Sampler(positions, uvs, indices, [texels], backend="cpu", scales=[2.0])
    f = s.generate(seed=3, target_count=1000)
    d = s.density(np.ascontiguousarray(f.triangles), np.ascontiguousarray(f.b1), np.ascontiguousarray(f.b2))
    uv = f.uvs()
    col = np.clip((uv[:, 0] * texels.shape[1]).astype(int), 0, texels.shape[1] - 1)
    row = np.clip((uv[:, 1] * texels.shape[0]).astype(int), 0, texels.shape[0] - 1)
    # Points on a texel edge may round either way; nearly all are inside one texel.
    assert np.mean(d == 2.0 * texels[row, col]) > 0.99
    assert np.all(d > 0)


def test_update_map_is_sampled_by_the_next_frame():
    positions, uvs, indices = mesh()
    s = ls.Sampler(positions, uvs, indices, [density()], backend="cpu")
    right = density()
    right[:, : right.shape[1] // 2] = 0.0
    s.update_map(0, right)
    u = s.generate(seed=4, target_count=COUNT).uvs()[:, 0]
    assert u.min() >= 0.5
    with pytest.raises(IndexError, match="map 1 of 1"):
        s.update_map(1, right)


def test_vulkan_unavailable_is_a_runtime_error():
    assert issubclass(ls.VulkanUnavailable, RuntimeError)
    positions, uvs, indices = mesh()
    with pytest.raises(RuntimeError):
        ls.Sampler(positions, uvs, indices, [density()], backend="vulkan", device="no such device")


@pytest.mark.parametrize("change, message", [
    (lambda p, t, i, d: (p.astype(np.float64), t, i, d), r"positions: expected dtype float32, got float64"),
    (lambda p, t, i, d: (p[:, :2].copy(), t, i, d), r"positions: expected shape \(any, 3\), got \(6, 2\)"),
    (lambda p, t, i, d: (np.hstack([p, p])[:, ::2], t, i, d), r"positions: the array is not C-contiguous"),
    (lambda p, t, i, d: (p.tolist(), t, i, d), r"positions: expected a numpy array of float32, got list"),
    (lambda p, t, i, d: (p, t[:5].copy(), i, d), r"uvs: expected shape \(6, 2\), got \(5, 2\)"),
    (lambda p, t, i, d: (p, t, i.astype(np.int32), d), r"indices: expected dtype uint32, got int32"),
    (lambda p, t, i, d: (p, t, i, d[None]), r"maps\[0\]: expected shape \(any, any\), got \(1, 16, 32\)"),
    (lambda p, t, i, d: (np.where(np.arange(6)[:, None] == 2, np.float32(np.nan), p), t, i, d), r"vertex 2 is not finite"),
    (lambda p, t, i, d: (p, t, np.where(i == 5, np.uint32(9), i), d), r"9"),
    (lambda p, t, i, d: (p, t, i, -d), r"negative"),
])
def test_bad_input_is_refused_with_a_message(change, message):
    p, t, i, d = change(*mesh(), density())
    with pytest.raises(ValueError, match=message):
        ls.Sampler(p, t, i, [d], backend="cpu")


def test_bad_request_is_refused_with_a_message():
    s = ls.Sampler(*mesh(), [density()], backend="cpu")
    with pytest.raises(ValueError, match=r"method: unknown value 'trss' \(one of trs, rs, naive, frs\)"):
        s.generate(method="trss")
    with pytest.raises(ValueError, match="target"):
        s.generate(target_count=float("nan"))
    with pytest.raises(ValueError, match="b1: expected dtype float32"):
        s.density(np.zeros(2, np.uint32), np.zeros(2), np.zeros(2, np.float32))
    with pytest.raises(ValueError, match="the mesh has 4 triangles"):
        s.density(np.array([4], np.uint32), np.zeros(1, np.float32), np.zeros(1, np.float32))


def test_refine_auto_weighs_its_subdivision_for_frame_samples():
    # The cost model's samples follow the density as any sampler's: the same integrals, and
    # samples that land only where the density is non-zero.
    d = density()
    plain = ls.Sampler(*mesh(), [d], backend="cpu", refine=None).generate(seed=3, target_count=1e4)
    s = ls.Sampler(*mesh(), [d], backend="cpu", refine="auto", frame_samples=1e4)
    frame = s.generate(seed=3, target_count=1e4)
    np.testing.assert_allclose(frame.expected_counts, plain.expected_counts, rtol=1e-6)
    assert frame.sample_count > 0
    assert np.all(s.density(*(np.ascontiguousarray(a) for a in (frame.triangles, frame.b1, frame.b2))) > 0)
    with pytest.raises(ValueError, match="frame_samples belongs to refine='auto'"):
        ls.Sampler(*mesh(), [d], backend="cpu", refine=0.5, frame_samples=1e4)
    with pytest.raises(ValueError, match="frame_samples: a finite count"):
        ls.Sampler(*mesh(), [d], backend="cpu", refine="auto", frame_samples=-1.0)
