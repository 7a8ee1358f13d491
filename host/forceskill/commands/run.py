"""forceskill run: execute a skill (or a sequence of skills) on the device, watch it, report the
force tracking from the telemetry."""

from __future__ import annotations

import argparse
import math
import re
import sys
import time
from typing import Any, TextIO

import numpy as np

from .. import wire as W
from ..errors import (
    ERR_FORCE_GAIN_INERTIA,
    ERR_OUTPUT_IS_INPUT,
    ERR_PERIODIC_ARGS,
    ERR_RUN_FAULT,
    ERR_SKILL_PEAK,
    ERR_TELEMETRY_GAP,
    FsError,
    fault_text,
)
from ..link import ERR_LINK_ARGS, ERR_LINK_STATE
from ..link import uds as U
from ..link.device import Device
from ..model.limits import (
    check_force_limit,
    check_skill_stiffness,
    path_peak_N,
    path_problem,
    peak_problem,
    skill_peak_N,
)
from ..model.periodic import check_amplitude_scale
from ..model.scales import check_path_scale, check_scales
from ..model.skill import Skill
from ..outputs import STDOUT, Outputs, check_target, format_rows
from ..wire.dbc import END_POLICIES
from ._args import add_force_limit, add_path_scale, add_scales, float_arg
from ._common import (
    Stream,
    add_common,
    close_log,
    columns,
    connect,
    link_errors,
    open_log,
    sigint_flag,
    tracking,
)

#: The longest run of lost telemetry a run's figures are measured across (as a recording's --max-gap).
MAX_TELEMETRY_GAP_MS = 100

#: Rows kept after a fault's tick: the device's longest safe-stop ramp (50 ticks; 40 by default)
#: and the zero after it. The device keeps the telemetry's rate in FAULT, so they are measured.
FAULT_RAMP_TICKS = 50

_STEP = re.compile(r"^\s*(\d+)\s*:\s*([0-9.]+)\s*(ms|s|c)?\s*$")
#: the most cycles one run of a periodic skill asks for (the wire's u16)
CYCLES_MAX = 65535


def parse_sequence(text: str) -> list[tuple[int, float]]:
    """'1:8s,2:9s' -> [(1, 8.0), (2, 9.0)] (slot, duration in s; 'ms' allowed); 'SLOT:Nc' is N
    cycles of a periodic skill, returned as -N (resolve_cycles turns it into seconds)."""
    steps = []
    for part in text.split(","):
        m = _STEP.match(part)
        if not m:
            raise FsError(
                ERR_LINK_ARGS, f"--sequence step {part.strip()!r} is not SLOT:DURATION (e.g. 1:8s or 2:20c)"
            )
        if m.group(3) == "c":
            n = float(m.group(2))
            if not (n == int(n) and 1 <= n <= CYCLES_MAX):
                raise FsError(
                    ERR_LINK_ARGS,
                    f"--sequence cycles must be a whole number 1..{CYCLES_MAX}: {part.strip()!r}",
                )
            steps.append((int(m.group(1)), -n))
            continue
        d = float(m.group(2)) * (1e-3 if m.group(3) == "ms" else 1.0)
        if not 0.0 < d <= 3600.0:
            raise FsError(ERR_LINK_ARGS, f"--sequence duration must be in (0, 3600] s: {part.strip()!r}")
        steps.append((int(m.group(1)), d))
    if not 1 <= len(steps) <= 8:
        raise FsError(ERR_LINK_ARGS, f"--sequence takes 1..8 steps, got {len(steps)}")
    return steps


def resolve_cycles(
    steps: list[tuple[int, float]], directory: dict[int, dict[str, Any]], time_scale: float
) -> list[tuple[int, float]]:
    """A sequence's cycle counts (negative durations from parse_sequence) as seconds: N times the
    slot's period (its duration) times the time scale, within (0, 3600] s."""
    out = []
    for slot, d in steps:
        s = -d * float(directory[slot]["duration_s"]) * time_scale if d < 0.0 else d
        if not 0.0 < s <= 3600.0:
            raise FsError(
                ERR_LINK_ARGS, f"--sequence: {s:g} s of cycles of slot {slot} is not in (0, 3600] s"
            )
        out.append((slot, s))
    return out


