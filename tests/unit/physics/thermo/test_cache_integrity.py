"""Caches are checked before they are reused, and live where one rule says.

A tampered, truncated or malformed cache file is rebuilt with a warning, never used;
``XDG_CACHE_HOME`` (through platformdirs) or ``RECIPSIM_CACHE`` decides where every
cache lives, created with mode 0o700.
"""

from __future__ import annotations

import json
import os
import stat
import subprocess
import sys
import warnings
from pathlib import Path

import numpy as np
import pytest

from recipsim.cache_dirs import check_private, private_dir
from recipsim.physics.thermo.coolprop_info import FluidConstants, coolprop_fluid_constants
from recipsim.physics.thermo.fluid import Fluid
from recipsim.physics.thermo.property_table import TableResolution
from recipsim.physics.thermo.property_table_cache import fluid_constants, load_property_table

COARSE = TableResolution(dt=4.0, dx=0.16, dt_sat=1.0)
R600A = ("Isobutane", 220.0, 400.0)


@pytest.fixture
def cache(tmp_path, monkeypatch):
    monkeypatch.setenv("RECIPSIM_CACHE", str(tmp_path / "cache"))
    fluid_constants.cache_clear()
    yield tmp_path / "cache"
    fluid_constants.cache_clear()


def _rewrite(path: Path, **changes: object) -> None:
    """Rewrite the table file with some arrays changed, keeping it a loadable npz."""
    with np.load(path, allow_pickle=False) as npz:
        arrays = {name: npz[name] for name in npz.files}
    arrays.update({k: np.asarray(v) for k, v in changes.items()})
    with open(path, "wb") as handle:
        np.savez(handle, **arrays)


