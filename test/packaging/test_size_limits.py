"""Size limits of the C++ code in src/ and include/: no file over 500 lines and no function
(lambdas included) over 80 lines. universal-ctags finds the functions and gives each one's
first and last line, so this test parses no C++ of its own.

The one exception is the interpreter's run loop (src/core/interpreter_run.inc): its handlers
end in computed gotos to one another's labels, which only works inside one function."""
import os
import re
import subprocess

# realpath: run from the workspace, this file is reached through its links to the package.
ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.realpath(__file__))))
MAX_FILE_LINES = 500
MAX_FUNCTION_LINES = 80
CPP = (".cpp", ".h", ".hpp", ".inc")
EXEMPT_FUNCTIONS = {"src/core/interpreter_run.inc"}


def cpp_files():
    out = []
    for top in ("src", "include"):
        for d, _, names in os.walk(os.path.join(ROOT, top)):
            out += [os.path.relpath(os.path.join(d, n), ROOT) for n in names if n.endswith(CPP)]
    return sorted(out)


def readable(scope, name):
    # ctags names an anonymous namespace or a lambda __anon<hash>: a lambda is the function
    # itself (the last name), an anonymous namespace only a scope to leave out.
    parts = [p for p in (scope.split("::") if scope else []) if not p.startswith("__anon")]
    parts = [p for p in parts if p != "plc_cell"]
    return "::".join(parts + ["<lambda>" if name.startswith("__anon") else name])


def functions(paths):
    """(path, first line, last line, name) of every function definition ctags finds."""
    out = subprocess.run(
        ["ctags", "-x", "--_xformat=%{input}\t%{line}\t%{end}\t%{scope}\t%{name}", "--langmap=C++:+.inc",
         "--languages=C++", "--kinds-C++=f", "--fields=+ne", "-o", "-"] + paths,
        cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.PIPE, universal_newlines=True, check=True).stdout
    for line in out.splitlines():
        path, first, last, scope, name = line.split("\t")
        yield path, int(first), int(last), readable(re.sub(r"^[a-z]+:", "", scope), name)


def test_ctags_sees_every_function():
    # Against a test that cannot fail: the tool finds the functions of a known file with
    # their real extents (Interpreter::load is in interpreter.cpp, the run loop in its .inc).
    found = {(name, path) for path, first, last, name in functions(["src/core/interpreter.cpp",
                                                                   "src/core/interpreter_run.inc"])}
    assert ("Interpreter::load", "src/core/interpreter.cpp") in found, sorted(found)
    runs = [(f, l) for p, f, l, n in functions(["src/core/interpreter_run.inc"]) if n == "Interpreter::PLC_RUN"]
    assert len(runs) == 1 and runs[0][1] - runs[0][0] > MAX_FUNCTION_LINES, runs


def test_no_file_over_500_lines():
    long_files = []
    for path in cpp_files():
        with open(os.path.join(ROOT, path), encoding="utf-8", errors="replace") as f:
            n = sum(1 for _ in f)
        if n > MAX_FILE_LINES:
            long_files.append("%s:1 (%d lines)" % (path, n))
    assert not long_files, "files over %d lines:\n%s" % (MAX_FILE_LINES, "\n".join(long_files))


def test_no_function_over_80_lines():
    long_functions = []
    for path, first, last, name in functions(cpp_files()):
        n = last - first + 1
        if n > MAX_FUNCTION_LINES and path not in EXEMPT_FUNCTIONS:
            long_functions.append((path, first, "%s:%d %s (%d lines)" % (path, first, name, n)))
    assert not long_functions, "functions over %d lines:\n%s" % (
        MAX_FUNCTION_LINES, "\n".join(text for _, _, text in sorted(long_functions)))
