"""Shared helpers of the Python package's tests (run by scripts/python-tests.sh)."""

import os
import pathlib

import numpy as np
import pytest

REPO = pathlib.Path(__file__).resolve().parents[2]
SHARED = REPO.parent / "shared" / "data"


@pytest.fixture
def repo() -> pathlib.Path:
    return REPO


@pytest.fixture
def shared() -> pathlib.Path:
    if not (SHARED / "volumes" / "mni152_t1.nii.gz").exists():
        pytest.skip(f"the shared data is not at {SHARED} (../shared/data next to the repository)")
    return SHARED


@pytest.fixture
def hatchery_bin() -> pathlib.Path:
    path = pathlib.Path(os.environ.get("HATCHERY_BIN", REPO / "target" / "release" / "hatchery"))
    if not path.exists():
        pytest.skip(f"the command line is not built at {path} (cargo build --release)")
    return path


def read_png(path) -> np.ndarray:
    from PIL import Image

    return np.asarray(Image.open(path).convert("RGBA"))


def assert_pictures_close(a: np.ndarray, b: np.ndarray, out_dir: pathlib.Path, tol: int = 1, what: str = "") -> None:
    """Equal within `tol`/255 per channel; on failure both pictures are written to `out_dir` and
    the worst pixel is named."""
    assert a.shape == b.shape, f"{what}: shapes {a.shape} and {b.shape}"
    diff = np.abs(a.astype(np.int16) - b.astype(np.int16))
    worst = int(diff.max())
    if worst > tol:
        from PIL import Image

        y, x, c = np.unravel_index(int(np.argmax(diff)), diff.shape)
        Image.fromarray(np.asarray(a, np.uint8)).save(out_dir / "a.png")
        Image.fromarray(np.asarray(b, np.uint8)).save(out_dir / "b.png")
        raise AssertionError(
            f"{what}: worst pixel ({x}, {y}) channel {c} differs by {worst}/255 "
            f"({a[y, x]} vs {b[y, x]}); pictures in {out_dir}"
        )


def blob(shape=(40, 36, 32), dtype=np.float32) -> np.ndarray:
    """A smooth off-centre blob with a bump (not symmetric, so a wrong axis order shows)."""
    i, j, k = np.meshgrid(*[np.linspace(-1, 1, n) for n in shape], indexing="ij")
    r2 = (i - 0.15) ** 2 / 0.5 + (j + 0.1) ** 2 / 0.35 + k**2 / 0.25
    v = 200.0 * np.exp(-2.5 * r2) + 80.0 * np.exp(-30.0 * ((i - 0.5) ** 2 + (j - 0.2) ** 2 + (k - 0.3) ** 2))
    return v.astype(dtype)


def oblique_affine() -> np.ndarray:
    """A voxel → world affine with anisotropic voxels, a rotation, an x flip and an offset."""
    c, s = np.cos(0.4), np.sin(0.4)
    rot = np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])
    a = np.eye(4)
    a[:3, :3] = rot @ np.diag([-1.2, 0.9, 1.5])
    a[:3, 3] = [30.0, -12.0, 7.0]
    return a
