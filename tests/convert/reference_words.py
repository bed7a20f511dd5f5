#!/usr/bin/env python3
"""Grows real cpfg files (vlab's examples) with a small L-system engine of this script's
own and compares each step's word, module by module and parameter by parameter, with the
word `ontogen word` grows from the same file (converted). The engine shares nothing with
ontogen: it reads the .l file itself (macros, the axiom, productions with contexts,
conditions and C expressions, ignore and consider lists) and rewrites strings as cpfg
does (each module by the first production that matches it, in the file's order).

  python3 tests/convert/reference_words.py --ontogen build/apps/ontogen --vlab /path/to/vlab

The repository's own cpfg files (tests/convert/*.l) are grown wherever it runs; the vlab
checkout's (given by --vlab or the environment's ONTOGEN_VLAB, as ctest runs it) only where
there is one, since vlab's files are not kept here. Exit 1 when any file's word differs.
"""
import argparse
import json
import math
import os
import pathlib
import re
import subprocess
import sys

# The files, under vlab/oofs/ext, and the last step compared (None: the file's derivation
# length; the signals' files derive one step, and are compared over more).
FILES = [
    ("10-manuals/ext/11-CPFG/ext/DragonCurve/fractal.l", 10),
    ("10-manuals/ext/11-CPFG/ext/GeneralizedCylinder/fractal.l", None),
    ("11-CPFG/ext/01-Introduction/ext/01-quadratic-Koch/fractal.l", None),
    ("11-CPFG/ext/01-Introduction/ext/03-snowflake/fractal.l", None),
    ("11-CPFG/ext/01-Introduction/ext/04-compound/leaf.l", None),
    ("11-CPFG/ext/01-Introduction/ext/05-compound-homo/leaf.l", None),
    ("11-CPFG/ext/01-Introduction/ext/06-compound-param/leaf.l", None),
    ("11-CPFG/ext/01-Introduction/ext/07-fractal-ferns/leaf.l", None),
    ("11-CPFG/ext/04-Signaling/ext/01-hormone-up/fractal.l", 12),
    ("11-CPFG/ext/04-Signaling/ext/02-hormone-down/fractal.l", 12),
    ("11-CPFG/ext/04-Signaling/ext/03-signal-down/fractal.l", 12),
    ("11-CPFG/ext/04-Signaling/ext/04-florigen/fractal.l", None),
    ("11-CPFG/ext/04-Signaling/ext/05-florigen-param/fractal.l", None),
    ("11-CPFG/ext/04-Signaling/ext/06-florigen+auxin/fractal.l", None),
    ("11-CPFG/ext/04-Signaling/ext/07-acrotonic-2-signals/fractal.l", None),
    ("11-CPFG/ext/04-Signaling/ext/08-basipetal-2-signals/fractal.l", None),
]

# The repository's own cpfg files (tests/convert/), grown wherever the test runs.
OWN_FILES = ["fig1_24b.l", "fig1_24d.l", "parametric_1_35.l", "signal.l", "fig1_5_digits.l", "c_textual.l",
             "continued.l"]

# A word longer than this is not compared past the step that reaches it (the test's time).
MAX_MODULES = 20000

# cpfg's module names of more than one character (the first that fits is taken).
LONG_NAMES = sorted(["@Gs", "@Gc", "@Ge", "@Gt", "@Gr", "@Tx", "@Ts", "@Ti", "@Td", "@Tp", "@Tf", "@Dd", "@Di",
                     "@bo", "@bc", "@O", "@o", "@v", "@c", "@M", "@R", "@L", "@b", "@D", "@#", "@!",
                     "?P", "?H", "?L", "?U", "?E"], key=len, reverse=True)

# How ontogen's word spells cpfg's modules whose labels the cell language has not
# (docs/LANGUAGE.md, "Coming from cpfg"): compared in cpfg's spelling.
ONTOGEN_SPELLING = {"color": ";", "sphere": "@O", "disc": "@o", "Texture": "@Tx", "SetElasticity": "@Ts",
                    "DecColor": ",", "IncWidth": "#", "BP": "{", "EP": "}", "PP": ".", "CylinderSides": "@!",
                    "gcbegin": "@Gs", "ContinueSpline": "@Gc", "gcend": "@Ge", "SplineTangents": "@Gt",
                    "RadiusTangents": "@Gr", "Circle3D": "@c"}


