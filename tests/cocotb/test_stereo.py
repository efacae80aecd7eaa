"""cocotb testbench of the generated stereo line processor (`declivity_stereo`).

Two AXI4-Stream video sources (cocotbext-axi) play a band of rows of a bundled
Middlebury pair into the left (`l_*`) and right (`r_*`) camera ports, with
random idle clocks inside the lines and horizontal blanking between them. A
monitor on the output (`m_*`, AXI4-Stream without `m_tready`: the core never
stalls) collects the output lines and a scoreboard checks every beat against
golden's hardware-parity output for the same band (`declivity depth
--hardware-parity`, computed from the pixels by the floating-point model, no
rtl code):

- the disparity, `m_tdata[13:0]`, equal to golden's `disparity16.png`;
- `m_tdata[15:14]` zero;
- the depth, `m_tdata[31:16]`, within the datasheet's bound of golden's
  `depth_mm.png` for the camera the core was generated for. Golden writes
  `round(1000 f b / d)`; the hardware's depth stage is within ½ + Z·2⁻¹⁵ mm of
  the exact `f b / d`, so the two differ by at most 1 + Z·2⁻¹⁵ mm (golden's
  rounding adds ½). Both are 0 where the disparity is 0;
- the frame structure: `m_tuser` on the first beat of the frame only,
  `m_tlast` on each line's last beat only, every output line as wide as the
  input, the beats of a line on consecutive clocks, as many output lines as
  input lines;
- the status counters (`records_dropped`, `lines_dropped`, `pixels_dropped`,
  `lines_wide`, `lines_unpaired`) do not move on this clean input, and `lines_full` stays 0
  (the 32-cell sensor matcher holds the 128 declivities a line the detector
  keeps; tsukuba's rows have fewer).

With `STEREO_RESET_AT=N`, the same band is first played and cut short by the
reset `N` clocks after its start (inside a line), which the sources and the
monitor take as cocotbext-axi's reset; the band then played again must come
out as above, beat for beat, with the status counters back at zero.

The output's contract is asserted on every clock: with no `m_tready`, the sink
takes a beat on every clock `m_tvalid` is high. `STEREO_SINK_STALL=p` models a
sink that is not ready on a share `p` of the clocks; each beat it would miss
is reported as lost.

The pytest side (`test_stereo_band`, `test_reset_mid_frame`, `test_perturbed_beat_fails`,
`test_sink_that_stalls_breaks_the_output_contract`) writes the
IP folder with `declivity verilog`, cuts the band into PNGs, runs golden with
`declivity depth`, builds the core with cocotb's runner under Icarus or
Verilator and runs the cocotb test below in the simulator. The perturbation
test flips one expected disparity and asserts that the scoreboard then fails;
the stalling-sink test, that the contract's assertion then fails.
"""

from __future__ import annotations

import logging
import os
import random
import shutil
import subprocess
import xml.etree.ElementTree as ElementTree
from dataclasses import dataclass
from pathlib import Path
from typing import Iterator

import pytest

# ---------------------------------------------------------------------------
# Shared constants (both the pytest side and the simulator side read them).

#: The repository (tests/cocotb/ is two levels under it).
REPO = Path(__file__).resolve().parents[2]

#: The depth stage's camera when `declivity verilog` is given none: the Middlebury 2014
#: Motorcycle pair at quarter size (datasheet, "Generation parameters").
FOCAL_PX = 994.97775
BASELINE_M = 0.193001

#: Disparity field of `m_tdata`: 14 bits, 4 fraction bits (1/16 px), in the `sd` configuration.
DISPARITY_BITS = 14

#: The scoreboard's errors, one a line, written into the simulator's working folder.
SCOREBOARD_FILE = "scoreboard_errors.txt"

#: Clock period of the testbench (the core has one clock, and a synchronous active-high reset).
CLOCK_NS = 10

# ---------------------------------------------------------------------------
# Simulator side: the cocotb test.

try:  # The simulator imports this module with cocotb; plain pytest collection needs it too.
    import cocotb
    from cocotb.clock import Clock
    from cocotb.triggers import ClockCycles, FallingEdge, RisingEdge, with_timeout
    from cocotbext.axi import AxiStreamBus, AxiStreamFrame, AxiStreamMonitor, AxiStreamSource
except ImportError:  # pragma: no cover - the requirements are missing; pytest reports it below.
    cocotb = None  # type: ignore[assignment]


