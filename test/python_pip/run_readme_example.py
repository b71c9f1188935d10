#!/usr/bin/env python3
"""Runs the first Python block of README.md's "Using it from Python" section (exit code 1 if it
raises), so that the README's example is checked against the installed package."""

import re
import sys

with open(sys.argv[1]) as f:
    text = f.read()
section = text[text.index("## Using it from Python"):text.index("## Samples")]
example = re.findall(r"```python\n(.*?)```", section, re.S)[0]
exec(compile(example, "README.md example", "exec"), {})