class Unsupported(Exception):
    pass


# ---------------------------------------------------------------- the text of the file

def without_comments(text):
    text = re.sub(r"/\*.*?\*/", lambda m: re.sub(r"[^\n]", " ", m.group(0)), text, flags=re.S)
    text = re.sub(r"//[^\n]*", "", text)
    text = re.sub(r"\\\r?\n", " ", text)
    return re.sub(r"\r?\n\t", " ", text)  # cpfg reads a line break and a tab as a space


def tokens_of(text):
    return re.findall(r"\d+\.?\d*(?:[eE][-+]?\d+)?|\.\d+(?:[eE][-+]?\d+)?|[A-Za-z_]\w*|&&|\|\||==|!=|<=|>=|\S",
                      text)


def expand(text, macros):
    """C's textual replacement of macros without parameters: each name that is a macro's
    (a whole identifier, as the preprocessor reads it) by its value, again in the value."""
    for _ in range(20):
        replaced = re.sub(r"[A-Za-z_]\w*", lambda m: " " + macros[m.group(0)] + " " if m.group(0) in macros
                          else m.group(0), text)
        if replaced == text:
            return text
        text = replaced
    raise Unsupported("macros nested too deep")


# ---------------------------------------------------------------- expressions (cpfg's C)

class Expression:
    """A C expression of cpfg evaluated with its rules: comparisons give 1 or 0, `^` is a
    power binding looser than a unary minus, `/` by 0 divides by 1, angles in degrees."""

    BINARY = {"||": 1, "&&": 2, "==": 3, "!=": 3, "<": 4, ">": 4, "<=": 4, ">=": 4, "+": 5, "-": 5, "*": 6,
              "/": 6, "%": 6, "^": 7}

    def __init__(self, text):
        self.tokens = tokens_of(text)
        self.at = 0
        self.tree = self.ternary()
        if self.at != len(self.tokens):
            raise Unsupported(f"cannot read the expression '{text}'")

    def peek(self):
        return self.tokens[self.at] if self.at < len(self.tokens) else None

    def take(self, expected=None):
        token = self.peek()
        if token is None or (expected is not None and token != expected):
            raise Unsupported(f"expected {expected!r}, found {token!r}")
        self.at += 1
        return token

    def ternary(self):
        condition = self.binary(1)
        if self.peek() == "?":
            self.take("?")
            yes = self.ternary()
            self.take(":")
            no = self.ternary()
            return ("?", condition, yes, no)
        return condition

    def binary(self, level):
        left = self.unary()
        while self.peek() in self.BINARY and self.BINARY[self.peek()] >= level:
            op = self.take()
            right = self.binary(self.BINARY[op] + 1)
            left = (op, left, right)
        return left

    def unary(self):
        if self.peek() in ("-", "+", "!"):
            op = self.take()
            return ("u" + op, self.unary())
        return self.primary()

    def primary(self):
        token = self.take()
        if token == "(":
            inner = self.ternary()
            self.take(")")
            return inner
        if re.match(r"[\d.]", token):
            return ("n", float(token))
        if re.match(r"[A-Za-z_]", token):
            if self.peek() == "(":
                self.take("(")
                args = []
                while self.peek() != ")":
                    args.append(self.ternary())
                    if self.peek() == ",":
                        self.take(",")
                self.take(")")
                return ("call", token, args)
            return ("name", token)
        raise Unsupported(f"unexpected '{token}' in an expression")

    FUNCTIONS = {
        "sin": lambda x: math.sin(math.radians(x)), "cos": lambda x: math.cos(math.radians(x)),
        "tan": lambda x: math.tan(math.radians(x)), "asin": lambda x: math.degrees(math.asin(x)),
        "acos": lambda x: math.degrees(math.acos(x)), "atan": lambda x: math.degrees(math.atan(x)),
        "sqrt": math.sqrt, "exp": math.exp, "log": math.log, "floor": math.floor, "ceil": math.ceil,
        "fabs": abs, "trunc": math.trunc, "min": min, "max": max,
    }

    def value(self, names, node=None):
        node = self.tree if node is None else node
        kind = node[0]
        if kind == "n":
            return node[1]
        if kind == "name":
            if node[1] not in names:
                raise Unsupported(f"unknown name '{node[1]}'")
            return names[node[1]]
        if kind == "call":
            if node[1] not in self.FUNCTIONS:
                raise Unsupported(f"function '{node[1]}'")
            return float(self.FUNCTIONS[node[1]](*(self.value(names, a) for a in node[2])))
        if kind == "?":
            return self.value(names, node[2]) if self.value(names, node[1]) != 0 else self.value(names, node[3])
        if kind == "u-":
            return -self.value(names, node[1])
        if kind == "u+":
            return self.value(names, node[1])
        if kind == "u!":
            return 1.0 if self.value(names, node[1]) == 0 else 0.0
        op, a = node[0], self.value(names, node[1])
        if op == "&&":
            return 1.0 if a != 0 and self.value(names, node[2]) != 0 else 0.0
        if op == "||":
            return 1.0 if a != 0 or self.value(names, node[2]) != 0 else 0.0
        b = self.value(names, node[2])
        if op in ("==", "!=", "<", ">", "<=", ">="):
            return 1.0 if {"==": a == b, "!=": a != b, "<": a < b, ">": a > b, "<=": a <= b, ">=": a >= b}[op] else 0.0
        if op == "+":
            return a + b
        if op == "-":
            return a - b
        if op == "*":
            return a * b
        if op == "/":
            return a / (b if b != 0 else 1.0)
        if op == "%":
            return math.fmod(math.trunc(a), math.trunc(b))
        if op == "^":
            return a ** b
        raise Unsupported(f"operator {op}")


