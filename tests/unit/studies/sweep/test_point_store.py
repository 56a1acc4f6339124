"""The point store's record files: one encoding per save, checksum verified on load,
column order kept, records of the previous format still read."""

from __future__ import annotations

import hashlib
import json
import math

from recipsim.studies.sweep.store import FORMAT, PointStore, record_bytes, record_checksum

OVERRIDES = ["operating_point.shaft_speed=3000 rpm"]


def _record() -> dict:
    # summary columns deliberately not in sorted order, and a NaN
    summary = {"status_z [-]": 1.0, "COP [-]": 1.7, "b [W]": math.nan, "a [W]": 2.0}
    return {"status": "ok", "message": "", "summary": summary, "overrides": OVERRIDES}


def _lines(store: PointStore) -> list[bytes]:
    (segment,) = store.points.glob("*.jsonl")
    return segment.read_bytes().splitlines(keepends=True)


def test_a_saved_record_loads_back_with_its_column_order(tmp_path):
    store = PointStore(tmp_path)
    store.save("p1", _record())
    store.close()
    loaded = PointStore(tmp_path).load("p1", OVERRIDES)
    assert loaded is not None
    assert loaded["format"] == FORMAT and loaded["point_id"] == "p1"
    assert list(loaded["summary"]) == list(_record()["summary"])
    assert math.isnan(loaded["summary"]["b [W]"])
    assert loaded["checksum"] == record_checksum(loaded)
    assert len(_lines(store)) == 1 and list(store.points.glob("*.json")) == []


def test_an_edited_or_reordered_record_is_not_trusted(tmp_path):
    store = PointStore(tmp_path)
    store.save("p1", _record())
    (segment,) = store.points.glob("*.jsonl")
    record = json.loads(segment.read_text())
    assert store.load("p1", OVERRIDES) is not None
    record["summary"]["COP [-]"] = 99.0
    segment.write_text(json.dumps(record) + "\n")
    assert PointStore(tmp_path).load("p1", OVERRIDES) is None
    record["summary"]["COP [-]"] = 1.7
    record["summary"] = dict(reversed(list(record["summary"].items())))
    segment.write_text(json.dumps(record) + "\n")
    assert PointStore(tmp_path).load("p1", OVERRIDES) is None
    assert PointStore(tmp_path).load("p2", OVERRIDES) is None  # no record at all


def test_a_torn_last_line_is_skipped_and_the_later_record_of_a_point_counts(tmp_path):
    """A process killed while writing leaves its last line cut short: that point is
    computed again, the others are kept; a point saved twice (``--retry-failed``) is
    taken from its later record, whichever segment holds it."""
    store = PointStore(tmp_path)
    store.save("p1", {**_record(), "status": "failed", "run": "a"})
    store.save("p2", {**_record(), "run": "a"})
    store.save("p3", {**_record(), "run": "a"})
    store.close()
    (segment,) = store.points.glob("a-*.jsonl")
    data = segment.read_bytes()
    segment.write_bytes(data[: len(data) - 40])  # p3's line cut short
    store.save("p1", {**_record(), "run": "b"})  # a later run's segment
    store.close()
    again = PointStore(tmp_path)
    assert again.load("p1", OVERRIDES)["status"] == "ok"
    assert again.load("p2", OVERRIDES) is not None
    assert again.load("p3", OVERRIDES) is None
    assert len(list(store.points.glob("*.jsonl"))) == 2


def test_a_closed_segment_is_never_appended_to_again(tmp_path):
    """One segment per process and run while it is open; after ``close`` (or a failed
    write) the next record starts a new segment, so no record follows a cut line."""
    store = PointStore(tmp_path)
    store.save("p1", {**_record(), "run": "a"})
    PointStore(tmp_path).save("p2", {**_record(), "run": "a"})  # the same open segment
    assert len(list(store.points.glob("a-*.jsonl"))) == 1
    store.close()
    store.save("p3", {**_record(), "run": "a"})
    store.close()
    assert len(list(store.points.glob("a-*.jsonl"))) == 2
    assert all(PointStore(tmp_path).load(p, OVERRIDES) for p in ("p1", "p2", "p3"))


