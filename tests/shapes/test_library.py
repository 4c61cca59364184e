"""The built-in library: valid shapes of the promised sizes, files match their design."""

from __future__ import annotations

import pytest

from etswarm.shapes import LIBRARY_NAMES, library_path, load_shape
from etswarm.shapes.design import DESIGNS, library_text
from etswarm.shapes.lattice import is_connected, is_constructible
from etswarm.shapes.library import library_description


@pytest.mark.parametrize("name", LIBRARY_NAMES)
def test_library_shape_is_valid(name: str) -> None:
    shape = load_shape(name)
    assert shape.name == name and shape.dropped == ()
    assert is_connected(shape.cells) and is_constructible(shape.cells)
    assert 15 <= shape.n_cells <= 400
    assert library_description(name)


@pytest.mark.parametrize("name", LIBRARY_NAMES)
def test_library_file_matches_its_design(name: str) -> None:
    assert library_path(name).read_text(encoding="utf-8") == library_text(name)


def test_paper_shapes_sizes() -> None:
    assert 30 <= load_shape("T").n_cells <= 60
    assert 40 <= load_shape("dumbbell").n_cells <= 80
    assert 60 <= load_shape("starfish").n_cells <= 120
    assert max(load_shape(n).n_cells for n in LIBRARY_NAMES) >= 300
    assert min(load_shape(n).n_cells for n in LIBRARY_NAMES) <= 15
    assert set(DESIGNS) == set(LIBRARY_NAMES)


def test_hollow_shape_is_marked_as_expected_to_fail() -> None:
    assert "FAIL" in library_description("O")