def _as_sent(v: float) -> float:
    """A scale as the device receives it (a whole number of the wire's steps)."""
    return W.from_steps(W.to_steps(v))


def check_slot_forces(
    client: Any,
    dev: Device,
    slots: list[int],
    directory: dict[int, dict[str, Any]],
    goal_scale: float,
    time_scale: float,
    force_limit_N: float,
    amplitude_scale: float = 1.0,
    path_scale: float = 1.0,
) -> dict[int, Skill]:
    """Read each slot's skill back (RequestUpload) and refuse, before anything moves, a skill
    stiffer than the device's stiffness limit (690), a goal scale that takes its rollout's peak
    above the force limit, a y path whose acceleration asks more than it (``path_peak_N``), or a
    rollout that is not finite (662); a periodic skill's peak is that of one cycle at the goal,
    amplitude and time scales. Returns the skills read back by slot."""
    skills: dict[int, Skill] = {}

    def call(what: str, fn: Any) -> Any:
        return U.call(what, fn, dev.node)

    call("session change", lambda: client.change_session(0x02))
    try:
        limit_Npm = U.stiffness_limit(client, dev.node)
        obj = W.Object.unpack(U.read_did(client, U.DID_OBJECT, dev.node))
        for slot in dict.fromkeys(slots):
            image = U.upload(client, dev.node, slot, int(directory[slot]["length"]))
            sk = Skill.from_bytes(image)
            skills[slot] = sk
            check_skill_stiffness(sk, f"slot {slot}", limit_Npm, dev.node, "nothing was started")
            if obj.use_model:
                check_object_inertia(sk, f"slot {slot} of node {dev.node}", obj.m_v_kg)
            if sk.periodic:
                from ..model.periodic import rollout as periodic_rollout

                _, f = periodic_rollout(sk, 1.0, goal_scale, amplitude_scale, time_scale)
                peak = float(np.max(np.abs(f))) if np.all(np.isfinite(f)) else math.inf
                problem = peak_problem(peak, 1.0, force_limit_N)
            else:
                peak = skill_peak_N(sk, time_scale)
                problem = peak_problem(peak, goal_scale, force_limit_N)
            if problem:
                limit = (
                    f"; largest goal scale {force_limit_N / peak:.4g}" if 0.0 < peak < float("inf") else ""
                )
                raise FsError(
                    ERR_SKILL_PEAK, f"slot {slot} of node {dev.node}: {problem}{limit}; nothing was started"
                )
            problem = path_problem(path_peak_N(sk, path_scale, time_scale), path_scale, force_limit_N)
            if problem:
                raise FsError(
                    ERR_SKILL_PEAK, f"slot {slot} of node {dev.node}: {problem}; nothing was started"
                )
    finally:
        try:
            client.change_session(0x01)
        except Exception:
            pass
    return skills


def check_object_inertia(sk: Skill, what: str, object_mass_kg: float) -> None:
    """Refuse (112) a skill whose force gains feed back more than the object's inertia on the
    device's object (k_f*m_v/m_d >= 1, k_f = kkf/k): its force loop would oscillate into the
    slew limit (fault 508) within a second of contact. The remedy is named."""
    if not object_mass_kg > 0.0:
        return
    k_f = sk.kkf_Npm / sk.stiffness_Npm
    ratio = k_f * object_mass_kg / sk.m_d_kg
    if ratio >= 1.0:
        raise FsError(
            ERR_FORCE_GAIN_INERTIA,
            f"{what}: its force gains are unstable on the device's {object_mass_kg:g} kg object "
            f"(k_f*m_v/m_d = {ratio:.3g} >= 1, k_f = kkf/k = {k_f:.4g}, m_d = {sk.m_d_kg:g} kg: the "
            f"force loop feeds back the object's inertia, fault 508 within a second of contact); fit "
            f"it again with --object-mass {object_mass_kg:g}; nothing was started",
        )


