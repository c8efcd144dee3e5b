"""The interpreter never dies and nothing is silently wrong: sizes that do not fit raise
MemoryError (also under a process memory limit), Ctrl-C stops every 3D solver, the CLI's checks
apply from Python, and a scene with missing results raises ConvergenceError."""

import signal
import subprocess
import sys
import textwrap
import time

import numpy as np
import pytest

import mrdw
from conftest import run_cli


@pytest.mark.parametrize(
    "call",
    [
        lambda: mrdw.surface((100000, 100000), (1.0, 1.0), 0.8, 4.0, 4.0, 32.0),
        lambda: mrdw.surface((2**33, 2**33), (1.0, 1.0), 0.8, 4.0, 4.0, 32.0),
        lambda: mrdw.line(10**12, 1.0, 0.8, 4.0, 4.0, 32.0),
    ],
)
def test_sizes_that_do_not_fit_raise_memory_error(call):
    with pytest.raises(MemoryError, match="needs about|overflows"):
        call()


def run_python(code, limit_bytes=None, timeout=120):
    """Runs `code` in a fresh interpreter (under an address-space limit if given)."""

    def limit():
        import resource

        resource.setrlimit(resource.RLIMIT_AS, (limit_bytes, limit_bytes))

    return subprocess.run(
        [sys.executable, "-c", textwrap.dedent(code)],
        capture_output=True,
        text=True,
        timeout=timeout,
        preexec_fn=limit if limit_bytes else None,
    )


def test_a_process_memory_limit_gives_memory_error_not_an_abort():
    # 4096^2 needs about 1.3 GB for the solver: under a 700 MB address-space limit
    # (the interpreter and numpy take about 300 MB of it) it does not fit.
    out = run_python(
        """
        import numpy as np, mrdw
        h = np.zeros((4096, 4096))
        try:
            mrdw.Contact(h)
        except MemoryError as e:
            print("MemoryError:", e)
        """,
        limit_bytes=700 * 2**20,
    )
    assert out.returncode == 0, out.stderr
    assert "MemoryError:" in out.stdout and "address-space limit" in out.stdout, out.stdout


# Each builds an object `o` and makes one call that would run for seconds to minutes: a
# tolerance below rounding (each solve runs to its iteration cap) or a cycle of 900,000
# loads.
LONG_CALLS = {
    "Contact": (
        "o = mrdw.Contact(h)",
        "o.solve(mean_pressure=0.01, tolerance=1e-300, max_iterations=10**7)",
    ),
    "PartialSlip": (
        "o = mrdw.PartialSlip(p, 0.3)",
        "o.cycle(0.5 * o.friction_limit, steps=10**5, cycles=4)",
    ),
    "ViscoelasticSlip": (
        # On 512^2 (the pressure refined fourfold): on 128^2 the step ends at its
        # rounding floor within a fifth of a second.
        "o = mrdw.ViscoelasticSlip(np.kron(p, np.ones((4, 4))), 0.3, 1.0, [(1.0, 1.0)])",
        "o.step(0.1, 1e-3, tolerance=1e-300)",
    ),
    "AdhesiveContact": (
        "o = mrdw.AdhesiveContact(h, 1e-4, periodic=False)",
        "o.step(approach=0.05, tolerance=1e-300)",
    ),
    "CohesiveContact": (
        "o = mrdw.CohesiveContact(h, 1e-4, 0.03)",
        "o.step(0.05, tolerance=1e-300)",
    ),
    # The recursive residual does fall below 1e-300, after seconds on 512^2.
    "stick_stiffness": (
        "o = np.add.outer(*2 * [((np.arange(512) + 0.5) / 512 - 0.5) ** 2]) < 0.09",
        "mrdw.stick_stiffness(o, tolerance=1e-300)",
    ),
}
# What keeps no state between calls goes on after an interrupt; the rest refuse.
STATELESS = ("Contact", "stick_stiffness")