def test_a_tampered_table_is_rebuilt_and_its_provenance_is_honest(cache):
    built = load_property_table(*R600A, COARSE)
    assert not built.from_cache and built.path.is_file()
    again = load_property_table(*R600A, COARSE)
    assert again.from_cache and np.array_equal(again.data, built.data, equal_nan=True)
    with np.load(built.path, allow_pickle=False) as npz:
        data = np.array(npz["data"])
    data[len(data) // 2] *= 1.001  # a plausible-looking edit of one coefficient
    _rewrite(built.path, data=data)
    with pytest.warns(UserWarning, match="checksum does not match"):
        rebuilt = load_property_table(*R600A, COARSE)
    assert not rebuilt.from_cache
    assert np.array_equal(rebuilt.data, built.data, equal_nan=True)
    # a claimed error that is not the measured one fails the checksum too
    _rewrite(built.path, error=json.dumps({"max_relative_error": 1e-12}))
    with pytest.warns(UserWarning, match="checksum"):
        honest = load_property_table(*R600A, COARSE)
    assert honest.error == built.error and not honest.from_cache
    assert load_property_table(*R600A, COARSE).from_cache  # the rebuilt file is good


def test_the_entropy_sums_are_cached_with_the_table_and_checked(cache):
    """A loaded table brings the entropy sums its build stored, equal to those computed
    from its data; an edited sum fails the checksum like an edited coefficient."""
    from recipsim.physics.thermo.table_entropy import entropy_tables

    built = load_property_table(*R600A, COARSE)
    loaded = load_property_table(*R600A, COARSE)
    assert loaded.from_cache and loaded.entropy is not None
    computed = entropy_tables(loaded.property_buffer(transport=False))
    np.testing.assert_array_equal(loaded.entropy, computed)
    np.testing.assert_array_equal(built.entropy, computed)
    entropy = loaded.entropy.copy()
    finite = np.flatnonzero(np.isfinite(entropy) & (entropy != 0.0))
    entropy[finite[len(finite) // 2]] *= 1.001
    _rewrite(built.path, entropy=entropy)
    with pytest.warns(UserWarning, match="checksum does not match"):
        assert not load_property_table(*R600A, COARSE).from_cache


@pytest.mark.parametrize(
    "damage",
    [b"", b"not a zip file at all", b"PK\x03\x04" + b"\x00" * 64],
    ids=["empty", "garbage", "truncated-zip"],
)
def test_an_unreadable_table_is_rebuilt_without_a_traceback(cache, damage):
    path = load_property_table(*R600A, COARSE).path
    path.write_bytes(damage)
    with pytest.warns(UserWarning, match="unreadable"):
        table = load_property_table(*R600A, COARSE)
    assert not table.from_cache and path.stat().st_size > 1000


def test_a_table_without_checksum_or_with_the_wrong_shape_is_rebuilt(cache):
    path = load_property_table(*R600A, COARSE).path
    with np.load(path, allow_pickle=False) as npz:
        arrays = {name: npz[name] for name in npz.files if name != "checksum"}
    with open(path, "wb") as handle:
        np.savez(handle, **arrays)
    with pytest.warns(UserWarning, match="unreadable"):
        assert not load_property_table(*R600A, COARSE).from_cache
    _rewrite(path, data=np.zeros((3, 3)))
    with pytest.warns(UserWarning, match="not shaped"):
        assert not load_property_table(*R600A, COARSE).from_cache


def test_fluid_constants_are_read_from_a_cached_table_of_the_fluid(cache, monkeypatch):
    """A table's file holds its fluid's constants (CoolProp's: limits, critical point, gas
    constant), read back without asking CoolProp; a table built with another CoolProp
    version is passed over, and CoolProp asked."""
    from recipsim.physics.thermo import property_table_cache

    load_property_table(*R600A, COARSE)
    expected = coolprop_fluid_constants("Isobutane")
    heos = Fluid("Isobutane")
    assert expected.t_crit == heos.critical_temperature
    assert expected.gas_constant == heos.gas_constant
    asked: list[str] = []

    def counted(name: str) -> FluidConstants:
        asked.append(name)
        return coolprop_fluid_constants(name)

    monkeypatch.setattr(property_table_cache, "coolprop_fluid_constants", counted)
    fluid_constants.cache_clear()
    assert fluid_constants("Isobutane") == expected
    assert asked == []
    monkeypatch.setattr(property_table_cache, "coolprop_version", lambda: "0.0")
    fluid_constants.cache_clear()
    assert fluid_constants("Isobutane") == expected
    assert asked == ["Isobutane"]
    with pytest.raises(ValueError):
        fluid_constants("NoSuchFluid")


@pytest.mark.parametrize(
    ("damage", "why"),
    [
        (lambda k: json.dumps({**k, "t_crit": 1.001 * k["t_crit"]}), "checksum does not match"),
        (lambda k: json.dumps({**k, "gas_constant": "143 J/(kg K)"}), "checksum does not match"),
        (lambda k: json.dumps({n: v for n, v in k.items() if n != "p_crit"}), "constants are"),
        (lambda k: "not json{", "unreadable"),
    ],
    ids=["altered", "text", "missing", "malformed"],
)
def test_damaged_fluid_constants_in_a_table_file_are_not_used(cache, damage, why):
    """Constants edited in a table's file are passed over (CoolProp's used instead), and
    the table is rebuilt with a warning when it is loaded."""
    path = load_property_table(*R600A, COARSE).path
    with np.load(path, allow_pickle=False) as npz:
        stored = json.loads(str(npz["constants"]))
    _rewrite(path, constants=damage(stored))
    fluid_constants.cache_clear()
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # passed over without a warning
        assert fluid_constants("Isobutane") == coolprop_fluid_constants("Isobutane")
    with pytest.warns(UserWarning, match=why):
        assert not load_property_table(*R600A, COARSE).from_cache
    fluid_constants.cache_clear()
    assert fluid_constants("Isobutane") == FluidConstants(**stored)  # the rebuilt file's


def test_every_cache_follows_xdg_cache_home_with_private_directories(tmp_path):
    """In a fresh interpreter without RECIPSIM_CACHE: numba's cache of recipsim's compiled
    functions lands under $XDG_CACHE_HOME/recipsim, created 0o700, and importing recipsim
    leaves the environment as it was (nothing else's numba cache is redirected)."""
    env = {k: v for k, v in os.environ.items() if k not in ("RECIPSIM_CACHE", "NUMBA_CACHE_DIR")}
    env["XDG_CACHE_HOME"] = str(tmp_path / "xdg")
    code = (
        "import os\n"
        "before = dict(os.environ)\n"
        "import recipsim\n"
        "from recipsim.physics.kinematics import piston_displacement\n"
        "piston_displacement(0.1, 0.01, 0.04)\n"
        "from recipsim.cache_dirs import numba_cache_path\n"
        "print(dict(os.environ) == before, numba_cache_path())\n"
    )
    out = subprocess.run(
        [sys.executable, "-c", code], env=env, capture_output=True, text=True, timeout=120
    )
    assert out.returncode == 0, out.stderr
    unchanged, numba_dir = out.stdout.split()
    assert unchanged == "True"
    root = tmp_path / "xdg" / "recipsim"
    assert Path(numba_dir).parent == root / "numba"
    assert list(Path(numba_dir).rglob("kinematics.piston_displacement-*.nbi"))
    for directory in (root, root / "numba", Path(numba_dir)):
        assert stat.S_IMODE(directory.stat().st_mode) == 0o700, directory


def test_a_users_numba_cache_dir_is_respected_and_not_redirected(tmp_path):
    """With NUMBA_CACHE_DIR set, recipsim's compiled code goes below it, and a user's own
    cached function is cached where numba's rules put it, as if recipsim were not there."""
    env = {k: v for k, v in os.environ.items() if k != "RECIPSIM_CACHE"}
    env["NUMBA_CACHE_DIR"] = str(tmp_path / "mine")
    (tmp_path / "user_code.py").write_text(
        "from numba import njit\n@njit(cache=True)\ndef twice(x):\n    return 2 * x\n"
    )
    code = (
        "import recipsim, user_code\n"
        "from recipsim.physics.kinematics import piston_displacement\n"
        "piston_displacement(0.1, 0.01, 0.04); user_code.twice(2.0)\n"
    )
    out = subprocess.run(
        [sys.executable, "-c", code],
        env=env,
        capture_output=True,
        text=True,
        timeout=120,
        cwd=tmp_path,
    )
    assert out.returncode == 0, out.stderr
    ours = list((tmp_path / "mine").glob("recipsim-*/physics/kinematics.*.nbi"))
    theirs = [p for p in (tmp_path / "mine").rglob("user_code.twice-*.nbi")]
    assert ours and theirs
    assert not any("recipsim-" in str(p) for p in theirs)


def test_a_cache_directory_others_can_write_is_reported(tmp_path):
    shared = private_dir(tmp_path / "shared")
    assert stat.S_IMODE(shared.stat().st_mode) == 0o700
    shared.chmod(0o777)
    with pytest.warns(UserWarning, match="writable by other users"):
        check_private(shared)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        check_private(shared)  # once per directory


def test_pickled_caches_are_not_loaded_from_a_root_others_can_write(tmp_path, monkeypatch):
    """A cache root (or its pint folder) writable by others: a warning naming it, and
    neither pint's pickled definitions nor numba's cache are taken from there; the run
    still works (unit strings converted, nothing planted read)."""
    from recipsim.cache_dirs import trusted_cache

    root = tmp_path / "shared-cache"
    root.mkdir()
    root.chmod(0o777)
    monkeypatch.setenv("RECIPSIM_CACHE", str(root))
    with pytest.warns(UserWarning, match="writable by other users"):
        assert trusted_cache(root / "pint") is None
    root.chmod(0o700)
    assert trusted_cache(root / "pint") == root / "pint"
    (root / "pint").chmod(0o777)
    with pytest.warns(UserWarning, match="writable by other users"):
        assert trusted_cache(root / "pint") is None


def test_a_planted_pint_pickle_in_an_open_cache_never_runs(tmp_path):
    """pint's definitions cache is pickled: a pickle planted in it runs code when it is
    loaded (shown on a private folder, the user's own, where it is loaded), so a folder
    others can write is never read: there the planted code leaves no trace."""
    root = tmp_path / "cache"
    env = {**os.environ, "RECIPSIM_CACHE": str(root)}
    code = "from recipsim.units import to_si; print(to_si('22 mm', 'm', 'f', 'k'))"

    def convert() -> str:
        out = subprocess.run(
            [sys.executable, "-W", "ignore", "-c", code],
            env=env, capture_output=True, text=True, timeout=120,
        )  # fmt: skip
        assert out.returncode == 0, out.stderr
        return out.stdout.strip()

    assert convert() == "0.022"  # fills the cache
    pickles = list((root / "pint").rglob("*.pickle"))
    assert pickles
    marker = tmp_path / "planted-code-ran"

    def plant() -> None:
        payload = (
            "import os, pickle, sys\n"
            "class P:\n"
            f"    def __reduce__(self): return (os.system, ('touch {marker}',))\n"
            "for name in sys.argv[1:]:\n"
            "    open(name, 'wb').write(pickle.dumps(P()))\n"
        )
        subprocess.run([sys.executable, "-c", payload, *map(str, pickles)], check=True)

    plant()
    convert()
    assert marker.exists()  # private: the user's own cache is trusted and read
    marker.unlink()
    plant()
    (root / "pint").chmod(0o777)
    assert convert() == "0.022"
    assert not marker.exists()


@pytest.mark.parametrize("damage", [b"", b"garbage", "half"])
def test_a_corrupted_numba_cache_index_is_compiled_again(tmp_path, damage):
    """A truncated or overwritten numba index (``*.nbi``) in recipsim's cache: the next
    process says so in one line, compiles the function again, gives the same value, and
    the one after it reads the rewritten cache silently."""
    env = {**os.environ, "RECIPSIM_CACHE": str(tmp_path / "cache")}
    env.pop("NUMBA_CACHE_DIR", None)
    code = (
        "from recipsim.physics.kinematics import piston_displacement\n"
        "print(repr(piston_displacement(0.7, 0.0092, 0.036)[0]))\n"
    )

    def run() -> subprocess.CompletedProcess[str]:
        return subprocess.run(
            [sys.executable, "-c", code], env=env, capture_output=True, text=True, timeout=120
        )

    first = run()
    assert first.returncode == 0, first.stderr
    (index,) = (tmp_path / "cache").rglob("kinematics.piston_displacement-*.nbi")
    whole = index.read_bytes()
    index.write_bytes(whole[: len(whole) // 2] if damage == "half" else damage)
    again = run()
    assert again.returncode == 0 and again.stdout == first.stdout, again.stderr
    assert "Traceback" not in again.stderr
    assert [line for line in again.stderr.splitlines() if "was unreadable" in line]
    third = run()
    assert third.returncode == 0 and third.stdout == first.stdout
    assert "unreadable" not in third.stderr
