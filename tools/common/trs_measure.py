"""The noise measurement of the Python tools, as trs-imgdiff defines it (tools/trs-imgdiff/main.cpp):
images read as RGB, relMSE over pixels and channels, and the lit pixels of an emitter mask.

Images are numpy arrays of shape (height, width, 3), float64; a pixel selection is a boolean
array of shape (height, width). numpy and OpenImageIO's binding are imported on first use, so
that a tool can import this module for commands that read no image.
"""

# Added to reference^2: keeps dark pixels from dominating relMSE. The value trs-imgdiff prints
# and writes as relmse_guard (scene_io/include/scene_io/relmse.h); tests/measure/test_measure.py checks it.
GUARD = 0.01


def read_exr(path):
    """An OpenEXR image's RGB as float64: a single channel spread to all three, channels past
    the third (alpha) dropped. Raises OSError with the reader's reason."""
    import numpy as np
    import OpenImageIO as oiio
    image = oiio.ImageInput.open(str(path))
    if image is None:
        raise OSError(f"{path}: {oiio.geterror()}")
    pixels = image.read_image(oiio.FLOAT)
    image.close()
    pixels = np.asarray(pixels, dtype=np.float64)
    if pixels.ndim == 2:
        pixels = pixels[:, :, None]
    return np.repeat(pixels[:, :, :1], 3, axis=2) if pixels.shape[2] == 1 else pixels[:, :, :3]


def relative_errors(image, reference):
    """(x - r)^2 / (r^2 + GUARD) per pixel and channel: relMSE's terms."""
    return (image - reference) ** 2 / (reference ** 2 + GUARD)


def relmse(image, reference, pixels=None):
    """The mean of relative_errors over every channel of the pixels selected (all by default);
    NaN where none is (trs-imgdiff reports 0 there)."""
    errors = relative_errors(image, reference)
    if pixels is None:
        return float(errors.mean())
    return float(errors[pixels].mean()) if pixels.any() else float("nan")


# The share of pixels, those of the largest error, that trimmed_relmse leaves out: rare bright
# paths (fireflies) that one render of a few seconds happens to hold decide its relMSE, and move
# it tenfold from seed to seed; without them it measures the noise every render of the strategy
# shows. The usual choice in path-guiding evaluations (e.g. Figueiredo et al.'s results for "Neural
# path guiding with distribution factorization", EGSR 2025), reported beside relMSE, never instead.
TRIMMED_SHARE = 0.001


def trimmed_mean(values, share=TRIMMED_SHARE):
    """The mean of a flat array with its floor(share x size) largest left out; NaN where empty."""
    import numpy as np
    if values.size == 0:
        return float("nan")
    kept = values.size - int(share * values.size)
    return float(np.partition(values, kept - 1)[:kept].mean())


def trimmed_relmse(image, reference, pixels=None, share=TRIMMED_SHARE):
    """relMSE over the pixels selected (all by default), each pixel's error its channels' mean,
    with the floor(share x pixels) largest left out; NaN where none is selected."""
    errors = relative_errors(image, reference).mean(axis=2)
    return trimmed_mean(errors.ravel() if pixels is None else errors[pixels], share)


def lit_pixels(emitter_mask):
    """The pixels an emitter mask (trs-render --emitter-mask) leaves at zero in its first channel:
    where no camera sample sees an emitter, and the noise is the light strategy's own."""
    return emitter_mask[:, :, 0] == 0