def path_tracking(
    cols: dict[str, np.ndarray], tick16: np.ndarray, path_m: np.ndarray, after_tick: int, start_tick: int
) -> dict[str, float]:
    """Path tracking of a skill with a y DMP: max/RMS |y - y_d| in mm over the path's rows, with
    y_d = y(start) + p (p = rollout_path - y_start, row n+1 at the n-th tick of the execution).
    The execution started at a tick in (after_tick, start_tick] (the last IDLE status and the
    first EXECUTE status, 10 ms apart): the start within that window that fits best is used, so
    the figures are exact to within that window."""
    y = cols["y"]
    best = {"path_max_mm": float("nan"), "path_rms_mm": float("nan"), "path_extent_mm": float("nan")}
    n_ref = path_m.size - 1
    span = max(1, (start_tick - after_tick) & 0xFFFFFF)
    best_rms = float("inf")
    for d in range(1, min(span, 64) + 1):
        hits = np.flatnonzero(tick16 == ((after_tick + d) & 0xFFFF))
        if not hits.size:
            continue
        i0 = int(hits[0])
        m = min(n_ref, y.size - i0)
        if m < 2:
            continue
        e = y[i0 : i0 + m] - (y[i0] + path_m[1 : m + 1])
        rms = float(np.sqrt(np.mean(e * e)))
        if rms < best_rms:
            best_rms = rms
            best = {
                "path_max_mm": 1e3 * float(np.max(np.abs(e))),
                "path_rms_mm": 1e3 * rms,
                "path_extent_mm": 1e3 * float(np.max(np.abs(path_m))),
            }
    return best


def _fault_index(first_tick: int, n: int, fault_tick: int | None) -> int:
    """Index of the fault's tick in a contiguous telemetry run starting at first_tick (16-bit
    ticks compared modulo 2^16), clipped to the run."""
    if fault_tick is None or n == 0:
        return n - 1
    d = (fault_tick - first_tick) & 0xFFFF
    return min(d, n - 1)


def _wait_ticks(dev: Device, tick0: int, n: int, timeout_s: float) -> None:
    """Until the device's status tick is n past tick0 (24-bit) or timeout_s of wall time."""
    end = time.monotonic() + timeout_s
    while time.monotonic() < end:
        cur = dev.status
        if cur is not None and ((cur.tick - tick0) & 0xFFFFFF) >= n:
            return
        time.sleep(0.01)
        dev.check_link()


def _contact_hold_s(client: Any, dev: Device, waits: bool) -> float:
    """How long the running execution's phase has held for contact (DID_CONTACT_WAIT), s; 0
    without a contact wait."""
    if not waits:
        return 0.0
    return W.ContactWait.unpack(U.read_did(client, U.DID_CONTACT_WAIT, dev.node)).hold_ms / 1000.0


