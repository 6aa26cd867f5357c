"""The Python modules' tests (pytest, run by ctest as python_modules). ctest puts the build's
modules on PYTHONPATH and names the command-line tools whose output they must equal."""

import os
from pathlib import Path

import pytest


def tool(name):
    path = os.environ.get(name)
    if not path:
        pytest.skip(f"{name} is not set (ctest sets it)")
    return Path(path)


@pytest.fixture(scope="session")
def trs_sample():
    return tool("TRS_SAMPLE")


@pytest.fixture(scope="session")
def trs_render_exe():
    return tool("TRS_RENDER")


@pytest.fixture(scope="session")
def scenes():
    return Path(__file__).resolve().parents[2] / "scenes"


def vulkan_or_skip():
    """Skips without a Vulkan device, or fails where LIGHTSAMPLER_REQUIRE_VULKAN=1 asks for one."""
    import lightsampler

    if not lightsampler.has_vulkan_backend():
        pytest.skip("built without the Vulkan backend")
    if lightsampler.vulkan_devices():
        return
    if os.environ.get("LIGHTSAMPLER_REQUIRE_VULKAN") == "1":
        pytest.fail("LIGHTSAMPLER_REQUIRE_VULKAN=1 but no Vulkan device")
    pytest.skip("no Vulkan device")
