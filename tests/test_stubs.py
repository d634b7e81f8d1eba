"""The stubs of the compiled module (_core.pyi) agree with what the extension really exports."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import restitution

#: numpy and polars are not analysed (loading their stubs takes mypy ~25 s, and their types become
#: Any): stubtest still checks every name, parameter name, kind and default against the runtime.
MYPY_CONFIG = "[mypy]\n[mypy-numpy.*,polars.*]\nfollow_imports = skip\nfollow_imports_for_stubs = True\n"


def stubtest(tmp_path: Path, mypypath: Path | None = None) -> subprocess.CompletedProcess[str]:
    config = tmp_path / "mypy.ini"
    config.write_text(MYPY_CONFIG)
    env = dict(os.environ)
    if mypypath is not None:
        env["MYPYPATH"] = str(mypypath)  # searched before the installed package
    return subprocess.run(
        [sys.executable, "-m", "mypy.stubtest", "--mypy-config-file", str(config), "restitution._core"],
        capture_output=True, text=True, cwd=tmp_path, env=env, timeout=300,
    )


def test_core_stubs_match_the_extension(tmp_path: Path) -> None:
    done = stubtest(tmp_path)
    assert done.returncode == 0, done.stdout + done.stderr


def test_stubtest_would_notice_drift(tmp_path: Path) -> None:
    # A stub with a parameter the extension lacks must be caught, or the test above proves nothing.
    real = Path(restitution.__file__).with_name("_core.pyi").read_text()
    # Appended after run_cases' last parameter, so it cannot be mistaken for a renamed one.
    end = ") -> dict[str, np.ndarray]:\n"
    assert end in real
    stubs = tmp_path / "stubs" / "restitution"
    stubs.mkdir(parents=True)
    (stubs / "__init__.pyi").write_text("")
    (stubs / "_core.pyi").write_text(real.replace(end, "    extra: int = 0,\n" + end, 1))
    done = stubtest(tmp_path, mypypath=stubs.parent)
    assert done.returncode != 0
    assert 'does not have parameter "extra"' in done.stdout, done.stdout