# ---------------------------------------------------------------- words and productions

def split_top(text, separator):
    """Splits at `separator` outside parentheses."""
    parts, depth, start = [], 0, 0
    for i, c in enumerate(text):
        depth += c == "("
        depth -= c == ")"
        if depth == 0 and c == separator:
            parts.append(text[start:i])
            start = i + 1
    parts.append(text[start:])
    return parts


def modules_of(text):
    """[(label, [argument text])] of a word written as cpfg writes it; None args: none."""
    result, at = [], 0
    while at < len(text):
        if text[at].isspace():
            at += 1
            continue
        label = next((name for name in LONG_NAMES if text.startswith(name, at)), text[at])
        at += len(label)
        args = None
        after = at
        while after < len(text) and text[after] == " ":
            after += 1
        if after < len(text) and text[after] == "(":
            depth, close = 0, after
            for close in range(after, len(text)):
                depth += text[close] == "("
                depth -= text[close] == ")"
                if depth == 0:
                    break
            args = [a.strip() for a in split_top(text[after + 1:close], ",")]
            at = close + 1
        result.append((label, args))
    return result


class Production:
    def __init__(self, text):
        left, right = text.split("-->", 1)
        parts = split_top(right, ":")
        if len(parts) > 1:
            raise Unsupported("a probability")
        successor = parts[0].strip()
        self.successor = [] if successor == "*" else [
            (label, None if args is None else [Expression(a) for a in args])
            for label, args in modules_of(successor)]
        pattern, *condition = split_top(left, ":")
        condition = condition[0].strip() if condition else "*"
        self.condition = None if condition == "*" else Expression(condition)
        if "{" in left:
            raise Unsupported("a C block")
        self.left, self.right = [], []
        if "<" in pattern:
            lc, pattern = pattern.split("<", 1)
            self.left = modules_of(lc)
        if ">" in pattern:
            pattern, rc = pattern.split(">", 1)
            self.right = modules_of(rc)
        strict = modules_of(pattern)
        if len(strict) != 1:
            raise Unsupported("a predecessor of several modules")
        self.predecessor = strict[0]
        for label, _ in self.left + self.right:
            if label in "[]":
                raise Unsupported("a bracket in a context")