def run_on_device(
    dev: Device, args: argparse.Namespace, writer: Any = None, info: TextIO = sys.stdout
) -> dict[str, Any]:
    """Check, start, watch and stop one execution. Returns the telemetry columns (ending at the
    fault's tick if it faulted), the figures, ``fault`` (0 or its code) and ``interrupted`` (Ctrl-C:
    the device was commanded to IDLE)."""
    st = dev.status
    if st is not None and st.state != "IDLE":
        raise FsError(
            ERR_LINK_STATE,
            f"node {dev.node} is in {st.state}"
            f"{f' (fault {fault_text(st.fault_code)})' if st.fault_code else ''}; run needs IDLE "
            "(clear a fault with: forceskill status --clear)",
        )
    end_code = END_POLICIES[args.end]
    g, ts, ps = _as_sent(args.goal_scale), _as_sent(args.time_scale), _as_sent(args.path_scale)
    fault, fault_tick, interrupted, total = 0, None, False, 0.0
    with sigint_flag() as stop, U.uds_client(dev) as client:
        directory = {e["slot"]: e for e in U.slot_directory(client, dev.node)}
        if args.sequence:
            steps = parse_sequence(args.sequence)
            for slot, _ in steps:
                if slot not in directory or not directory[slot]["valid"]:
                    raise FsError(ERR_LINK_ARGS, f"slot {slot} of node {dev.node} holds no skill")
            steps = resolve_cycles(steps, directory, ts)
            data = W.RunSequence(end_code, tuple(W.RunStep(slot, g, ts, d) for slot, d in steps)).pack()
            rid, expected = U.RID_RUN_SEQUENCE, sum(d for _, d in steps)
            last_end = directory[steps[-1][0]]["end"]
            slots = [slot for slot, _ in steps]
        else:
            if args.slot is None:
                raise FsError(ERR_LINK_ARGS, "give --slot N or --sequence SLOT:DURATION,...")
            e = directory.get(args.slot)
            if e is None or not e["valid"]:
                raise FsError(ERR_LINK_ARGS, f"slot {args.slot} of node {dev.node} holds no skill")
            # the optional path scale (firmware reading skill format v3) only when it is not 1; a
            # periodic run (--cycles, --amplitude-scale) is the 12-byte start
            periodic = args.cycles is not None or args.amplitude_scale != 1.0
            cycles = 1 if args.cycles is None else args.cycles
            # --band-action stop: the start with the band stop time (periodic: 14 bytes)
            stop_ms = band_stop_ms(args)
            data = (
                W.RunPeriodic(
                    args.slot, g, ts, end_code, ps, cycles, _as_sent(args.amplitude_scale), stop_ms or None
                ).pack()
                if periodic
                else W.RunSkillBand(args.slot, g, ts, end_code, ps, stop_ms).pack()
                if stop_ms
                else W.RunSkill(args.slot, g, ts, end_code, ps if ps != 1.0 else None).pack()
            )
            period = float(e["duration_s"]) * args.time_scale
            rid, expected = U.RID_RUN_SKILL, (period * cycles if cycles > 0 else math.inf)
            last_end = e["end"]
            slots = [args.slot]
        skills = check_slot_forces(
            client, dev, slots, directory, g, ts, args.force_limit, _as_sent(args.amplitude_scale), ps
        )
        periodic_args = args.cycles is not None or args.amplitude_scale != 1.0
        if not args.sequence and periodic_args and not skills[args.slot].periodic:
            raise FsError(
                ERR_PERIODIC_ARGS,
                f"slot {args.slot} of node {dev.node} holds a discrete skill: --cycles and "
                "--amplitude-scale apply to periodic skills only; nothing was started",
            )
        waits = any(sk.contact_wait for sk in skills.values())
        banded = any(sk.band_lo_N is not None for sk in skills.values())
        path_skill = skills.get(slots[0]) if not args.sequence else None
        if path_skill is not None and not path_skill.has_y:
            path_skill = None
        end_policy = args.end if args.end != "skill" else last_end
        tail = args.hold_for if end_policy == "hold" else 0.5 + 0.05
        total = expected + tail
        if stop["stop"]:
            return {
                "columns": columns([])[0],
                "figures": tracking(columns([])[0]),
                "path": None,
                "expected_s": expected,
                "fault": 0,
                "interrupted": True,
                "started": False,
                "band": None,
                "skill": None,
            }
        notifier = dev.notifier
        assert notifier is not None
        if writer is not None:
            notifier.add_listener(writer)
        U.motion_session(client, dev)  # authenticated heartbeats and commands; the run's start
        tel = dev.start_telemetry()
        n_emcy = len(dev.emergencies)
        dev.start_heartbeat(telemetry_period_ms=getattr(args, "telemetry_period", 1))
        try:
            with link_errors(dev.node, dev.channel):
                time.sleep(0.05)
                before = dev.status
                idle_tick = before.tick if before is not None else 0
                U.call("start", lambda: client.start_routine(rid, data), dev.node)
                st = dev.wait_state({"EXECUTE", "FAULT"}, 2.0 * args.timeout)
                start_tick = st.tick
                what = f"sequence {args.sequence}" if args.sequence else f"slot {args.slot}"
                if not args.sequence and args.cycles is not None:
                    what += f", {args.cycles} cycles" if args.cycles else ", cycles until Ctrl-C"
                print(
                    f"node {dev.node}: executing {what}"
                    f", goal x{args.goal_scale:g}, time x{args.time_scale:g}, end {end_policy}: "
                    f"{expected:.3f} s + {tail:.2f} s",
                    file=info,
                    flush=True,
                )
                while True:
                    if st.state == "FAULT":
                        fault = st.fault_code
                        fault_tick = st.tick & 0xFFFF
                        emcy = dev.emergencies[n_emcy:]
                        if emcy:
                            fault, fault_tick = int(emcy[0][1]["FaultCode"]), int(emcy[0][1]["Tick"]) & 0xFFFF
                        _wait_ticks(dev, st.tick, FAULT_RAMP_TICKS + 1, 2.0 * args.timeout)  # the ramp
                        break
                    if stop["stop"]:
                        interrupted = True
                        dev.command_until("idle", {"IDLE", "FAULT"}, 2.0 * args.timeout)
                        break
                    if st.state != "EXECUTE":
                        break
                    if ((st.tick - start_tick) & 0xFFFFFF) >= total * W.TICK_HZ:
                        # a contact wait lengthens the run by the time its phase held
                        held = _contact_hold_s(client, dev, waits)
                        if expected + held + tail > total:
                            total = expected + held + tail
                            continue
                        dev.command_until("idle", {"IDLE", "FAULT"}, 2.0 * args.timeout)
                        break
                    time.sleep(0.02)
                    dev.check_link()
                    cur = dev.status
                    assert cur is not None
                    st = cur
                time.sleep(0.05)
        finally:
            dev.stop_heartbeat()
            if writer is not None:
                notifier.remove_listener(writer)
        contact = W.ContactWait.unpack(U.read_did(client, U.DID_CONTACT_WAIT, dev.node)) if waits else None
        band = W.Band.unpack(U.read_did(client, U.DID_BAND, dev.node)) if banded else None
    samples, states = dev.telemetry_samples(tel), dev.telemetry_states(tel)
    period_ms = getattr(args, "telemetry_period", 1)
    # the samples of the execution (by the device's states) within the run's window, the ticks
    # between them interpolated on the tick grid, the samples due at the period that never
    # arrived counted
    n_keep = int(round(total * W.TICK_HZ)) + 1
    grid, stream = columns(samples, period_ms, states, n_keep)
    first_tick = stream.first_tick
    i_fault = n_keep  # the figures end at the fault's row; the columns go on through its ramp
    if fault and grid["t"].size:
        i_fault = _fault_index(first_tick & 0xFFFF, grid["t"].size, fault_tick)
        n_keep = min(n_keep, i_fault + FAULT_RAMP_TICKS + 1)
    cols = {k: v[:n_keep] for k, v in grid.items()}
    measured = {k: v[: i_fault + 1] for k, v in cols.items()}
    path_fig = None
    if path_skill is not None and grid["t"].size:
        from ..model import periodic as per
        from ..model.dmp import rollout_path

        if path_skill.periodic:  # the run's cycles (until stopped: as long as the telemetry)
            n_cyc = cycles if cycles > 0 else total / (path_skill.duration_s * ts)
            _, y_hat = per.rollout_path(
                path_skill, cycles=n_cyc, time_scale=ts, path_scale=ps, ramp_in=True, ramp_out=cycles > 0
            )
        else:
            _, y_hat = rollout_path(path_skill, time_scale=ts, path_scale=ps)
        tick16 = (first_tick + np.arange(measured["t"].size)) & 0xFFFF
        path_fig = path_tracking(measured, tick16, y_hat - path_skill.y_start_m, idle_tick, start_tick)
    cols["fault"] = np.zeros(cols["t"].size)
    if fault and cols["t"].size:
        cols["fault"][i_fault:] = fault
    return {
        "columns": cols,
        "figures": tracking(measured),
        "fault_row": i_fault if fault else None,
        "path": path_fig,
        "expected_s": expected,
        "fault": fault,
        "interrupted": interrupted,
        "started": True,
        "stream": stream,
        "contact": contact,
        "band": band,
        "skill": None if args.sequence else skills.get(args.slot),
    }