def test_a_record_file_of_format_3_is_still_read(tmp_path):
    """Sweeps saved each point in a file of its own (format 3): they resume, and a file
    edited after its checksum is not trusted."""
    store = PointStore(tmp_path)
    store.points.mkdir(parents=True)
    body = {"format": 3, "point_id": "p1", **_record()}
    store.path("p1").write_bytes(record_bytes(body))
    loaded = store.load("p1", OVERRIDES)
    assert loaded is not None and loaded["summary"]["COP [-]"] == 1.7
    store.path("p1").write_text(store.path("p1").read_text().replace("1.7", "2.5"))
    assert store.load("p1", OVERRIDES) is None


def test_a_record_of_format_2_is_still_read(tmp_path):
    """Format 2 summed its checksum over the keys sorted (and wrote them in order)."""
    store = PointStore(tmp_path)
    body = {"format": 2, "point_id": "p1", **_record()}
    blob = json.dumps(body, sort_keys=True, allow_nan=True, default=str, ensure_ascii=True)
    body["checksum"] = hashlib.sha256(blob.encode()).hexdigest()
    store.points.mkdir(parents=True)
    store.path("p1").write_text(json.dumps(body, allow_nan=True))
    loaded = store.load("p1", OVERRIDES)
    assert loaded is not None and loaded["summary"]["COP [-]"] == 1.7
    assert store.load("p1", ["operating_point.shaft_speed=1.0"]) is None  # other inputs


def test_write_bytes_atomically_leaves_the_old_file_when_it_fails(tmp_path):
    from recipsim.atomic import write_bytes_atomically

    target = tmp_path / "new" / "a.json"
    write_bytes_atomically(target, b"first")  # the missing directory is created
    assert target.read_bytes() == b"first"
    try:
        write_bytes_atomically(target, None)  # type: ignore[arg-type]
    except TypeError:
        pass
    else:  # pragma: no cover - the write must fail
        raise AssertionError("writing None did not fail")
    assert target.read_bytes() == b"first"
    assert [p.name for p in target.parent.iterdir()] == ["a.json"]


def test_a_stale_temporary_of_the_same_name_is_stepped_over(tmp_path):
    """A temporary file left by a killed process of the same id takes the next number:
    the write succeeds and the stale files stay for ``clean_temporaries``."""
    import os
    import re

    from recipsim import atomic

    upcoming = int(re.search(r"\d+", repr(atomic._TEMPORARY_NUMBERS)).group())
    stale = [tmp_path / f".a.{os.getpid()}-{upcoming + k}.json.tmp" for k in range(3)]
    for path in stale:
        path.write_bytes(b"stale")
    atomic.write_bytes_atomically(tmp_path / "a.json", b"fresh")
    assert (tmp_path / "a.json").read_bytes() == b"fresh"
    assert all(path.read_bytes() == b"stale" for path in stale)
    assert len(list(tmp_path.glob(".*.tmp"))) == 3


def test_a_point_id_is_the_hash_of_its_inputs_as_one_json_document():
    """The identifier built from parts (the refrigerant's part encoded once) is the
    SHA-256 of the JSON of ``{"recipsim", "case", "refrigerant"}`` with sorted keys, as
    the store has always named points: a sweep run before resumes into its points."""
    from pathlib import Path

    from recipsim import __version__
    from recipsim.studies.sweep.plan import point_id

    case = {"z": {"b": [1.5, math.nan], "a": "é"}, "name": "c", "path": Path("x/y.toml")}
    refrigerant = 'name = "R134a"\n# "quoted" \\ ü\n'
    whole = json.dumps(
        {"recipsim": __version__, "case": case, "refrigerant": refrigerant},
        sort_keys=True,
        default=str,
        ensure_ascii=True,
    )
    expected = hashlib.sha256(whole.encode()).hexdigest()[:16]
    assert point_id(case, refrigerant) == expected
    assert point_id(case, refrigerant + " ") != expected