@dataclass(frozen=True)
class Band:
    """The band of rows streamed, and golden's output for it, as the pytest side wrote them."""

    left: list[list[int]]
    right: list[list[int]]
    disparity16: list[list[int]]
    depth_mm: list[list[int]]
    dispmax_lsb: int

    @property
    def width(self) -> int:
        """Pixels per line."""
        return len(self.left[0])

    @property
    def height(self) -> int:
        """Lines in the band (the frame's rows)."""
        return len(self.left)


def read_png_rows(path: Path) -> list[list[int]]:
    """The rows of a greyscale PNG (8- or 16-bit) as lists of integers."""
    from PIL import Image

    with Image.open(path) as img:
        width, height = img.size
        pixels = list(img.getdata())
    return [pixels[y * width : (y + 1) * width] for y in range(height)]


def load_band_from_env() -> Band:
    """The band the pytest side prepared, from the paths in the environment."""
    band_dir = Path(os.environ["STEREO_BAND_DIR"])
    return Band(
        left=read_png_rows(band_dir / "left.png"),
        right=read_png_rows(band_dir / "right.png"),
        disparity16=read_png_rows(band_dir / "golden" / "disparity16.png"),
        depth_mm=read_png_rows(band_dir / "golden" / "depth_mm.png"),
        dispmax_lsb=int(os.environ["STEREO_DISPMAX_LSB"]),
    )


def depth_tolerance_mm(golden_mm: int) -> float:
    """Largest |hardware − golden| depth allowed at golden's depth `golden_mm`.

    The datasheet bounds the depth stage by ½ + Z·2⁻¹⁵ mm from the exact f·b/d;
    golden's PNG holds f·b/d rounded to the millimetre (½ more).
    """
    return 1.0 + golden_mm / 2**15


def idle_pattern(rng: random.Random, idle_share: float) -> Iterator[int]:
    """A pause generator for an AxiStreamSource: 1 (tvalid held low) on a share of the clocks."""
    while True:
        yield 1 if rng.random() < idle_share else 0


class Scoreboard:
    """Compares each output line with golden's and keeps every mismatch found."""

    def __init__(self, band: Band, perturb_beat: int | None) -> None:
        """Expected lines from `band`; `perturb_beat` (beat index in the frame) gets a wrong disparity."""
        self.band = band
        self.expected_disparity = [row[:] for row in band.disparity16]
        if perturb_beat is not None:
            y, x = divmod(perturb_beat, band.width)
            # One LSB (1/16 px) off the golden value: the smallest error the check must see.
            self.expected_disparity[y][x] ^= 1
        self.errors: list[str] = []
        self.lines_checked = 0
        self.beats_checked = 0

    def check_line(self, frame: AxiStreamFrame) -> None:
        """Checks the next output line: width, tuser and every beat's disparity and depth."""
        y = self.lines_checked
        self.lines_checked += 1
        if y >= self.band.height:
            self.errors.append(f"output line {y}: more lines out than the {self.band.height} in")
            return
        beats = list(frame.tdata)
        tuser = frame.tuser if isinstance(frame.tuser, list) else [frame.tuser] * len(beats)
        if len(beats) != self.band.width:
            self.errors.append(f"output line {y}: {len(beats)} beats, the input line has {self.band.width}")
        for x, word in enumerate(beats[: self.band.width]):
            self.beats_checked += 1
            want_tuser = 1 if (y, x) == (0, 0) else 0
            if int(tuser[x]) != want_tuser:
                self.errors.append(f"({x}, {y}): m_tuser {int(tuser[x])}, expected {want_tuser}")
            disparity = word & ((1 << DISPARITY_BITS) - 1)
            if (word >> DISPARITY_BITS) & 0x3:
                self.errors.append(f"({x}, {y}): m_tdata[15:14] = {(word >> 14) & 3}, expected 0")
            want = self.expected_disparity[y][x]
            if disparity != want:
                self.errors.append(f"({x}, {y}): disparity {disparity}/16 px, golden's hardware parity {want}/16 px")
            depth = word >> 16
            want_depth = self.band.depth_mm[y][x]
            if (depth == 0) != (want_depth == 0) or abs(depth - want_depth) > depth_tolerance_mm(want_depth):
                self.errors.append(f"({x}, {y}): depth {depth} mm, golden {want_depth} mm (bound ±{depth_tolerance_mm(want_depth):.2f})")