CSV_COLUMNS = ("t", "x", "y", "f_contact", "f_operator", "f_cmd", "f_hat", "fault")
#: a skill with a band (format v5): the telemetry's BandOutside after the fault column
CSV_BAND_COLUMN = "band_out"
#: --band-ms's default: 50 ms outside the band in one piece
BAND_MS_DEFAULT = 50


def run_table(cols: dict[str, np.ndarray], banded: bool) -> tuple[tuple[str, ...], np.ndarray]:
    """The CSV's column names and rows: CSV_COLUMNS, and with a band CSV_BAND_COLUMN (0/1 per
    row) after them."""
    names = CSV_COLUMNS + ((CSV_BAND_COLUMN,) if banded else ())
    return names, np.column_stack([cols[k] for k in names])


def band_stop_ms(args: argparse.Namespace) -> int:
    """The run's band stop time in ms: 0 with --band-action report, else --band-ms."""
    if getattr(args, "band_action", "report") != "stop":
        return 0
    return int(getattr(args, "band_ms", BAND_MS_DEFAULT))


def band_summary(band: Any) -> str:
    """The band check's line: time outside in % of the time checked, the longest piece, the
    largest excursion in band widths, the first excursion's time."""
    pct = 100.0 * band.outside_ms / band.checked_ms if band.checked_ms else 0.0
    first = f", first at {band.first_ms / 1000.0:.3f} s" if band.outside_ms else ""
    return (
        f"outside the demonstrated band: {pct:.1f} % of the run, longest {band.longest_ms} ms, "
        f"largest {band.max_widths:.3f} band widths{first}"
    )


