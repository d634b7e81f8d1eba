"""The property tests of tests/test_hypothesis.py at ten times their CI counts: about 10^5 random
scenes and fuzzed inputs. Prints the wall time and the examples per second.

    python benchmarks/hypothesis_1e5.py [scale]      # default scale 10 (CI runs scale 1, ~10^4)
"""

from __future__ import annotations

import os
import subprocess
import sys
import time
from pathlib import Path

if __name__ == "__main__":
    scale = sys.argv[1] if len(sys.argv) > 1 else "10"
    root = Path(__file__).resolve().parents[1]
    env = dict(os.environ, RESTITUTION_HYPOTHESIS_SCALE=scale)
    start = time.perf_counter()
    rc = subprocess.call([sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider",
                          str(root / "tests" / "test_hypothesis.py")], env=env, cwd=root)
    wall = time.perf_counter() - start
    examples = 10_600 * int(scale)  # the sum of the max_examples in tests/test_hypothesis.py
    print(f"hypothesis at scale {scale}: about {examples} examples in {wall:.0f} s ({examples / wall:.0f}/s), rc {rc}")
    raise SystemExit(rc)
