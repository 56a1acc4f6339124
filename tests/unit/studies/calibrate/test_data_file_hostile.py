"""The calibration data file under hostile input: every file is read through the bounded,
regular-file, UTF-8 reader the case files use, so that a FIFO, a device, a huge file or
one with a huge field is refused at once with one message naming the file; a byte-order
mark is skipped; a repeated column is refused rather than silently using one of them.
Property-based: any text gives points or a CaseError, never another exception."""

from __future__ import annotations

import os
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from recipsim.errors import CaseError
from recipsim.studies.calibrate.data import MAX_DATA_BYTES, MAX_POINTS, read_points

HEADER = "evaporating_temperature [degC],condensing_temperature [degC],cooling_capacity [W]\n"


def _refused(path: Path, words: str) -> None:
    with pytest.raises(CaseError, match=words) as info:
        read_points(path)
    assert str(path) in str(info.value) and "\n" not in str(info.value)


def test_a_fifo_and_a_device_are_refused_without_blocking(tmp_path: Path) -> None:
    fifo = tmp_path / "data.csv"
    os.mkfifo(fifo)
    _refused(fifo, "not a regular file")
    _refused(Path("/dev/zero"), "not a regular file")


def test_a_huge_file_a_huge_field_and_too_many_rows_are_refused(tmp_path: Path) -> None:
    huge = tmp_path / "huge.csv"
    huge.write_text(HEADER + "-25,55,68\n" * (MAX_DATA_BYTES // 10))
    _refused(huge, "at most 1000000 are read")
    field = tmp_path / "field.csv"
    field.write_text(HEADER + "-25,55," + "9" * 200_000 + "\n")
    _refused(field, "not a readable CSV file")
    rows = tmp_path / "rows.csv"
    rows.write_text(HEADER + "-25,55,68\n" * (MAX_POINTS + 1))
    _refused(rows, f"at most {MAX_POINTS} measured points")


def test_text_that_is_not_utf8_is_refused_and_a_byte_order_mark_skipped(tmp_path: Path) -> None:
    excel = tmp_path / "excel.csv"
    excel.write_bytes(HEADER.replace("degC", "\xb0C").encode("latin-1") + b"-25,55,68\n")
    _refused(excel, "not UTF-8")
    bom = tmp_path / "bom.csv"
    bom.write_bytes(b"\xef\xbb\xbf" + HEADER.encode() + b"-25,55,68\n")
    points, targets = read_points(bom)
    assert targets == ("cooling_capacity [W]",)
    assert points[0].overrides["operating_point.evaporating_temperature"] == "-25 degC"


def test_a_repeated_column_is_refused(tmp_path: Path) -> None:
    twice = tmp_path / "twice.csv"
    twice.write_text(
        "evaporating_temperature [degC],evaporating_temperature [degC],cooling_capacity [W]\n"
        "-25,-30,68\n"
    )
    _refused(twice, "more than once")


def test_a_missing_file_is_a_case_error(tmp_path: Path) -> None:
    _refused(tmp_path / "missing.csv", "no such")


@settings(max_examples=150, deadline=None)
@given(st.text(max_size=400))
def test_any_text_gives_points_or_a_case_error(tmp_path_factory, text: str) -> None:
    path = tmp_path_factory.mktemp("fuzz") / "data.csv"
    path.write_text(text, encoding="utf-8", errors="surrogatepass")
    try:
        read_points(path)
    except CaseError as exc:
        assert "\n" not in exc.message
