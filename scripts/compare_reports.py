"""Compare two report folders written by ``terradyn reproduce`` row by row: findings (text and verdict),
metrics, settings and tables; wall times, code fingerprints, versions and figure bytes are left out.

Run: python scripts/compare_reports.py BEFORE_FOLDER AFTER_FOLDER   (exit 1 when a row differs)
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

COMPARED = ("status", "settings", "metrics", "findings", "tables")


def _untimed(value: object) -> object:
    """``value`` without wall-clock fields (keys naming a wall time), which differ run to run."""
    if isinstance(value, dict):
        return {k: _untimed(v) for k, v in value.items() if "wall_time" not in k}
    if isinstance(value, list):
        return [_untimed(v) for v in value]
    return value


def rows(folder: Path) -> dict[str, dict]:
    return {
        p.name: json.loads(p.read_text(encoding="utf-8")) for p in sorted((folder / "cache").glob("*.json"))
    }


def main(before: Path, after: Path) -> int:
    a, b = rows(before), rows(after)
    differ = 0
    for name in sorted(set(a) | set(b)):
        if name not in a or name not in b:
            print(f"{name}: only in {'after' if name in b else 'before'}")
            differ += 1
            continue
        bad = [k for k in COMPARED if _untimed(a[name].get(k)) != _untimed(b[name].get(k))]
        if bad:
            differ += 1
            print(f"{name}: differs in {', '.join(bad)}")
            for k in bad:
                print(f"  before {k}: {json.dumps(a[name].get(k))[:600]}")
                print(f"  after  {k}: {json.dumps(b[name].get(k))[:600]}")
    print(f"{len(set(a) | set(b))} rows compared, {differ} differ")
    return 1 if differ else 0


if __name__ == "__main__":
    sys.exit(main(Path(sys.argv[1]), Path(sys.argv[2])))
