"""The CAN journey of test_journey.py (record a demonstration, fit, upload with read-back, run at
1x and 1.5x, tracking figures, a sequence, cantools on every device frame) with the device on a
SocketCAN interface (`hil_sim serve --socketcan vcan0`) and the host tools on python-can's
`socketcan` interface. Skipped with a message where the kernel has no AF_CAN or no vcan0."""

from __future__ import annotations

import time

import pytest
import test_journey as journey_tests

from helpers.canbus import JOURNEY_HOST_TIMEOUT_MS, SCENARIOS
from helpers.socketcan import SocketCANServer, vcan_or_skip

# The journey's tests, collected here again on the SocketCAN server, in its order (the record test
# leaves what the others read)
test_record_fit_upload_run = journey_tests.test_record_fit_upload_run
test_tracking_figures_1x_and_1_5x = journey_tests.test_tracking_figures_1x_and_1_5x
test_sequence_in_series = journey_tests.test_sequence_in_series
test_cantools_decodes_every_device_frame = journey_tests.test_cantools_decodes_every_device_frame


@pytest.fixture(scope="module")
def server():
    """The journey's device on the interface, with the journey's host-silence timeout (helpers.canbus)."""
    s = SocketCANServer(
        SCENARIOS / "pressing_task1_demo.toml", vcan_or_skip(), host_timeout_ms=JOURNEY_HOST_TIMEOUT_MS
    )
    time.sleep(0.2)
    yield s
    err = s.stop()
    print(err.strip().splitlines()[-1] if err.strip() else "hil_sim serve: no stop line")  # shown by -s


@pytest.fixture(scope="module")
def journey(server, tmp_path_factory):
    return {"dir": tmp_path_factory.mktemp("journey_socketcan"), "server": server}
