# biscara's host for LinuxCNC's Python plug-ins (the INI file's [PYTHON] section).
#
# Run by `python3 -c` with: the TOPLEVEL file ("" when none), then the folders to put first on
# sys.path (PATH_PREPEND) and last (PATH_APPEND), separated by a "--" argument. It stands in for
# LinuxCNC's embedded modules `interpreter` (the interpreter as `this`, its parameters, a few of
# its attributes) and `emccanon` (the canon calls that move: STRAIGHT_FEED, STRAIGHT_TRAVERSE,
# DWELL; MESSAGE and COMMENT do nothing); the interpreter's state stays with biscara, asked for
# over the pipe when Python reads it.
#
# The protocol, one line each way, fields separated by tabs, text fields escaped (\\ \t \n \r):
#   biscara -> Python: `callable NAME`, `call NAME ARG...`, `exec AS_FILE CODE`, `reload`.
#   Python -> biscara, while one runs: `param NAME`, `paramn INDEX`, `setparam NAME VALUE`,
#     `setparamn INDEX VALUE`, `names locals|globals`, `attr NAME`, `setattr NAME VALUE`,
#     `canon NAME ARG...`; each answered `ok [VALUE...]`, `str TEXT` or `err MESSAGE`.
#   Python -> biscara, at its end (and once TOPLEVEL has run): `done none|float V|int V|str TEXT|bool 0|1|generator|other
#     REPR TYPE`, or `raised MESSAGE`.
# Python's own standard output goes to standard error: the pipe is the protocol's.
import os
import sys
import traceback
import types

_out = os.fdopen(os.dup(1), "w", encoding="utf-8", newline="\n")
_in = os.fdopen(os.dup(0), "r", encoding="utf-8", newline="\n")
os.dup2(2, 1)
_null = os.open(os.devnull, os.O_RDONLY)
os.dup2(_null, 0)
sys.stdout = sys.stderr
sys.stdin = open(os.devnull, encoding="utf-8")


def _escape(text):
    return (
        str(text)
        .replace("\\", "\\\\")
        .replace("\t", "\\t")
        .replace("\n", "\\n")
        .replace("\r", "\\r")
    )


def _unescape(text):
    out = []
    chars = iter(text)
    for char in chars:
        if char == "\\":
            char = {"t": "\t", "n": "\n", "r": "\r"}.get(next(chars, "\\"), "\\")
        out.append(char)
    return "".join(out)


def _send(*fields):
    _out.write("\t".join(fields) + "\n")
    _out.flush()


def _ask(*fields):
    """Sends a request to biscara and returns its answer's fields; `err` raises."""
    _send(*fields)
    line = _in.readline()
    if not line:
        sys.exit(0)
    answer = line.rstrip("\n").split("\t")
    if answer[0] == "err":
        raise RuntimeError(_unescape(answer[1]))
    return answer


def _number(value):
    return repr(float(value))


class Params:
    """The interpreter's parameters: `params[5220]`, `params["_x"]`, assignable."""

    def __getitem__(self, key):
        if isinstance(key, bool) or not isinstance(key, (int, str)):
            raise RuntimeError("params subscript type must be integer or string")
        if isinstance(key, int):
            return float(_ask("paramn", str(key))[1])
        return float(_ask("param", _escape(key))[1])

    def __setitem__(self, key, value):
        if isinstance(key, bool) or not isinstance(key, (int, str)):
            raise RuntimeError("params subscript type must be integer or string")
        if isinstance(key, int):
            _ask("setparamn", str(key), _number(value))
        else:
            _ask("setparam", _escape(key), _number(value))

    def __len__(self):
        return 5602

    def locals(self):
        return [_unescape(name) for name in _ask("names", "locals")[1:]]

    def globals(self):
        return [_unescape(name) for name in _ask("names", "globals")[1:]]

    def __call__(self):
        return self.locals() + self.globals()


def _attribute(name, writable=False):
    def get(self):
        answer = _ask("attr", name)
        return _unescape(answer[1]) if answer[0] == "str" else float(answer[1])

    def put(self, value):
        _ask("setattr", name, _number(value))

    return property(get, put if writable else None)


_ATTRIBUTES = (
    "params return_value value_returned call_level remap_level sequence_number task "
    "filename current_x current_y current_z feed_rate"
)


class Interp:
    """LinuxCNC's interpreter as Python sees it (`self`, `interpreter.this`); attributes set
    on it are kept for the whole run, as LinuxCNC keeps them."""

    params = property(lambda self: _params)
    return_value = _attribute("return_value", writable=True)
    value_returned = _attribute("value_returned", writable=True)
    call_level = _attribute("call_level")
    remap_level = _attribute("remap_level")
    sequence_number = _attribute("sequence_number")
    task = _attribute("task")
    filename = _attribute("filename")
    current_x = _attribute("current_x")
    current_y = _attribute("current_y")
    current_z = _attribute("current_z")
    feed_rate = _attribute("feed_rate")

    def __getattr__(self, name):
        raise AttributeError(
            f"'Interp' object has no attribute '{name}' (biscara's interpreter gives "
            f"Python: {_ATTRIBUTES.replace(' ', ', ')}, and what Python sets on it)"
        )


