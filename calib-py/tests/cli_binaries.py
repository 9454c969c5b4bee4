"""The command-line tools the Python results are compared with."""

import os
import subprocess
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]


def repo_binary(name: str) -> Path:
    """The CLI `name` (gough, arm) of crate calib-`name`: $<NAME>_BIN, else a build in the
    repository's target folder (built if missing), so the comparison with the CLI always runs."""
    env = os.environ.get(f"{name.upper()}_BIN")
    if env:
        return Path(env)
    for profile in ("release", "debug"):
        path = REPO / "target" / profile / name
        if path.exists():
            return path
    subprocess.run(["cargo", "build", "-p", f"calib-{name}", "--bin", name], cwd=REPO, check=True)
    return REPO / "target" / "debug" / name
