# O-word subroutines written in Python, for the conformance programs python_*.ngc: each is
# called as `o<name> call [args]` with the interpreter as `self`.
import emccanon


def square(self, x, y, side):
    """Feeds around a square at the current Z, corner (x, y), in program coordinates."""
    z = self.params["_z"]
    for dx, dy in ((side, 0), (side, side), (0, side), (0, 0)):
        emccanon.STRAIGHT_FEED(1, x + dx, y + dy, z, 0, 0, 0, 0, 0, 0)
    emccanon.STRAIGHT_TRAVERSE(2, x, y, z + 5, 0, 0, 0, 0, 0, 0)
    return side * 4.0


def hypot(self, a, b):
    return (a * a + b * b) ** 0.5


def counted(self, *args):
    """Counts its calls on self (kept across calls) and reports the arguments it was given."""
    self.calls += 1
    self.params["_calls"] = self.calls
    self.params["_nargs"] = len(args)
    self.params["local_only"] = 7.0
    self.params[100] = sum(args)
    return None


def caller_parameter(self):
    """#1 of the caller: a Python subroutine has no #1-#30 of its own."""
    return self.params[1]


def fails(self, *args):
    raise ValueError("the subroutine failed on purpose")


def says_why(self, *args):
    return "says_why: a string returned is the error"


def returns_an_int(self, *args):
    return 5