STATUS_COUNTERS = ("records_dropped", "lines_dropped", "pixels_dropped", "lines_full", "lines_wide", "lines_unpaired")


async def watch_clocks(dut, errors: list[str], width: int, beats: list[int], sink_stall: float, rng: random.Random) -> None:
    """Every clock: the beats of a line on consecutive clocks, `m_tlast` only on a line's
    last beat, and the status counters unchanged from their values at the start.
    `beats[0]` counts every output beat seen.

    The output contract, asserted: the core has no `m_tready`, so its sink must take a beat
    on every clock `m_tvalid` is high (datasheet, "Stream rules"). The sink modelled here is
    not ready on a share `sink_stall` of the clocks (0: always ready, a sink that keeps the
    contract); a beat offered on such a clock is lost, and reported."""
    start = {name: int(getattr(dut, name).value) for name in STATUS_COUNTERS}
    in_line = 0  # beats of the current output line so far
    clock = 0
    while True:
        await RisingEdge(dut.clock)
        clock += 1
        sink_ready = rng.random() >= sink_stall
        if int(dut.m_tvalid.value) and not sink_ready:
            errors.append(f"beat lost on clock {clock}: m_tvalid high while the sink was not ready "
                          "(no m_tready: the sink must take a beat on every clock it is offered)")
        for name, value in start.items():
            now = int(getattr(dut, name).value)
            if now != value:
                errors.append(f"status counter {name} moved from {value} to {now}")
                start[name] = now
        if int(dut.m_tvalid.value):
            beats[0] += 1
            in_line += 1
            last = int(dut.m_tlast.value)
            if last != (in_line == width):
                errors.append(f"m_tlast {last} on beat {in_line} of a {width}-pixel line")
            if last:
                in_line = 0
        elif in_line:
            errors.append(f"m_tvalid low after beat {in_line} of a line: the beats of a line are not consecutive")
            in_line = 0


#: The core's ports (datasheet, "Ports"), looked up by name before any bus is made.
PORTS = (
    "clock", "reset", "l_tdata", "l_tvalid", "l_tuser", "l_tlast", "l_tready",
    "r_tdata", "r_tvalid", "r_tuser", "r_tlast", "r_tready", "dispmin", "dispmax", "height",
    "m_tvalid", "m_tdata", "m_tuser", "m_tlast", *STATUS_COUNTERS,
)


def fetch_ports(dut) -> None:
    """Looks up every port of the core by name, before the buses probe for absent signals.

    Under Verilator 5.006 with cocotb 1.9, a lookup of an absent name (the buses' optional
    tkeep, tid, tdest, and the output's tready) makes cocotb discover the module's signals
    by iteration, and handles found that way neither take writes nor show new values (the
    sources' tvalid never reached the core). Handles looked up by name are cached, and the
    buses then reuse them."""
    for name in PORTS:
        getattr(dut, name)


async def play_camera(source: AxiStreamSource, rows: list[list[int]], rng: random.Random, hblank_max: int, clock) -> None:
    """Sends `rows` as one frame: a line per AXI4-Stream packet (tlast on its last pixel),
    tuser on the frame's first pixel, then 1..hblank_max idle clocks of horizontal blanking."""
    for y, row in enumerate(rows):
        tuser = [1 if (y, x) == (0, 0) else 0 for x in range(len(row))]
        await source.send(AxiStreamFrame(tdata=bytes(row), tuser=tuser))
        await source.wait()
        await ClockCycles(clock, rng.randint(1, hblank_max))