def write_run_plot(args: argparse.Namespace, r: dict[str, Any], outs: Outputs) -> None:
    """The run's --plot: the telemetry, the pieces outside the band and, for a --slot run of a
    skill with a band, the band on the run's time (scaled as f_hat, the skill's nominal phase:
    a contact wait's held phase is not followed)."""
    from ..plot import run_figure

    cols = r["columns"]
    sk = r.get("skill")
    band = None
    if sk is not None and sk.band_lo_N is not None:
        band = sk.band_at(cols["t"], args.goal_scale, args.time_scale, args.amplitude_scale)
    what = f"sequence {args.sequence}" if args.sequence else f"slot {args.slot}"
    title = f"node {args.node}: {what}, goal x{args.goal_scale:g}, time x{args.time_scale:g}"
    if r.get("band") is not None:
        title += "\n" + band_summary(r["band"])
    fault_t = float(cols["t"][r["fault_row"]]) if r["fault"] and cols["t"].size else None
    run_figure(cols, args.plot, title=title, band=band, fault_t=fault_t, outs=outs)


def _cmd(args: argparse.Namespace) -> int:
    check_scales(args.goal_scale, args.time_scale)
    check_path_scale(args.path_scale)
    if args.sequence and args.path_scale != 1.0:
        raise FsError(ERR_LINK_ARGS, "--path-scale applies to --slot only (a sequence runs every path at 1)")
    if args.sequence and (args.cycles is not None or args.amplitude_scale != 1.0):
        raise FsError(
            ERR_LINK_ARGS,
            "--cycles and --amplitude-scale apply to --slot only (a sequence step takes SLOT:Nc cycles)",
        )
    if args.sequence and args.band_action == "stop":
        raise FsError(
            ERR_LINK_ARGS, "--band-action stop applies to --slot only (a sequence reports its band)"
        )
    if not 1 <= args.band_ms <= 65535:
        raise FsError(ERR_LINK_ARGS, f"--band-ms must be in 1..65535: {args.band_ms}")
    if args.cycles is not None and not 0 <= args.cycles <= CYCLES_MAX:
        raise FsError(ERR_LINK_ARGS, f"--cycles must be in 0..{CYCLES_MAX} (0: until Ctrl-C): {args.cycles}")
    check_amplitude_scale(args.amplitude_scale)
    check_force_limit(args.force_limit)
    if not (math.isfinite(args.hold_for) and 0.0 <= args.hold_for <= 3600.0):
        raise FsError(ERR_LINK_ARGS, f"--hold-for must be in [0, 3600] s: {args.hold_for:g}")
    if args.sequence:
        parse_sequence(args.sequence)
    to_stdout = args.csv == STDOUT
    if args.plot:  # refused before connecting
        real = check_target(args.plot)
        if args.csv and not to_stdout and check_target(args.csv) == real:
            raise FsError(ERR_OUTPUT_IS_INPUT, f"output {args.plot!r} is given twice (--csv and --plot)")
    info = sys.stderr if to_stdout else sys.stdout
    with Outputs() as outs:
        csv_tmp = outs.add(args.csv) if args.csv and not to_stdout else None
        writer = open_log(outs, args.output) if args.output else None  # refused before connecting
        try:
            with connect(args) as dev:
                r = run_on_device(dev, args, writer, info=info)
        finally:
            if writer is not None:
                close_log(writer)
        cols, fig = r["columns"], r["figures"]
        if not r["started"]:
            print("forceskill: interrupted before the start: nothing was sent", file=sys.stderr)
            return 130
        names, block = run_table(cols, r.get("band") is not None)
        if csv_tmp is not None:
            with open(csv_tmp, "w", encoding="ascii", newline="\n") as f:
                f.write(",".join(names) + "\n" + format_rows(block))
        elif to_stdout:
            sys.stdout.write(",".join(names) + "\n" + format_rows(block))
            sys.stdout.flush()
        if args.plot:
            write_run_plot(args, r, outs)
        outs.commit()  # the telemetry, the plot and the bus log are kept on a fault or Ctrl-C too
    n, stream = cols["t"].size, r.get("stream", Stream())
    if stream.lost_samples:
        print(
            f"telemetry: {stream.lost_samples} samples lost on the bus "
            f"(longest gap {stream.longest_gap_ms} ms), "
            "interpolated from their neighbours",
            file=info,
        )
    period = getattr(args, "telemetry_period", 1)
    received = (
        f"{stream.received} samples every {period} ms, {n} rows on the 1 ms grid"
        if period > 1
        else f"{n} samples"
    )
    print(
        f"telemetry: {received} over {cols['t'][-1] if n else 0:.3f} s; "
        f"max contact force {fig['max_force_N']:.3f} N, max reference {fig['max_ref_N']:.3f} N",
        file=info,
    )
    print(
        f"force tracking: max {fig['tracking_max_pct']:.2f} %, RMS {fig['tracking_rms_pct']:.2f} % of max reference",
        file=info,
    )
    cw = r.get("contact")
    if cw is not None:
        print(
            f"contact wait: the phase held {cw.hold_ms} ms over {cw.losses} "
            f"loss{'es' if cw.losses != 1 else ''} of contact (rate at the end {cw.rate:g})",
            file=info,
        )
    band = r.get("band")
    if band is not None:
        print(band_summary(band), file=info)
    pf = r.get("path")
    if pf is not None:
        print(
            f"path tracking: max {pf['path_max_mm']:.3f} mm, RMS {pf['path_rms_mm']:.3f} mm "
            f"(y path extent {pf['path_extent_mm']:.2f} mm, path scale {args.path_scale:g})",
            file=info,
        )
    wrote = f"; telemetry written to {args.csv}" if args.csv and not to_stdout else ""
    if args.csv and not to_stdout:
        print(f"wrote {args.csv}", file=info)
    if r["fault"]:
        t_f = f" at {cols['t'][r['fault_row']]:.3f} s" if n else ""
        raise FsError(
            ERR_RUN_FAULT,
            f"node {args.node} faulted during execution: fault {fault_text(r['fault'])}{t_f}{wrote}",
        )
    if n == 0 and not r["interrupted"]:
        raise FsError(ERR_TELEMETRY_GAP, f"node {args.node}: no telemetry arrived during the run{wrote}")
    if stream.longest_gap_ms > MAX_TELEMETRY_GAP_MS:
        raise FsError(
            ERR_TELEMETRY_GAP,
            f"node {args.node}: the telemetry missed {stream.longest_gap_ms} ms in a row "
            f"(more than {MAX_TELEMETRY_GAP_MS} ms): the tracking figures above are not measured there{wrote}",
        )
    if r["interrupted"]:
        print(f"forceskill: interrupted: node {args.node} commanded to IDLE{wrote}", file=sys.stderr)
        return 130
    return 0