_params = Params()
this = Interp()

interpreter = types.ModuleType("interpreter", "biscara's stand-in for LinuxCNC's interpreter")
interpreter.this = this
interpreter.Interp = Interp
interpreter.TOLERANCE_EQUAL = 0.0001
for _value, _name in enumerate(
    "INTERP_OK INTERP_EXIT INTERP_EXECUTE_FINISH INTERP_ENDFILE INTERP_FILE_NOT_OPEN "
    "INTERP_ERROR".split()
):
    setattr(interpreter, _name, _value)
interpreter.INTERP_MIN_ERROR = 3
interpreter.equal = lambda a, b: abs(a - b) < 0.0001
interpreter.is_near_int = lambda value: abs(int(value + 0.5) - value) < 0.0001
interpreter.nearest_int = lambda value: int(value + 0.5)


def _missing(module, offers):
    def missing(name):
        if name.startswith("__"):
            raise AttributeError(name)
        raise AttributeError(
            f"module '{module}' has no attribute '{name}' (biscara's {module} gives Python: "
            f"{offers}; the rest of LinuxCNC's is not supported)"
        )

    return missing


interpreter.__getattr__ = _missing(
    "interpreter", "this, equal, is_near_int, nearest_int, the INTERP_ codes, TOLERANCE_EQUAL"
)

emccanon = types.ModuleType("emccanon", "biscara's stand-in for LinuxCNC's emccanon")


def _move(name):
    def move(line_number, x, y, z, a, b, c, u, v, w):
        _ask("canon", name, *(_number(value) for value in (x, y, z, a, b, c, u, v, w)))

    move.__name__ = name
    return move


emccanon.STRAIGHT_FEED = _move("STRAIGHT_FEED")
emccanon.STRAIGHT_TRAVERSE = _move("STRAIGHT_TRAVERSE")
emccanon.DWELL = lambda seconds: _ask("canon", "DWELL", _number(seconds)) and None
emccanon.MESSAGE = lambda text: None
emccanon.COMMENT = lambda text: None
emccanon.__getattr__ = _missing(
    "emccanon", "STRAIGHT_FEED, STRAIGHT_TRAVERSE, DWELL, MESSAGE, COMMENT"
)

sys.modules["interpreter"] = interpreter
sys.modules["emccanon"] = emccanon

_toplevel = sys.argv[1]
_split = sys.argv.index("--")
for _folder in reversed(sys.argv[2:_split]):
    sys.path.insert(0, _folder)
sys.path.extend(sys.argv[_split + 1 :])
_main = {"__name__": "__main__", "interpreter": interpreter, "emccanon": emccanon}


def _failure(error):
    """One line: the exception and where in the plug-in's code it was raised."""
    what = "".join(traceback.format_exception_only(type(error), error)).strip()
    what = " ".join(what.split("\n")[-1:]) or type(error).__name__
    frames = [
        frame
        for frame in traceback.extract_tb(error.__traceback__)
        if frame.filename != "<string>"
    ]
    if frames:
        frame = frames[-1]
        what += f" (at {os.path.basename(frame.filename)}:{frame.lineno}, in {frame.name})"
    return what


def _load():
    if _toplevel:
        with open(_toplevel, encoding="utf-8") as file:
            code = compile(file.read(), _toplevel, "exec")
        exec(code, _main)
    if callable(_main.get("__init__")):
        _main["__init__"](this)


def _oword(name):
    module = _main.get("oword")
    function = getattr(module, name, None) if isinstance(module, types.ModuleType) else None
    return function if callable(function) else None


def _result(value):
    if value is None:
        return ("done", "none")
    if isinstance(value, types.GeneratorType):
        return ("done", "generator")
    if isinstance(value, str):
        return ("done", "str", _escape(value))
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        return ("done", "other", _escape(repr(value)), _escape(type(value).__name__))
    if isinstance(value, int):
        return ("done", "int", str(value))
    return ("done", "float", repr(value))


def _serve():
    try:
        _load()
    except BaseException as error:  # noqa: BLE001 - every failure is reported
        _send("raised", _escape(_failure(error)))
        return
    _send("done", "none")
    for line in _in:
        fields = line.rstrip("\n").split("\t")
        try:
            if fields[0] == "callable":
                _send("done", "bool", "1" if _oword(_unescape(fields[1])) else "0")
            elif fields[0] == "call":
                function = _oword(_unescape(fields[1]))
                if function is None:
                    raise NameError(f"oword.{_unescape(fields[1])} is not callable")
                arguments = [float(value) for value in fields[2:]]
                _send(*_result(function(this, *arguments)))
            elif fields[0] == "exec":
                code = _unescape(fields[2])
                if fields[1] == "1":
                    with open(code, encoding="utf-8") as file:
                        code = file.read()
                exec(compile(code, "<py comment>", "exec"), _main)
                _send("done", "none")
            elif fields[0] == "reload":
                _load()
                _send("done", "none")
            else:
                raise ValueError(f"unknown request {fields[0]!r}")
        except SystemExit:
            return
        except BaseException as error:  # noqa: BLE001 - every failure is reported
            _send("raised", _escape(_failure(error)))


_serve()