if cocotb is not None:

    @cocotb.test()
    async def stream_band_against_golden(dut) -> None:
        """Streams the band through both cameras and checks every output beat against golden."""
        band = load_band_from_env()
        seed = int(os.environ.get("STEREO_SEED", "1"))
        idle_share = float(os.environ.get("STEREO_IDLE", "0.1"))
        hblank_max = int(os.environ.get("STEREO_HBLANK", "32"))
        perturb = os.environ.get("STEREO_PERTURB_BEAT")
        sink_stall = float(os.environ.get("STEREO_SINK_STALL", "0"))
        rng = random.Random(seed)

        reset_at = os.environ.get("STEREO_RESET_AT")
        fetch_ports(dut)
        cocotb.start_soon(Clock(dut.clock, CLOCK_NS, units="ns").start())
        dut.reset.value = 0
        dut.dispmin.value = 0
        dut.dispmax.value = band.dispmax_lsb
        dut.height.value = band.height
        for side in ("l", "r"):
            getattr(dut, f"{side}_tvalid").value = 0
        left = AxiStreamSource(AxiStreamBus.from_prefix(dut, "l"), dut.clock, dut.reset)
        right = AxiStreamSource(AxiStreamBus.from_prefix(dut, "r"), dut.clock, dut.reset)
        left.set_pause_generator(idle_pattern(random.Random(rng.random()), idle_share))
        right.set_pause_generator(idle_pattern(random.Random(rng.random()), idle_share))
        # One 32-bit word a beat (no tkeep): a single lane, not four bytes.
        sink = AxiStreamMonitor(AxiStreamBus.from_prefix(dut, "m"), dut.clock, dut.reset, byte_lanes=1)
        for component in (left, right, sink):
            component.log.setLevel(logging.WARNING)  # no line of log per frame
        scoreboard = Scoreboard(band, int(perturb) if perturb else None)
        errors = scoreboard.errors
        # A few clocks for the registers' initial values to settle, then the frame.
        await ClockCycles(dut.clock, 4)
        if reset_at:
            # The band, cut short by a reset inside one of its lines: the sources drop the
            # rest of their line (cocotbext-axi flushes on reset) and the band is played anew.
            players = [
                cocotb.start_soon(play_camera(source, rows, random.Random(rng.random()), hblank_max, dut.clock))
                for source, rows in ((left, band.left), (right, band.right))
            ]
            await ClockCycles(dut.clock, int(reset_at))
            for player in players:
                player.kill()
            left.clear()
            right.clear()
            await FallingEdge(dut.clock)
            dut.reset.value = 1
            await ClockCycles(dut.clock, 2)
            await FallingEdge(dut.clock)
            dut.reset.value = 0
            sink.clear()
            for name in STATUS_COUNTERS:
                if int(getattr(dut, name).value) != 0:
                    errors.append(f"status counter {name} is {int(getattr(dut, name).value)} after the reset")
        beats = [0]
        cocotb.start_soon(watch_clocks(dut, errors, band.width, beats, sink_stall, random.Random(rng.random())))
        cocotb.start_soon(play_camera(left, band.left, random.Random(rng.random()), hblank_max, dut.clock))
        cocotb.start_soon(play_camera(right, band.right, random.Random(rng.random()), hblank_max, dut.clock))

        # The last line leaves after the scanline latency (a few thousand clocks for a
        # 384-pixel line) and the median's flush; 20 line periods per row is ample.
        timeout_clocks = 20_000 + 20 * band.height * (band.width + hblank_max) * 2
        for _ in range(band.height):
            frame = await with_timeout(sink.recv(), timeout_clocks * CLOCK_NS, "ns")
            scoreboard.check_line(frame)
        # Nothing after the frame: a few line periods of silence.
        await ClockCycles(dut.clock, 4 * band.width)
        await FallingEdge(dut.clock)
        if not sink.empty() or beats[0] != band.width * band.height:
            errors.append(f"{beats[0]} beats out, the frame has {band.width * band.height} pixels")
        dut._log.info("checked %d lines, %d beats; %d errors", scoreboard.lines_checked, scoreboard.beats_checked, len(errors))
        for e in errors[:20]:
            dut._log.error(e)
        # For the pytest side (cocotb's results file keeps no assertion message).
        Path(SCOREBOARD_FILE).write_text("".join(f"{e}\n" for e in errors))
        assert not errors, f"{len(errors)} errors, first: {errors[0]}"


# ---------------------------------------------------------------------------
# pytest side: golden, the IP folder, the build and the run.

#: The band of the CI run: a few real rows of tsukuba (the frame is the band).
PAIR = os.environ.get("STEREO_PAIR", "tsukuba")
ROWS = os.environ.get("STEREO_ROWS", "100:104")

SIMULATORS = ["icarus", "verilator"]


def declivity_binary() -> Path:
    """The `declivity` command: $DECLIVITY_BIN, else the workspace's release build."""
    path = Path(os.environ.get("DECLIVITY_BIN", REPO / "target" / "release" / "declivity"))
    if not path.is_file():
        pytest.fail(f"{path}: no declivity binary (cargo build --release -p cli, or set DECLIVITY_BIN)")
    return path