def register(sub: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    p = sub.add_parser(
        "run",
        help="execute a skill or a sequence on the device and report tracking",
        description="Start a skill (--slot) or a sequence (--sequence 1:8s,2:9s) with "
        "RoutineControl, keep the host heartbeat, record telemetry at 1 kHz, stop after "
        "the duration (hold: after --hold-for more seconds), and report the force "
        "tracking max/RMS in %% of the maximum reference force. Before anything is "
        "started, each slot's skill is read back and a goal scale that takes its peak "
        "above --force-limit is refused. Ctrl-C commands IDLE, writes the telemetry and "
        "exits 130; a fault writes the telemetry up to the fault and exits 2.",
    )
    p.add_argument("--slot", type=int, metavar="N", help="slot 1..8")
    p.add_argument("--sequence", metavar="SLOT:DUR,...", help="skills in series, e.g. 1:8s,2:9s")
    add_scales(p, "refused if the skill's peak times S is above --force-limit")
    add_path_scale(p, "--slot")
    p.add_argument(
        "--cycles",
        type=int,
        default=None,
        metavar="N",
        help="a periodic skill (--slot): run N periods, 0 until Ctrl-C (default 1); in a "
        "--sequence a step SLOT:Nc runs N cycles",
    )
    p.add_argument(
        "--amplitude-scale",
        type=float_arg,
        default=1.0,
        metavar="S",
        help="a periodic skill (--slot): multiply the stroke's amplitude about its mean force by S "
        "(--goal-scale sets the mean force, --time-scale the period)",
    )
    p.add_argument(
        "--end",
        choices=("skill", "hold", "release"),
        default="skill",
        help="end policy (default: the skill's own)",
    )
    p.add_argument(
        "--hold-for",
        type=float,
        default=0.5,
        metavar="S",
        help="with hold: seconds to hold the last force before stopping (0.5)",
    )
    p.add_argument(
        "--band-action",
        choices=("report", "stop"),
        default="report",
        help="a skill with a band (fit from several recordings): report the time outside it "
        "(default), or stop the run with fault 515 after --band-ms outside it in one piece",
    )
    p.add_argument(
        "--band-ms",
        type=int,
        default=BAND_MS_DEFAULT,
        metavar="N",
        help=f"with --band-action stop: ms outside the band in one piece that stop the run ({BAND_MS_DEFAULT})",
    )
    p.add_argument("-o", "--output", metavar="LOG", help="also log the bus (.blf .asc .log .trc .csv)")
    p.add_argument(
        "--plot",
        metavar="PNG",
        help="write the contact force and f_hat over the run; a skill with a band: the band "
        "(--slot) and the pieces outside it shaded",
    )
    p.add_argument(
        "--csv",
        metavar="CSV",
        help="write the telemetry as t,x,y,f_contact,f_operator,f_cmd,f_hat,fault (a skill with a "
        "band: and band_out, 1 while the contact force was outside it) "
        "('-': standard output); also on a fault (ending with the fault row) and on Ctrl-C",
    )
    add_force_limit(p)
    add_common(p)
    p.set_defaults(func=_cmd)
