"""The bench scripts' one way to find Debian's NumPy and SciPy.

Debian's python3-numpy and python3-scipy live in /usr/bin/python3's dist-packages; another
python3 first on PATH (a pyenv shim, a venv) does not see them.
"""
import os
import sys


def reexec_or_exit(script, message):
    """From an ImportError handler: re-runs `script` (with its arguments) once under
    /usr/bin/python3, else exits with `message` (what is missing and how to install it)."""
    flag = "NEEDLE_BENCH_REEXEC"
    if os.path.exists("/usr/bin/python3") and not os.environ.get(flag):
        os.environ[flag] = "1"
        os.execv("/usr/bin/python3", ["/usr/bin/python3", os.path.abspath(script)] + sys.argv[1:])
    sys.exit(message)