def run(cmd: list[str]) -> None:
    """Runs `cmd`; its output goes to the test's log, and a failure fails the test."""
    out = subprocess.run(cmd, capture_output=True, text=True)
    if out.returncode != 0:
        pytest.fail(f"{' '.join(cmd)} failed ({out.returncode}):\n{out.stdout}\n{out.stderr}")


def pair_dispmax(pair_dir: Path) -> float:
    """The pair's largest disparity from its meta.txt, as `declivity eval` reads it."""
    for line in (pair_dir / "meta.txt").read_text().splitlines():
        key, _, value = line.partition(":")
        if key.strip() == "dispmax":
            return float(value.split()[0])
    raise ValueError(f"{pair_dir / 'meta.txt'}: no dispmax")


@pytest.fixture(scope="session")
def band(tmp_path_factory: pytest.TempPathFactory) -> tuple[Path, int]:
    """Cuts rows `STEREO_ROWS` of the pair into PNGs and runs golden's hardware parity on them.

    Returns the band's folder and the `dispmax` input (1/16 px). The band is a frame of its
    own for both golden and the core (the row check and the vertical median end it)."""
    from PIL import Image

    pair_dir = REPO / "data" / "stereo" / PAIR
    out = tmp_path_factory.mktemp("band")
    start, _, end = ROWS.partition(":")
    for side in ("left", "right"):
        with Image.open(pair_dir / f"{side}_gray.png") as img:
            grey = img.convert("L")
            box = (0, int(start) if start else 0, grey.width, int(end) if end else grey.height)
            grey.crop(box).save(out / f"{side}.png")
    dispmax = pair_dispmax(pair_dir) + 1.0
    run([
        str(declivity_binary()), "depth", str(out / "left.png"), str(out / "right.png"),
        "--dispmax", str(dispmax), "--hardware-parity",
        "--focal-px", str(FOCAL_PX), "--baseline-m", str(BASELINE_M), "--out", str(out / "golden"),
    ])
    return out, round(dispmax * 16)


