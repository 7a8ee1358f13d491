"""The firmware images of the power-cut runner (`hil_sim powercut`) are what their generator writes
and parse with the host's reader: versions 1.0.0 and 1.1.0 for the host target, tag valid."""

from __future__ import annotations

import runpy

from forceskill.model import fwimage as fw
from helpers.paths import REPO

VECTORS = REPO / "tests" / "vectors"


def test_powercut_images_are_reproduced_and_authentic() -> None:
    gen = runpy.run_path(str(VECTORS / "powercut_fw_generate.py"))
    images = gen["images"]()
    assert len(images) == 2
    for path, data in images.items():
        assert path.read_bytes() == data, "run tests/vectors/powercut_fw_generate.py"
        img = fw.parse_image(data, fw.DEV_KEY)
        assert img.authentic
    versions = sorted(fw.parse_image(d, fw.DEV_KEY).version for d in images.values())
    assert versions == ["1.0.0", "1.1.0"]