@pytest.mark.parametrize("kind", sorted(LONG_CALLS))
def test_ctrl_c_stops_a_3d_solve(kind):
    # SIGINT ends the call within a second or two; an object whose step was interrupted
    # refuses the next (its state is the unfinished step's).
    build, call = LONG_CALLS[kind]
    proc = subprocess.Popen(
        [
            sys.executable,
            "-c",
            textwrap.dedent(
                f"""
                import signal, sys, numpy as np, mrdw
                # A shell that starts the tests in the background hands its children
                # SIGINT ignored, and Python keeps it so: install Python's handler.
                signal.signal(signal.SIGINT, signal.default_int_handler)
                h = mrdw.surface((128, 128), (1.0, 1.0), 0.8, 8.0, 8.0, 200.0, rms_slope=0.1, seed=1)
                x = (np.arange(128) + 0.5) / 128 - 0.5
                r2 = x[:, None] ** 2 + x[None, :] ** 2
                p = np.sqrt(np.maximum(0.09 - r2, 0.0))
                {build}
                print("solving", flush=True)
                try:
                    {call}
                except KeyboardInterrupt:
                    print("interrupted", flush=True)
                    if "{kind}" not in {STATELESS}:
                        try:
                            {call}
                        except RuntimeError as e:
                            print("refused:", e, flush=True)
                    sys.exit(7)
                """
            ),
        ],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    assert proc.stdout.readline().strip() == "solving"
    time.sleep(1.0)
    assert proc.poll() is None, "the call ended before the interrupt: the test proves nothing"
    t0 = time.monotonic()
    proc.send_signal(signal.SIGINT)
    try:
        out, err = proc.communicate(timeout=30)
    finally:
        proc.kill()  # never leave a solving child behind
    assert time.monotonic() - t0 < 2.0
    assert proc.returncode == 7, err
    assert "interrupted" in out
    if kind not in STATELESS:
        assert f"refused: a step of this {kind} was interrupted" in out, out


def test_the_command_lines_checks_apply_from_python(mrdw_bin, tmp_path):
    h = np.cos(np.arange(256.0)).reshape(16, 16) * 1e-2
    c = mrdw.Contact(h)
    for tol in (1.0, 1e300):
        with pytest.raises(ValueError, match=r"tolerance = .* must lie in \(0, 1e-2\]"):
            c.solve(mean_pressure=0.01, tolerance=tol)
    with pytest.raises(ValueError, match=r"size\[0\] \(lx, the map's size in x\) = 1e300 must lie in"):
        mrdw.Contact(h, size=(1e300, 1e300))
    # The tangential solvers take the same range of sizes and moduli (outside it cell
    # areas or tractions overflow to a NaN).
    p = np.zeros((16, 16))
    p[6:10, 6:10] = 1.0
    for make in (
        lambda **kw: mrdw.PartialSlip(p, 0.3, **kw),
        lambda **kw: mrdw.PartialSlip(p, 0.3, periodic=False, **kw),
        lambda **kw: mrdw.stick_stiffness(p > 0, **kw),
    ):
        with pytest.raises(ValueError, match=r"size\[0\] \(lx, the map's size in x\) = 1e300 must lie in"):
            make(size=(1e300, 1e300))
        with pytest.raises(ValueError, match=r"e_star \(the contact modulus E\*\) = 1e-300 must lie in \[1e-100, 1e100\]"):
            make(e_star=1e-300)
    with pytest.raises(ValueError, match=r"size\[1\] \(ly, the map's size in y\) = 1e-300 must lie in"):
        mrdw.ViscoelasticSlip(p, 0.3, 1.0, size=(1.0, 1e-300))
    # Extreme values read as given (1e300), not as their 300 digits.
    with pytest.raises(ValueError, match=r"mu = 1e300 must lie in \(0, 1e6\]$"):
        mrdw.PartialSlip(p, 1e300)
    # A glassy shear modulus out of that range (at 1e-300 the iteration breaks down).
    for relaxed in (1e-300, 1e300):
        with pytest.raises(ValueError, match=r"glassy shear modulus G\*\(0\) = .* must lie in"):
            mrdw.ViscoelasticSlip(p, 0.3, relaxed)
    # The CLI refuses the same with the same words.
    np.save(tmp_path / "h.npy", h)
    for key, message in [
        ("tolerance = 1.0", "tolerance = 1e0 must lie in (0, 1e-2]"),
        ("size = [1e300, 1e300]", "size[0] (lx, the map's size in x) = 1e300 must lie in"),
    ]:
        scene = tmp_path / "b.toml"
        body = 'name = "b"\n[material]\ne_star = 1.0\n[[outputs]]\nkind = "bem_contact"\nheights = "h.npy"\nmean_pressures = [0.01]\n'
        if not key.startswith("size"):
            body += "size = [1.0, 1.0]\n"
        scene.write_text(body + key + "\n")
        out = run_cli(mrdw_bin, "run", str(scene), "--out", str(tmp_path / "o"))
        assert out.returncode == 2 and message in out.stderr, out.stderr


def test_a_scene_with_missing_results_raises(tmp_path):
    # fig7-ci with 2.3 springs per shortest wave: no velocity is resolved, xi is missing.
    scene = tmp_path / "f.toml"
    base = case_text("fig7-ci")
    scene.write_text(
        base.replace("waves = 4.0, band", "waves = 80.0, band").replace(
            "springs = 1024", "springs = 256"
        )
    )
    with pytest.raises(mrdw.ConvergenceError, match="requested results are missing") as e:
        mrdw.run_scene(str(scene))
    assert e.value.failures and "not fitted" in e.value.failures[0]
    assert "sliding_friction" in e.value.last["tables"]


def case_text(name):
    from conftest import ROOT

    return (ROOT / "cases" / f"{name}.toml").read_text()
