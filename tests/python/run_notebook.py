"""Executes a notebook headless (nbclient, Debian's python3-nbclient and python3-ipykernel) from the
repository's root; exits non-zero, naming the cell, when a cell fails.

    PYTHONPATH=build/python /usr/bin/python3 tests/python/run_notebook.py docs/notebooks/path-integral.ipynb [OUT.ipynb]
"""
import pathlib
import sys

import nbclient
import nbformat

path = pathlib.Path(sys.argv[1])
notebook = nbformat.read(path, as_version=4)
root = pathlib.Path(__file__).resolve().parents[2]
client = nbclient.NotebookClient(notebook, timeout=300, kernel_name="python3", resources={"metadata": {"path": str(root)}})
try:
    client.execute()
except nbclient.exceptions.CellExecutionError as e:
    print(f"{path}: a cell failed:\n{e}", file=sys.stderr)
    sys.exit(1)
if len(sys.argv) > 2:
    nbformat.write(notebook, sys.argv[2])
print(f"{path}: {len(notebook.cells)} cells ran")
