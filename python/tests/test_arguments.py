"""Hostile arguments: integers beyond the C type that takes them, non-real arrays, strings with a NUL, and counts
given as strings, floats or bools are refused instead of being wrapped, cut or truncated."""
import numpy as np
import pytest

import ggx

S = ggx.Shape.iso(0.3)
NORMALS = np.tile([0.0, 0.0, 1.0], (4, 4, 1))
TINY = {"size": 4, "spp": 1, "threads": 1}


@pytest.mark.parametrize("call", [
    lambda: ggx.mipmap(NORMALS, 0.1, nodes=(2 ** 32 + 8, 16)),
    lambda: ggx.mipmap(NORMALS, 0.1, nodes=(8, -(2 ** 32) + 16)),
    lambda: ggx.mipmap(NORMALS, 0.1, max_iterations=2 ** 32 + 1),
    lambda: ggx.mipmap(NORMALS, 0.1, threads=2 ** 32 + 1),
    lambda: ggx.filter_lobes([S], nodes=(2 ** 32 + 8, 16)),
    lambda: ggx.filter_kl(S, [S], nodes=(8, 2 ** 64 + 16)),
    lambda: ggx.render(S, seed=2 ** 64 + 1, **TINY),
    lambda: ggx.render(S, seed=-1, **TINY),
    lambda: ggx.render(S, depth=2 ** 32 + 1, **TINY),
    lambda: ggx.fit_heightfield(np.zeros((4, 4)), downsample=2 ** 32 + 2),
    lambda: ggx.fit_normals(np.tile([0.0, 0.0, 1.0], (8, 1)), max_iterations=2 ** 32 + 1),
    lambda: ggx.set_batch_threads(2 ** 32 + 4),
])
def test_integers_beyond_c_are_refused(call):
    with pytest.raises(OverflowError):
        call()


def test_seed_is_not_wrapped():
    a = ggx.render(S, seed=1, **TINY)
    assert np.array_equal(a, ggx.render(S, seed=np.uint64(1), **TINY))
    ggx.render(S, seed=2 ** 64 - 1, **TINY)  # the largest seed is taken
    with pytest.raises(OverflowError):
        ggx.render(S, seed=2 ** 64 + 1, **TINY)


@pytest.mark.parametrize("call", [
    lambda: ggx.mipmap(NORMALS, np.full((4, 4), 0.1 + 0.5j)),
    lambda: ggx.mipmap(NORMALS, 0.1, alpha_y=np.full((4, 4), 0.2 + 1j)),
    lambda: ggx.mipmap(NORMALS, np.full((4, 4), "0.1")),
    lambda: ggx.mipmap(NORMALS, np.full((4, 4), np.datetime64("2020-01-01"))),
    lambda: ggx.mipmap(NORMALS, 0.1 + 0.5j),
    lambda: ggx.mipmap(NORMALS.astype(complex), 0.1),
    lambda: ggx.render(S, light=("point", np.complex128(0.3 + 1j), 0.0), **TINY),
    lambda: ggx.ndf(S, np.array([0, 0, 1], dtype=np.complex64)),
    lambda: ggx.texel_lobe(np.array([0, 0, 1j]), 0.1),
    lambda: ggx.fit_heightfield(np.zeros((4, 4)), spacing=(1j, 1)),
])
def test_non_real_arrays_are_refused(call):
    with pytest.raises(ValueError):
        call()


def test_nul_in_strings_is_refused(tmp_path):
    p = tmp_path / "a.txt"
    p.write_text("0 1\n2 3\n")
    assert ggx.read_surface(str(p)).data.shape == (2, 2)
    for cut in (str(p) + "\0.png", str(p).encode() + b"\0.png"):
        with pytest.raises(ValueError, match="NUL"):
            ggx.read_surface(cut)
    with pytest.raises(ValueError, match="NUL"):
        ggx.render(S, light=str(p) + "\0.exr", **TINY)
    with pytest.raises(ValueError, match="NUL"):
        ggx.render(S, sampler="brdf\0junk", **TINY)
    with pytest.raises(ValueError):
        ggx.render(S, sampler=["brdf"], **TINY)


@pytest.mark.parametrize("call", [
    lambda: ggx.render(S, spp="2", size=4, threads=1),
    lambda: ggx.render(S, spp=2.7, size=4, threads=1),
    lambda: ggx.render(S, spp=True, size=4, threads=1),
    lambda: ggx.render(S, spp=1, size=4.0, threads=1),
    lambda: ggx.render(S, spp=1, size=("4", 4), threads=1),
    lambda: ggx.render(S, depth=3.5, **TINY),
    lambda: ggx.render(S, seed=1.5, **TINY),
    lambda: ggx.render(S, spp=1, size=4, threads=1.0),
    lambda: ggx.mipmap(NORMALS, 0.1, threads=2.5),
    lambda: ggx.mipmap(NORMALS, 0.1, nodes=(8.9, 16)),
    lambda: ggx.mipmap(NORMALS, 0.1, max_iterations="3"),
    lambda: ggx.filter_lobes([S], max_iterations=np.float64(3)),
    lambda: ggx.fit_normals(np.tile([0.0, 0.0, 1.0], (8, 1)), threads=2.0),
    lambda: ggx.fit_heightfield(np.zeros((4, 4)), downsample=False),
    lambda: ggx.set_batch_threads(1.5),
    lambda: ggx.set_batch_threads("2"),
])
def test_counts_must_be_integers(call):
    with pytest.raises(TypeError):
        call()


def test_integer_counts_are_taken():
    a = ggx.render(S, spp=np.int32(2), size=(np.int64(4), 4), depth=np.uint8(3), threads=np.int16(1))
    assert np.array_equal(a, ggx.render(S, spp=2, size=4, depth=3, threads=1))
    ggx.mipmap(NORMALS, 0.1, nodes=np.array([2, 4]), max_iterations=np.int64(1), threads=np.int8(2))
    ggx.set_batch_threads(np.int64(1))


def test_argument_errors_stay_value_errors():
    """The package's promise that every error is a ValueError holds for the new refusals too."""
    for call in (lambda: ggx.render(S, spp=2.7, size=4), lambda: ggx.render(S, seed=2 ** 64 + 1, **TINY)):
        with pytest.raises(ValueError):
            call()


def test_one_sided_ranges_name_their_bound():
    """A count with a lower bound only says that bound, not a missing upper one."""
    for call, what in ((lambda: ggx.fit_heightfield(np.zeros((4, 4)), downsample=-1), "downsample"),
                       (lambda: ggx.fit_normals(np.tile([0.0, 0.0, 1.0], (8, 1)), max_iterations=-1),
                        "max_iterations")):
        with pytest.raises(ValueError, match=f"{what}: expected an integer of at least 0, got -1") as e:
            call()
        assert "None" not in str(e.value)
