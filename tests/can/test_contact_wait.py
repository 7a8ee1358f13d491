"""A phase that waits for contact, over CAN: a periodic wiping skill (fitted from the HIL wiping
demonstration, hil_sim/scenarios/wiping_strokes_demo.toml) with ``fit --contact-wait 2,0.05``
and the same skill without it run 8 cycles on two scenarios whose contact is lost 3 s into the
execution: hil_sim/scenarios/contact_surface_ends.toml (the surface steps 5 mm away for 0.5 s)
and contact_part_lifted.toml (the part lifted 10 mm over 0.1 s, held off 0.6 s, put back).

With the wait: the phase held for about the loss (the hold the device reports, DID_CONTACT_WAIT,
printed by ``run``), f_hat stood still while the contact was lost and then went on where it was
(the rollout of the skill, late by the hold), the contact force after re-contact stayed within
the force limit and the run did not fault. Without: f_hat ran on through its phase (the rollout
on time) while the contact was lost."""

from __future__ import annotations

import subprocess
import time

import numpy as np
import pytest

from forceskill.model import periodic
from forceskill.model.skill import Skill
from helpers.canbus import JOURNEY_HOST_TIMEOUT_MS, SCENARIOS, Server, forceskill
from helpers.paths import hil_sim_path

K_NPM = 2000.0
CYCLES = 8
LOSS_AT_S = 3.0  # the scenarios' away_at_s
FORCE_LIMIT_N = 50.0  # the device's default force limit (wire.toml FORCE_LIMIT_N)
# scenario, loss duration (s: away_for_s, and the ramp of the lifted part once)
SCENARIOS_LOSS = (("contact_surface_ends.toml", 0.5), ("contact_part_lifted.toml", 0.7))


@pytest.fixture(scope="module")
def skills(tmp_path_factory: pytest.TempPathFactory) -> dict[str, str]:
    d = tmp_path_factory.mktemp("contact")
    demo = d / "wipe.csv"
    subprocess.run(
        [str(hil_sim_path()), "run", str(SCENARIOS / "wiping_strokes_demo.toml"), "-o", str(demo)],
        check=True,
        capture_output=True,
    )
    from forceskill import cli

    for name, extra in (("wait", ["--contact-wait", "2,0.05"]), ("plain", [])):
        assert (
            cli.main(
                ["fit", str(demo), "-k", str(K_NPM), "--periodic", "-o", str(d / f"{name}.skill"), *extra]
            )
            == 0
        )
    return {"wait": str(d / "wait.skill"), "plain": str(d / "plain.skill")}


def _lag(f_hat: np.ndarray, ref: np.ndarray) -> int:
    """How many ticks the phase is behind the rollout in the second after the start's blend (1 s):
    the best match over 0..299 (the telemetry's row 0 is the execution's first tick; the phase
    also waits at the start while the contact force builds up under the blend)."""
    m = 1000
    errs = [float(np.mean((f_hat[i + 1000 : i + 1000 + m] - ref[1000 : 1000 + m]) ** 2)) for i in range(300)]
    return int(np.argmin(errs))


@pytest.mark.parametrize("scenario,loss_s", SCENARIOS_LOSS)
def test_the_phase_waits_for_contact_and_resumes_where_it_was(
    skills, tmp_path, capsys, scenario, loss_s
) -> None:  # type: ignore[no-untyped-def]
    server = Server(SCENARIOS / scenario, host_timeout_ms=JOURNEY_HOST_TIMEOUT_MS)
    try:
        time.sleep(0.2)
        bus = server.bus_args()
        for slot, name in ((1, "wait"), (2, "plain")):
            out = forceskill(capsys, "upload", skills[name], "--slot", str(slot), "-q", *bus)
            assert "verified by read-back" in out
        sk = Skill.read(skills["wait"])
        assert sk.contact_wait and sk.contact_threshold_N == pytest.approx(2.0)
        _, rollout = periodic.rollout(sk, cycles=CYCLES + 2)
        ref = rollout[1:]  # the n-th tick's f_hat is the state after n + 1 steps
        dt = sk.dt_s
        res = {}
        for slot, name in ((1, "wait"), (2, "plain")):
            csv = tmp_path / f"{name}.csv"
            out = forceskill(
                capsys, "run", "--slot", str(slot), "--cycles", str(CYCLES), "--csv", str(csv), *bus
            )
            cols = np.genfromtxt(csv, delimiter=",", names=True)
            f_hat, f_c = np.asarray(cols["f_hat"]), np.asarray(cols["f_contact"])
            res[name] = (out, f_hat, f_c, _lag(f_hat, ref))
        out, f_hat, f_c, lag0 = res["wait"]
        hold_ms = int(out.split("the phase held ")[1].split(" ms")[0])
        a, b = int(LOSS_AT_S / dt), int((LOSS_AT_S + loss_s) / dt)
        shift = int(round(hold_ms * 1e-3 / dt))
        # the rollout late by the hold after the loss (the tracking is good: f_hat is the
        # reference itself), on time before it
        after = np.arange(b + 300, min(f_hat.size, ref.size + shift, int((CYCLES * sk.duration_s) / dt)))
        e_before = float(np.sqrt(np.mean((f_hat[1000 + lag0 : a] - ref[1000 : a - lag0]) ** 2)))
        e_after = float(np.sqrt(np.mean((f_hat[after] - ref[after - shift]) ** 2)))
        held = f_hat[a + 100 : b - 50]
        after_contact = f_c[b : b + 1000]
        print(
            f"{scenario}: hold {hold_ms} ms, {lag0} of them at the start, for a {loss_s * 1e3:.0f} ms loss; "
            f"f_hat while lost "
            f"{np.min(held):.3f}..{np.max(held):.3f} N; f_hat vs rollout RMS {e_before:.4f} N before, "
            f"{e_after:.4f} N after (late by the hold); contact force after re-contact max "
            f"{np.max(after_contact):.2f} N, largest step {np.max(np.abs(np.diff(after_contact))):.3f} N/tick"
        )
        assert abs(hold_ms - lag0 - loss_s * 1e3) <= 0.2 * loss_s * 1e3, out
        assert np.ptp(held) <= 0.1  # the reference stood still while the contact was lost
        assert e_before <= 0.01 and e_after <= 0.02  # one/two telemetry steps of 0.01 N
        assert np.max(after_contact) <= FORCE_LIMIT_N
        # no step of f_hat from the loss on (the start's blend from the measured force, noise
        # included, is the start's own)
        assert np.max(np.abs(np.diff(f_hat[a:]))) <= 2.0 * np.max(np.abs(np.diff(ref)))
        # without the wait the reference runs on through its phase, on time
        out_p, f_hat_p, _, lag_p = res["plain"]
        assert lag_p <= 2, lag_p  # the telemetry's first row: the execution's first tick or next to it
        assert "contact wait" not in out_p
        n = min(f_hat_p.size, int(CYCLES * sk.duration_s / dt))
        e_plain = float(np.sqrt(np.mean((f_hat_p[1000 + lag_p : n] - ref[1000 : n - lag_p]) ** 2)))
        print(
            f"{scenario} without the wait: f_hat vs rollout on time ({lag_p} ticks) RMS {e_plain:.4f} N, "
            f"while lost {np.min(f_hat_p[a + 100 : b - 50]):.3f}..{np.max(f_hat_p[a + 100 : b - 50]):.3f} N"
        )
        assert e_plain <= 0.01 and np.ptp(f_hat_p[a + 100 : b - 50]) > 1.0
    finally:
        server.stop()