def parse(path):
    text = without_comments(path.read_text(errors="replace"))
    macros, productions, axiom, steps = {}, [], None, None
    ignore, consider = set(), None
    section = "production"
    for line in text.split("\n"):
        line = line.strip()
        if not line:
            continue
        low = line.lower()
        if low.startswith("#define"):
            match = re.match(r"#define\s+(\w+)(\(?)\s*(.*)", line)
            if match.group(2):
                raise Unsupported("a macro with parameters")
            macros[match.group(1)] = match.group(3).strip()
            continue
        line = expand(line, macros)
        low = line.lower()
        if low.startswith(("lsystem:", "seed:", "maximum depth")):
            pass
        elif low.startswith("endlsystem"):
            break
        elif low.startswith("derivation length:"):
            steps = int(Expression(line.split(":", 1)[1]).value({}))
        elif low.startswith("axiom:"):
            axiom = line.split(":", 1)[1]
        elif low.startswith(("ignore:", "#ignore")):
            ignore |= {label for label, _ in modules_of(re.sub(r"^(ignore:|#ignore)", "", line, flags=re.I))}
        elif low.startswith(("consider:", "#consider")):
            consider = {label for label, _ in modules_of(re.sub(r"^(consider:|#consider)", "", line, flags=re.I))}
        elif low.startswith("decomposition"):
            raise Unsupported("a decomposition")
        elif low.startswith("homomorphism"):
            section = "homomorphism"  # the interpretation's: no step's word depends on it
        elif low.startswith(("start:", "end:", "starteach:", "endeach:", "define:")):
            raise Unsupported("a C block")
        elif "-->" in line:
            if section == "production":
                productions.append(Production(line))
        else:
            raise Unsupported(f"a line '{line}'")
    word = [(label, None if args is None else [Expression(a).value({}) for a in args])
            for label, args in modules_of(axiom)]
    return word, productions, steps, ignore, consider


# ---------------------------------------------------------------- the derivation

def skipped(label, ignore, consider):
    if consider is not None:
        return label not in consider and label not in "[]"
    return label in ignore


def bind(pattern, module, names):
    label, params = pattern
    if label != module[0] or len(params or []) != len(module[1] or []):
        return False
    for name, value in zip(params or [], module[1] or []):
        names[name] = value
    return True


def left_matches(word, at, context, ignore, consider, names):
    i = at - 1
    for pattern in reversed(context):
        while i >= 0:
            label = word[i][0]
            if label == "]":  # a whole branch on the left
                depth = 0
                while i >= 0:
                    depth += word[i][0] == "]"
                    depth -= word[i][0] == "["
                    i -= 1
                    if depth == 0:
                        break
            elif label == "[" or skipped(label, ignore, consider):
                i -= 1
            else:
                break
        if i < 0 or not bind(pattern, word[i], names):
            return False
        i -= 1
    return True


def right_matches(word, at, context, ignore, consider, names):
    i = at + 1
    for pattern in context:
        while i < len(word):
            label = word[i][0]
            if label == "[":  # a branch the context does not enter
                depth = 0
                while i < len(word):
                    depth += word[i][0] == "["
                    depth -= word[i][0] == "]"
                    i += 1
                    if depth == 0:
                        break
            elif skipped(label, ignore, consider):
                i += 1
            else:
                break
        if i >= len(word) or word[i][0] == "]" or not bind(pattern, word[i], names):
            return False
        i += 1
    return True


def step(word, productions, ignore, consider):
    out = []
    for at, module in enumerate(word):
        for p in productions:
            names = {}
            if not bind(p.predecessor, module, names):
                continue
            if p.left and not left_matches(word, at, p.left, ignore, consider, names):
                continue
            if p.right and not right_matches(word, at, p.right, ignore, consider, names):
                continue
            if p.condition is not None and p.condition.value(names) == 0:
                continue
            out.extend((label, None if args is None else [a.value(names) for a in args]) for label, args in p.successor)
            break
        else:
            out.append(module)
    return out