@pytest.fixture(scope="session")
def ip_folder(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """The core's IP folder as `declivity verilog --top stereo` writes it (sd, 32 cells, default camera)."""
    out = tmp_path_factory.mktemp("ip") / "declivity_stereo"
    run([str(declivity_binary()), "verilog", "--top", "stereo", "--out", str(out)])
    return out


_built: dict[str, Path] = {}


def build(simulator: str, ip: Path, tmp_path_factory: pytest.TempPathFactory):
    """The core built once per session and simulator, through its own file list."""
    from cocotb.runner import get_runner

    if shutil.which("iverilog" if simulator == "icarus" else "verilator") is None:
        pytest.fail(f"{simulator} is not installed (apt-get install -y iverilog verilator)")
    os.environ["DECLIVITY_STEREO_DIR"] = str(ip)
    # Verilator's C++ of the 32-cell core is large: two compile jobs (cocotb's runner calls
    # make without -j) and no C++ optimisation. A band of a few rows then builds in about
    # 90 s instead of 4 min and runs in 5 s instead of 2 s (tests/cocotb/README.md).
    os.environ.setdefault("MAKEFLAGS", "-j2 OPT_FAST=-O0 OPT_SLOW=-O0 OPT_GLOBAL=-O0")
    runner = get_runner(simulator)
    if simulator not in _built:
        build_dir = tmp_path_factory.mktemp(f"build_{simulator}")
        file_list = str(ip / "declivity_stereo.f")
        args = ["-c", file_list] if simulator == "icarus" else ["-f", file_list, "-Wno-fatal", "-Wno-lint", "-Wno-style"]
        runner.build(hdl_toplevel="declivity_stereo", build_args=args, build_dir=build_dir, timescale=("1ns", "1ps"))
        _built[simulator] = build_dir
    return runner, _built[simulator]


def run_cocotb(simulator: str, ip: Path, band: tuple[Path, int], tmp_path_factory: pytest.TempPathFactory, extra: dict[str, str]) -> tuple[int, int, str]:
    """Runs the cocotb test in the simulator; returns (tests, failures, the scoreboard's errors)."""
    from cocotb.runner import get_results

    runner, build_dir = build(simulator, ip, tmp_path_factory)
    band_dir, dispmax_lsb = band
    env = {"STEREO_BAND_DIR": str(band_dir), "STEREO_DISPMAX_LSB": str(dispmax_lsb), **extra}
    test_dir = tmp_path_factory.mktemp(f"run_{simulator}")
    try:
        runner.test(
            test_module="test_stereo",
            hdl_toplevel="declivity_stereo",
            hdl_toplevel_lang="verilog",
            build_dir=build_dir,
            test_dir=test_dir,
            extra_env=env,
        )
    except SystemExit:
        # Under pytest, cocotb's runner exits when a cocotb test fails; the results say which.
        pass
    # Under pytest the runner names the results file after the pytest test: the one file
    # the run leaves in test_dir whose name starts with it.
    found = [p for p in test_dir.iterdir() if p.is_file() and p.name.startswith(runner.current_test_name)]
    if len(found) != 1:
        pytest.fail(f"{simulator}: no results file of the cocotb run in {test_dir}")
    results = found[0]
    tests, failed = get_results(results)
    errors = test_dir / SCOREBOARD_FILE
    messages = errors.read_text() if errors.is_file() else " ".join(f.get("message") or "" for f in ElementTree.parse(results).iter("failure"))
    return tests, failed, messages


@pytest.mark.parametrize("simulator", SIMULATORS)
def test_stereo_band(simulator: str, ip_folder: Path, band: tuple[Path, int], tmp_path_factory: pytest.TempPathFactory) -> None:
    """Every output beat of the band equals golden's hardware parity; frame and counters clean."""
    tests, failed, messages = run_cocotb(simulator, ip_folder, band, tmp_path_factory, {})
    assert (tests, failed) == (1, 0), f"{simulator}: the cocotb test failed: {messages}"


@pytest.mark.parametrize("simulator", SIMULATORS)
def test_reset_mid_frame(simulator: str, ip_folder: Path, band: tuple[Path, int], tmp_path_factory: pytest.TempPathFactory) -> None:
    """A reset inside the second line of a frame: the frame played again after it equals
    golden's hardware parity, beat for beat, and the counters restart from zero."""
    band_dir, _ = band
    width = len(read_png_rows(band_dir / "left.png")[0])
    tests, failed, messages = run_cocotb(simulator, ip_folder, band, tmp_path_factory, {"STEREO_RESET_AT": str(width + width // 2)})
    assert (tests, failed) == (1, 0), f"{simulator}: the cocotb test after a reset failed: {messages}"


@pytest.mark.parametrize("simulator", SIMULATORS)
def test_perturbed_beat_fails(simulator: str, ip_folder: Path, band: tuple[Path, int], tmp_path_factory: pytest.TempPathFactory) -> None:
    """One expected disparity off by 1/16 px (a beat of the second line) fails the scoreboard,
    with that beat as its one error: the check can fail, and nothing else differs."""
    band_dir, _ = band
    width = len(read_png_rows(band_dir / "left.png")[0])
    x, y = width // 2, 1
    tests, failed, messages = run_cocotb(simulator, ip_folder, band, tmp_path_factory, {"STEREO_PERTURB_BEAT": str(y * width + x)})
    assert (tests, failed) == (1, 1), f"{simulator}: the perturbed run was expected to fail"
    errors = messages.splitlines()
    assert len(errors) == 1 and errors[0].startswith(f"({x}, {y}): disparity"), f"{simulator}: the one error expected is the perturbed beat's: {messages}"


@pytest.mark.parametrize("simulator", ["icarus"])
def test_sink_that_stalls_breaks_the_output_contract(simulator: str, ip_folder: Path, band: tuple[Path, int], tmp_path_factory: pytest.TempPathFactory) -> None:
    """A sink that is not ready on a tenth of the clocks loses beats, and the contract's
    assertion reports each one, with nothing else wrong: the core has no `m_tready` and does
    not wait. (Icarus only: the check is the testbench's, the same under both simulators.)"""
    tests, failed, messages = run_cocotb(simulator, ip_folder, band, tmp_path_factory, {"STEREO_SINK_STALL": "0.1"})
    assert (tests, failed) == (1, 1), f"{simulator}: the run with a stalling sink was expected to fail"
    errors = messages.splitlines()
    assert errors and all(e.startswith("beat lost on clock") for e in errors), f"{simulator}: only lost beats expected: {messages[:2000]}"
