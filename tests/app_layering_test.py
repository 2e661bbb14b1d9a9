#!/usr/bin/env python3
"""app/ reaches ui/ through one header, ui/run_viewer.h, the entry point of `pathlab view` (issue
30): the commands share nothing else with the viewer, so ui/ can be reshaped without touching the
CLI. Prints every other ui/ include of app/ and fails."""
import pathlib, re, sys

app = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else pathlib.Path(__file__).parent.parent / "app")
entry = "ui/run_viewer.h"
include = re.compile(r'#include\s+[<"]([^">]+)[">]')
bad, entries = [], 0
for f in sorted(app.rglob("*")):
    if f.suffix not in (".h", ".cpp"):
        continue
    for target in include.findall(f.read_text(errors="replace")):
        if target == entry:
            entries += 1
        elif target.startswith("ui/"):
            bad.append(f"{f}: includes {target} (app/ may include only {entry} of ui/)")
for b in bad:
    print(b)
print(f"{entries} includes of {entry}, {len(bad)} other ui/ includes in {app}")
sys.exit(1 if bad else 0)
