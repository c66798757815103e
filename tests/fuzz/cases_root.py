"""The package root's own public function: ``data_path``."""

from cga_lessons import data_path
from fuzz.harness import Case

CASES = [
    Case(
        data_path,
        {"*args": ("carmen", "intel-corrected.log.gz")},
        skip={"*args": "spoiled by the whole tuples below: the parts are names, not numbers"},
        label="data_path",
        extra={"*args": [("no-such-folder", "x.log"), ("..", "README.md"), ("/etc", "passwd"), (None,), ("", "x")]},
    ),
]
EXEMPT = {}