# ---------------------------------------------------------------- the comparison

def ontogen_words(ontogen, path, times):
    done = subprocess.run([ontogen, "word", str(path), "--json", "--at", ",".join(map(str, times))],
                          capture_output=True, text=True, timeout=300)
    if done.returncode != 0:
        raise AssertionError(f"ontogen word failed ({done.returncode}): {done.stderr[:500]}")
    words = []
    for time in json.loads(done.stdout)["times"]:
        words.append([(ONTOGEN_SPELLING.get(c["label"], c["label"]), c["params"]) for c in time["cells"]])
    return words


def same(reference, grown):
    if len(reference) != len(grown):
        return f"{len(reference)} modules, ontogen {len(grown)}"
    for i, ((label, args), (glabel, gargs)) in enumerate(zip(reference, grown)):
        args = args or []
        if label != glabel or len(args) != len(gargs) or any(
                not math.isclose(a, b, rel_tol=1e-9, abs_tol=1e-9) for a, b in zip(args, gargs)):
            return f"module {i}: {label}{tuple(args)}, ontogen {glabel}{tuple(gargs)}"
    return None


# The engine itself against words ABOP prints (section 1.8's signal; p. 43's parametric
# L-system), from this folder's files of those figures, before it judges ontogen.
ABOP_WORDS = {
    "signal.l": ["b + a - a a", "a + b - a a", "a + a - b a", "a + a - a b"],
    "parametric_1_35.l": ["B(2) A(4, 4)", "B(1) B(4) A(1, 0)", "B(0) B(3) A(2, 1)", "C B(2) A(4, 3)",
                          "C B(1) A(8, 7)"],
}


def shown(word):
    return " ".join(label + ("" if args is None else "(" + ", ".join(f"{a:g}" for a in args) + ")")
                    for label, args in word)


def check_engine():
    for name, expected in ABOP_WORDS.items():
        word, productions, _, ignore, consider = parse(pathlib.Path(__file__).with_name(name))
        grown = [word]
        while len(grown) < len(expected):
            grown.append(step(grown[-1], productions, ignore, consider))
        if [shown(w) for w in grown] != expected:
            raise AssertionError(f"the engine grows {name} as {[shown(w) for w in grown]}, ABOP {expected}")


def compare(ontogen, path, label, last=None):
    """Grows one file by the engine and by ontogen; True when every step's word agrees."""
    word, productions, steps, ignore, consider = parse(path)
    steps = last or steps
    words = [word]
    while len(words) <= steps and len(words[-1]) <= MAX_MODULES:
        words.append(step(words[-1], productions, ignore, consider))
    times = list(range(1, len(words)))
    grown = ontogen_words(ontogen, path, times)
    differs = next(((t, why) for t, ref, got in zip(times, words[1:], grown) if (why := same(ref, got))), None)
    if differs:
        print(f"FAIL {label} at step {differs[0]}: {differs[1]}")
        return False
    print(f"ok   {label}: steps 1 to {times[-1]}, {len(words[-1])} modules at the last")
    return True


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--ontogen", default="build/apps/ontogen")
    parser.add_argument("--vlab", default=os.environ.get("ONTOGEN_VLAB"))
    args = parser.parse_args()
    check_engine()
    results = []
    # The repository's own cpfg files run everywhere, so the comparison never goes unrun.
    here = pathlib.Path(__file__).resolve().parent
    for name in OWN_FILES:
        results.append(compare(args.ontogen, here / name, name))
    if args.vlab and (pathlib.Path(args.vlab) / "oofs" / "ext").is_dir():
        root = pathlib.Path(args.vlab) / "oofs" / "ext"
        for name, last in FILES:
            results.append(compare(args.ontogen, root / name, name, last))
    else:
        print(f"no vlab checkout (--vlab or ONTOGEN_VLAB): its {len(FILES)} files not grown")
    passed = sum(results)
    print(f"{passed} passed, {len(results) - passed} failed")
    return 0 if passed == len(results) else 1


if __name__ == "__main__":
    sys.exit(main())
