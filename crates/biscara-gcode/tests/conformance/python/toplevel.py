# TOPLEVEL of the conformance programs' Python plug-ins (python_*.ini): LinuxCNC runs it first;
# its `oword` module holds the O-word subroutines written in Python.
import oword  # noqa: F401
import interpreter


def __init__(self):
    # LinuxCNC calls this with the interpreter once the plug-ins are loaded.
    self.calls = 0
    self.params["_python_loaded"] = 1.0 if self is interpreter.this else 2.0
