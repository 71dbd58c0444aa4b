"""Random mutants in the lines changed since a revision: `make mutation-test RANDOM=N`.

Nobody chooses these mutants. Every changed line of a C++, GLSL or Python source file (under
src/, include/, shaders/, apps/, python/, tools/) yields its candidate one-line bugs; a seeded
draw picks N of them. tools/mutation_test.py plants each in its scratch tree and runs the tests
of the ctest labels that tests/mutations/coverage.toml maps the file to (then, for a survivor,
every other test).

Candidates (operator: kind):
  compare    a comparison to its neighbour (< <=, > >=, == !=); Python `is` / `is not`
  arith      binary `+` `-` (sign) and `*` `/` (swap) exchanged, `+=` `-=` `*=` `/=` likewise
  negate     a unary minus dropped (sign)
  logic      `&&` `||` exchanged; Python `and` `or`
  not        a `!` (Python `not`) dropped (logic)
  int        an integer literal n to n + 1, or n - 1 (off-by-one)
  float      a floating literal halved, 0 to 1 (constant)
  bool       `true` `false` exchanged; Python `True` `False` (constant)
  minmax     `min` `max`, `floor` `ceil` exchanged (swap)
  swap-args  the two simple arguments of a call exchanged: f(a, b) to f(b, a) (swap)
  drop       a one-line statement that declares nothing deleted; Python: `pass` (drop)
  if         an `if` condition made `true` or `false` (logic)

Nothing inside a string literal or a comment is touched; preprocessor lines, imports,
static_assert and assert (compiled out in release builds), templates' and includes' angle
brackets, stream and shift operators, ++ and --, declarations' and signatures' lines, and print,
log and throw statements are skipped. Binary operators must stand between spaces, as
clang-format writes them: that keeps `<` of a template and `*` of a pointer out.

The draw: candidates are sorted (file, line, column, operator, text), so the same tree, revision
and seed give the same mutants. random.Random(seed) shuffles the changed lines and each line's
candidates; the draw takes one candidate of each line in the shuffled order, then a second of
each, and so on: every changed line that can be mutated is equally likely to get the first
mutants, whatever its operators. The order goes on past N: the runner takes replacements from
it for mutants that do not build.
"""
import dataclasses
import difflib
import hashlib
import json
import random
import re
import subprocess
import tomllib
from pathlib import Path

SOURCE_DIRS = ("src/", "include/", "shaders/", "apps/", "python/", "tools/")
CPP_SUFFIXES = {".cpp", ".h", ".hpp", ".cc", ".cxx", ".inl"}
GLSL_SUFFIXES = {".glsl", ".comp", ".vert", ".frag", ".geom", ".tesc", ".tese", ".h"}
KIND = {"compare": "compare", "negate": "sign", "logic": "logic", "not": "logic",
        "int": "off-by-one", "float": "constant", "bool": "constant", "minmax": "swap",
        "swap-args": "swap", "drop": "drop", "if": "logic"}  # arith: sign or swap, per operator


def language(path):
    """'cpp', 'glsl' (shaders/, shared .h headers included) or 'python'; None: not mutated."""
    path = str(path)
    if not path.startswith(SOURCE_DIRS):
        return None
    suffix = Path(path).suffix
    if path.startswith("shaders/"):
        return "glsl" if suffix in GLSL_SUFFIXES else None
    if suffix in CPP_SUFFIXES:
        return "cpp"
    return "python" if suffix == ".py" else None


# --- which lines changed -----------------------------------------------------------------------

HUNK = re.compile(r"^@@ -\d+(?:,\d+)? \+(\d+)(?:,(\d+))? @@")


def parse_diff(text):
    """{path: set of line numbers added or changed} from `git diff -U0` output."""
    changed, current = {}, None
    for line in text.splitlines():
        if line.startswith("+++ "):
            name = line[4:].strip().strip('"')
            current = None if name == "/dev/null" else name.removeprefix("b/")
        elif line.startswith("@@") and current is not None:
            m = HUNK.match(line)
            if m:
                start = int(m.group(1))
                count = 1 if m.group(2) is None else int(m.group(2))
                changed.setdefault(current, set()).update(range(start, start + count))
    return {path: lines for path, lines in changed.items() if lines}


def git(root, *args):
    # Paths as they are (no octal quoting of non-ASCII names); bytes that are not UTF-8 kept
    # as they are, so a file in another encoding neither stops the draw nor is written back
    # changed.
    return subprocess.run(["git", "-c", "core.quotepath=off", *args], cwd=root, check=True,
                          capture_output=True, text=True, errors="surrogateescape").stdout


def verified_revision(root, since):
    """The commit `since` names; ValueError for an option, a range or a name git does not know."""
    if not since or since.startswith("-") or ".." in since:
        raise ValueError(f"'{since}' is not a revision")
    try:
        return git(root, "rev-parse", "--verify", "--quiet", "--end-of-options",
                   since + "^{commit}").strip()
    except subprocess.CalledProcessError:
        raise ValueError(f"'{since}' is not a commit of this repository") from None


def changed_lines(root, since, untracked=True):
    """Lines of the working tree added or changed since `since`; untracked files (not ignored)
    count as added whole."""
    changed = parse_diff(git(root, "diff", "-U0", "-M", "--no-color", "--no-ext-diff",
                             "--src-prefix=a/", "--dst-prefix=b/", since, "--"))
    if untracked:
        for name in git(root, "ls-files", "-o", "--exclude-standard", "-z").split("\0"):
            path = Path(root) / name
            if name and language(name) and path.is_file():
                count = len(path.read_text(errors="surrogateescape").splitlines())
                changed[name] = set(range(1, count + 1))
    return {p: lines for p, lines in changed.items() if language(p)}


# --- lexing: strings and comments out of the way ----------------------------------------------

def _word_before(text, i):
    j = i
    while j > 0 and (text[j - 1].isalnum() or text[j - 1] == "_"):
        j -= 1
    return j, text[j:i]


def _fill(out, start, end, char):
    for k in range(start, end):
        if out[k] != "\n":
            out[k] = char


def _string_end(text, i, quote):
    """End (exclusive) of a quoted literal opening at i: escapes skipped, a newline ends it."""
    n, j = len(text), i + len(quote)
    while j < n:
        if text[j] == "\\":
            j += 2
        elif text.startswith(quote, j):
            return j + len(quote)
        elif text[j] == "\n" and len(quote) == 1:
            return j
        else:
            j += 1
    return n


def blank(text, lang):
    """`text` with comments turned to spaces and string and character literals (prefixes too)
    to `"`: the same length and lines, so a column means the same in both."""
    out, n, i = list(text), len(text), 0
    while i < n:
        c = text[i]
        if lang == "python" and c == "#" or lang != "python" and text.startswith("//", i):
            end = text.find("\n", i)
            end = n if end < 0 else end
            _fill(out, i, end, " ")
            i = end
        elif lang != "python" and text.startswith("/*", i):
            end = text.find("*/", i + 2)
            end = n if end < 0 else end + 2
            _fill(out, i, end, " ")
            i = end
        elif c in "\"'":
            start, word = _word_before(text, i)
            if lang == "python":
                prefix = word.lower() in {"r", "u", "b", "f", "br", "rb", "fr", "rf"}
                quote = c * 3 if text.startswith(c * 3, i) else c
                end = _string_end(text, i, quote)
            else:
                if c == "'" and word[:1].isdigit():  # a digit separator: 100'000
                    i += 1
                    continue
                prefix = word in {"u8", "u", "U", "L", "R", "u8R", "uR", "UR", "LR"}
                raw = prefix and word.endswith("R") and c == '"'
                m = re.match(r'"([^()\\\s]{0,16})\(', text[i:]) if raw else None
                if m:
                    close = text.find(")" + m.group(1) + '"', i)
                    end = n if close < 0 else close + len(m.group(1)) + 2
                else:
                    end = _string_end(text, i, c)
            _fill(out, start if prefix else i, end, '"')
            i = end
        else:
            i += 1
    return "".join(out)


OPS_C = (r"<<=|>>=|<=>|->\*|\.\.\.|->|\+\+|--|<<|>>|<=|>=|==|!=|&&|\|\||\+=|-=|\*=|/=|%=|&=|"
         r"\|=|\^=|::")
OPS_PY = r"\*\*=|//=|>>=|<<=|->|:=|\*\*|//|<<|>>|<=|>=|==|!=|\+=|-=|\*=|/=|%=|&=|\|=|\^=|@="
TOKEN = r"""(?P<num>(?:\d[\d_']*(?:\.[\d_]*)?|\.\d[\d_]*)(?:[eE][-+]?\d+)?\w*)
          | (?P<id>[A-Za-z_]\w*) | (?P<str>"+) | (?P<op>{ops}|[^\s\w"]) | (?P<ws>\s+)"""
TOKENS = {"cpp": re.compile(TOKEN.format(ops=OPS_C), re.X),
          "python": re.compile(TOKEN.format(ops=OPS_PY), re.X)}


@dataclasses.dataclass
class Token:
    type: str
    text: str
    start: int
    end: int


def tokens(blanked_line, lang):
    pattern = TOKENS["python" if lang == "python" else "cpp"]
    return [Token(m.lastgroup, m.group(), m.start(), m.end())
            for m in pattern.finditer(blanked_line) if m.lastgroup != "ws"]


# --- per-line context --------------------------------------------------------------------------

C_KEYWORDS = {"return", "if", "else", "for", "while", "do", "switch", "case", "default", "break",
              "continue", "goto", "throw", "delete", "new", "sizeof", "co_return", "co_yield",
              "using", "typedef", "static_assert", "assert", "template", "typename", "const",
              "constexpr", "static", "auto", "operator", "namespace", "struct", "class", "enum"}
PY_KEYWORDS = {"return", "raise", "yield", "import", "from", "def", "class", "if", "elif", "else",
               "for", "while", "try", "except", "finally", "with", "pass", "break", "continue",
               "global", "nonlocal", "assert", "del", "lambda", "async", "await", "print",
               "and", "or", "not", "in", "is", "None", "True", "False", "match", "case"}
SKIP_C = re.compile(r"(#|static_assert\b|assert\s*\(|template\b|using\b|namespace\b|typedef\b|"
                    r"friend\b|extern\b|throw\b|(std::)?(f|s|sn)?printf\s*\(|fmt::print\b|"
                    r"std::(cout|cerr|clog)\b|ImGui::Text|layout\s*\(|precision\b|struct\b|"
                    r"class\b|enum\b|union\b)")
SKIP_PY = re.compile(r"(import\b|from\b|assert\b|print\s*\(|raise\b|def\b|class\b|@|global\b|"
                     r"nonlocal\b|sys\.(stdout|stderr)\.write\b|log(ging|ger)?\.)")
OPENS, CLOSES = {"python": "([{", "cpp": "([", "glsl": "(["}, {"python": ")]}", "cpp": ")]",
                                                               "glsl": ")]"}


@dataclasses.dataclass
class Line:
    text: str      # the line as written
    blank: str     # comments and strings blanked
    depth: int     # open brackets at its start
    depth_end: int
    head: bool     # a statement starts on it
    skip: bool     # preprocessor, import, print, ...: nothing on it is mutated
    prev_end: str  # the last character of the previous line with code ('' at the top)


def analyse(text, lang):
    """Each line of `text` with what the operators need to know about it."""
    raw, blanked = text.split("\n"), blank(text, lang).split("\n")
    out, depth, prev_end, skipping, in_define = [], 0, "", False, False
    opens, closes = OPENS[lang], CLOSES[lang]
    for line, b in zip(raw, blanked):
        code = b.strip()
        if lang != "python" and (in_define or code.startswith("#")):
            in_define = code.endswith("\\")  # a preprocessor line: skipped, and transparent
            out.append(Line(line, b, depth, depth, False, True, prev_end))
            continue
        start = depth
        for ch in b:
            depth = max(depth + (ch in opens) - (ch in closes), 0)
        if lang == "python":
            head = start == 0 and not prev_end.endswith("\\")
            skip_head = bool(SKIP_PY.match(code))
        else:
            head = start == 0 and prev_end in ("", ";", "{", "}", ":", ")")
            skip_head = bool(SKIP_C.match(code))
        if code:
            skipping = skip_head if head else skipping
        out.append(Line(line, b, start, depth, head and bool(code), skipping or not code,
                        prev_end))
        if code:
            prev_end = code[-1]
    return out


# --- the operators -----------------------------------------------------------------------------

COMPARE = {"<": "<=", "<=": "<", ">": ">=", ">=": ">", "==": "!=", "!=": "=="}
ARITH = {"+": ("-", "sign"), "-": ("+", "sign"), "*": ("/", "swap"), "/": ("*", "swap"),
         "+=": ("-=", "sign"), "-=": ("+=", "sign"), "*=": ("/=", "swap"), "/=": ("*=", "swap")}
MINMAX = {"min": "max", "max": "min", "floor": "ceil", "ceil": "floor", "fmin": "fmax",
          "fmax": "fmin"}
UNARY_AFTER = {"(", "[", ",", "=", "==", "!=", "<", ">", "<=", ">=", "&&", "||", "!", "?", ":",
               "+", "-", "*", "/", "+=", "-=", "*=", "/=", "{", "return", "case", "and", "or",
               "not", "in", "if", "else", "elif"}
SYMMETRIC = {"min", "max", "fmin", "fmax", "dot", "distance", "equal", "notEqual", "hypot",
             "swap", "gcd", "lcm", "isinstance", "issubclass", "getattr", "hasattr", "setattr",
             "print", "get", "setdefault", "pop", "format", "join", "tie", "make_pair", "pair",
             "max_element", "min_element", "emplace", "insert", "assert", "static_assert",
             "sizeof", "alignof", "decltype", "if", "for", "while", "switch", "return", "catch",
             "elif", "and", "or", "not", "in"}
TYPES = {"int", "float", "double", "bool", "uint", "char", "void", "auto", "size_t", "vec2",
         "vec3", "vec4", "ivec2", "ivec3", "ivec4", "uvec2", "uvec3", "uvec4", "mat3", "mat4",
         "str", "list", "dict", "tuple", "set", "bytes", "object"}
ARG = r"-?(?:[A-Za-z_]\w*(?:(?:\.|->|::)[A-Za-z_]\w*)*(?:\[\w+\])?|\d[\w.]*)"
CALL = re.compile(rf"(?<![\w.>:])([A-Za-z_]\w*(?:(?:::|\.|->)[A-Za-z_]\w*)*)\(\s*({ARG})\s*,"
                  rf"\s*({ARG})\s*\)")
DROP_C = re.compile(r"(?:\+\+|--)?([A-Za-z_]\w*)(?:(?:\.|->|::)[A-Za-z_]\w*|\[[^\]]*\])*"
                    r"(?:\s*(?:=(?!=)|\+=|-=|\*=|/=|%=|&=|\|=|\^=|<<=|>>=|\+\+|--)|\()")
STEP_C = re.compile(r"(?:\+\+|--)([A-Za-z_]\w*)(?:(?:\.|->)[A-Za-z_]\w*|\[[^\]]*\])*;\Z")  # ++i;
DECLARED = re.compile(r"(?<![\w.>:])([A-Za-z_][\w:]*(?:<[^<>;()]*>)?)[&*]?\s+[&*]?([A-Za-z_]\w*)\s*"
                      r"(?=[=;,)(\[{])")
DROP_PY = re.compile(r"([A-Za-z_]\w*)((?:\.[A-Za-z_]\w*|\[[^\]]*\])*)\s*"
                     r"(=(?!=)|\+=|-=|\*=|/=|//=|%=|\|=|&=|\()")
INT = re.compile(r"(\d+)([uUlLzZ]*)\Z")
FLOAT = re.compile(r"((?:\d+\.\d*|\.\d+|\d+)(?:[eE][-+]?\d+)?)([fFlL]{0,2})\Z")


def _operand_end(t, lang):
    keywords = PY_KEYWORDS - {"None", "True", "False"} if lang == "python" else C_KEYWORDS
    return t is not None and (t.type == "num" or t.type == "id" and t.text not in keywords
                              or t.text in (")", "]"))


def _operand_start(t, lang):
    keywords = PY_KEYWORDS - {"None", "True", "False", "not"} if lang == "python" \
        else C_KEYWORDS - {"sizeof"}
    return t is not None and (t.type == "num" or t.type == "id" and t.text not in keywords
                              or t.text in ("(", "-", "!", "~", "[", "{"))


def _spaced(line, t):
    return 0 < t.start and line[t.start - 1] == " " and t.end < len(line) and line[t.end] == " "


def _float_text(value, original):
    """`value` written as a literal of the same language as `original` (e.g. 0.5f)."""
    m = FLOAT.match(original)
    text = repr(float(value))
    return text + m.group(2)


def token_edits(line, lang):
    """(start, end, replacement, operator, kind) for each token-level candidate of a line."""
    toks = tokens(line.blank, lang)
    out = []
    for i, t in enumerate(toks):
        prev = toks[i - 1] if i else None
        nxt = toks[i + 1] if i + 1 < len(toks) else None
        binary = (_spaced(line.blank, t) and _operand_end(prev, lang)
                  and _operand_start(nxt, lang))
        if t.text in COMPARE and binary:
            out.append((t.start, t.end, COMPARE[t.text], "compare", "compare"))
        elif t.text in ARITH and binary:
            out.append((t.start, t.end, ARITH[t.text][0], "arith", ARITH[t.text][1]))
        if t.text == "-" and nxt is not None and nxt.start == t.end \
                and (nxt.type in ("num", "id") or nxt.text == "(") \
                and (prev is None or prev.text in UNARY_AFTER):
            out.append((t.start, t.end, "", "negate", "sign"))
        if lang != "python":
            if t.text in ("&&", "||") and binary:
                out.append((t.start, t.end, "||" if t.text == "&&" else "&&", "logic", "logic"))
            if t.text == "!" and nxt is not None and nxt.start == t.end \
                    and _operand_start(nxt, lang):
                out.append((t.start, t.end, "", "not", "logic"))
            if t.text in ("true", "false"):
                out.append((t.start, t.end, "false" if t.text == "true" else "true", "bool",
                            "constant"))
        else:
            if t.text in ("and", "or") and binary:
                out.append((t.start, t.end, "or" if t.text == "and" else "and", "logic", "logic"))
            if t.text == "not" and nxt is not None and nxt.text != "in" \
                    and (prev is None or prev.text != "is") and _operand_start(nxt, lang):
                out.append((t.start, nxt.start, "", "not", "logic"))
            if t.text == "is" and nxt is not None:
                if nxt.text == "not":
                    out.append((t.start, nxt.end, "is", "compare", "compare"))
                else:
                    out.append((t.start, t.end, "is not", "compare", "compare"))
            if t.text in ("True", "False"):
                out.append((t.start, t.end, "False" if t.text == "True" else "True", "bool",
                            "constant"))
        template = lang != "python" and (  # std::array<float, 4>, std::get<0>
            prev is not None and prev.text == "<" and prev.end == t.start
            or nxt is not None and nxt.text in (">", ">>") and nxt.start == t.end)
        if t.type == "num" and not template:
            m, f = INT.match(t.text), FLOAT.match(t.text)
            if m and (lang != "python" or not m.group(2)) and (m.group(1) == "0"
                                                                 or m.group(1)[0] != "0"):
                n = int(m.group(1))
                out.append((t.start, t.end, f"{n + 1}{m.group(2)}", "int", "off-by-one"))
                if n > 0:
                    out.append((t.start, t.end, f"{n - 1}{m.group(2)}", "int", "off-by-one"))
            elif f and ("." in f.group(1) or "e" in f.group(1).lower()) \
                    and (lang != "python" or not f.group(2)):
                value = float(f.group(1))
                out.append((t.start, t.end, _float_text(value / 2 if value else 1.0, t.text),
                            "float", "constant"))
        if t.text in MINMAX and nxt is not None and nxt.start == t.end \
                and nxt.text in ("(", "<") and not line.blank.startswith("()", nxt.start) \
                and (prev is None or prev.text not in ("def", "int", "float", "auto")):
            out.append((t.start, t.end, MINMAX[t.text], "minmax", "swap"))
    return out


def _word_left(blanked, at):
    left = blanked[:at].rstrip()
    m = re.search(r"[A-Za-z_]\w*\Z", left)
    return m.group() if m else None


def declared_types(blanked_text):
    """{name: the type words a C++ or GLSL file declares it with} (`float x`, `const Foo& x`)."""
    types = {}
    for m in DECLARED.finditer(blanked_text):
        if m.group(1) not in C_KEYWORDS | {"else", "and", "or", "not", "co_await"}:
            types.setdefault(m.group(2), set()).add(m.group(1))
    return types


def arg_type(arg, types):
    """A C++ or GLSL argument's type, as far as a glance tells (None: unknown)."""
    if re.match(r"-?\d", arg):
        return "float" if re.search(r"[.eEfF]", arg) and not arg.startswith("0x") else \
            "uint" if arg.endswith(("u", "U")) else "int"
    if "::" in arg and "." not in arg and "->" not in arg:
        return arg.rsplit("::", 1)[0]  # Enum::Value
    name = re.split(r"\.|->", arg)[-1]  # a.b.c: c's type, if the file declares a c
    if re.fullmatch(r"[A-Za-z_]\w*", name) and len(types.get(name, ())) == 1:
        return next(iter(types[name]))
    return None


def swap_edits(line, lang, types=None):
    """f(a, b) -> f(b, a) for two simple, different arguments of a call that is no declaration,
    and (C++, GLSL) whose types, where a glance at the file tells them, are the same."""
    out = []
    for m in CALL.finditer(line.blank):
        name = re.split(r"::|\.|->", m.group(1))[-1]
        a, b = m.group(2), m.group(3)
        word = _word_left(line.blank, m.start(1))
        if name in SYMMETRIC or name.startswith("atomic") or a in TYPES or b in TYPES:
            continue
        if lang != "python" and types is not None:
            ta, tb = arg_type(a, types), arg_type(b, types)
            if ta is None or tb is None or ta != tb:
                continue
        if word is not None and word not in UNARY_AFTER | {"co_return", "yield", "await"}:
            continue  # `Type name(a, b)`: a declaration, or a constructor's
        text = line.text
        new = (text[:m.start(2)] + text[m.start(3):m.end(3)] + text[m.end(2):m.start(3)]
               + text[m.start(2):m.end(2)] + text[m.end(3):])
        out.append((m.start(2), new, "swap-args", "swap"))
    return out


def _matching(blanked, at):
    depth = 0
    for k in range(at, len(blanked)):
        depth += blanked[k] == "("
        depth -= blanked[k] == ")"
        if depth == 0:
            return k
    return None


# A function's or constructor's declaration, not a call: `= delete;`, `= default;`, `= 0;`, a
# return type before the name (`void f(int);`), or parameters written with their types
# (`Layout(uint32_t width);`). Deleting one does not build or changes nothing.
DECLARES_FUNCTION = re.compile(
    r"=\s*(?:delete|default|0)\s*;\Z"
    r"|\A(?:[\w:]+(?:<[^;()]*>)?[&*\s]+)+[~\w:]+\s*\("
    r"|\(\s*(?:const\s+)?[\w:]+(?:<[^;()]*>)?[&*\s]+[&*]*\w+\s*(?:[,)=]|\Z)")


def declares_function(code):
    call = re.match(r"\s*(?:return\b|[\w.:\[\]>-]+\s*[-+*/%&|^]?=)", code)
    return call is None and DECLARES_FUNCTION.search(code) is not None


def line_edits(line, lang, assigned):
    """(column, new line, operator, kind) for the whole-line candidates: drop and if."""
    code = line.blank.strip()
    indent = line.text[:len(line.text) - len(line.text.lstrip())]
    out = []
    if lang == "python":
        whole = line.head and line.depth == 0 and line.depth_end == 0
        m = DROP_PY.match(code)
        first = re.match(r"[A-Za-z_]\w*", code)
        if whole and m and not code.endswith(("\\", ":")) and first.group() not in PY_KEYWORDS \
                and (m.group(2) or m.group(3) != "=" or m.group(1) in assigned):
            out.append((len(indent), indent + "pass", "drop", "drop"))
        m = re.match(r"(if|elif)\s+(.+):\Z", code)
        if whole and m and m.group(2) not in ("True", "False") and ":=" not in m.group(2) \
                and "__name__" not in m.group(2):
            for value in ("True", "False"):
                out.append((len(indent), f"{indent}{m.group(1)} {value}:", "if", "logic"))
        return out
    m = DROP_C.match(code) or STEP_C.match(code)
    if line.head and line.depth == 0 and line.depth_end == 0 and m and code.endswith(";") \
            and m.group(1) not in C_KEYWORDS and line.prev_end in (";", "{", "}") \
            and "{" not in code and "}" not in code and not declares_function(code):
        out.append((len(indent), "", "drop", "drop"))
    for k in re.finditer(r"\bif\s*\(", line.blank):
        open_at = k.end() - 1
        close = _matching(line.blank, open_at)
        cond = line.blank[open_at + 1:close] if close is not None else None
        if cond is None or cond.strip() in ("true", "false") or ";" in cond \
                or re.search(r"(?<![=!<>])=(?!=)", cond):
            continue
        for value in ("true", "false"):
            new = line.text[:open_at + 1] + value + line.text[close:]
            out.append((open_at, new, "if", "logic"))
    return out


@dataclasses.dataclass(frozen=True, order=True)
class Candidate:
    file: str
    line: int      # 1-based
    col: int       # 0-based, in the line
    op: str
    mutated: str   # the whole line, mutated
    original: str  # the whole line, as written
    kind: str


def file_candidates(path, text, wanted, lang=None):
    """Every candidate on the lines `wanted` (1-based) of `text`, the file at `path`."""
    lang = lang or language(path)
    lines = analyse(text, lang)
    types = declared_types(blank(text, lang)) if lang != "python" else None
    out, assigned, offset = [], set(), 0
    for number, line in enumerate(lines, 1):
        at, offset = offset, offset + len(line.text) + 1
        if number in wanted and not line.skip and occurrence(text, line.text, at):
            edits = [(s, line.text[:s] + r + line.text[e:], op, kind)
                     for s, e, r, op, kind in token_edits(line, lang)]
            edits += swap_edits(line, lang, types) + line_edits(line, lang, assigned)
            out += [Candidate(str(path), number, col, op, new, line.text, kind)
                    for col, new, op, kind in edits if new != line.text]
        # Names bound so far (Python's drop: assigning one again declares nothing).
        m = re.match(r"\s*(?:for\s+)?([A-Za-z_]\w*)\s*(?:=(?!=)|\bin\b)", line.blank)
        if m:
            assigned.add(m.group(1))
    return sorted(set(out))


def collect(root, since, untracked=True):
    """Every candidate in the lines changed since `since`, sorted; the changed lines; and the
    texts the candidates were found in (a mutant is made from these, not from the file as it is
    later: the tree may be edited while mutants run)."""
    root = Path(root)
    changed = changed_lines(root, since, untracked)
    out, texts = [], {}
    for path in sorted(changed):
        texts[str(path)] = (root / path).read_text(errors="surrogateescape")
        out += file_candidates(path, texts[str(path)], changed[path])
    return out, changed, texts


def draw(candidates, seed):
    """Every candidate once, in the seeded draw order (the module's docstring)."""
    rng = random.Random(seed)
    by_line = {}
    for c in sorted(candidates):
        by_line.setdefault((c.file, c.line), []).append(c)
    keys = sorted(by_line)
    for key in keys:
        rng.shuffle(by_line[key])
    rng.shuffle(keys)
    order, rounds = [], max((len(v) for v in by_line.values()), default=0)
    for r in range(rounds):
        order += [by_line[key][r] for key in keys if r < len(by_line[key])]
    return order


# --- mutants in mutation_test.py's shape -------------------------------------------------------

def line_offset(text, number):
    """Offset of the start of line `number` (1-based) in `text`."""
    offset = 0
    for _ in range(number - 1):
        offset = text.index("\n", offset) + 1
    return offset


def occurrence(text, find, offset):
    """The `occurrence` that makes mutation_test.locate() find `find` at `offset`; None if no
    occurrence does."""
    count, at = 0, -1
    while True:
        at = text.find(find, at + 1)
        if at < 0 or at > offset:
            return None
        count += 1
        if at == offset:
            return count if count <= text.count(find) else None


def stable_id(c):
    """The same for a candidate whatever the seed, the line's number or its indentation."""
    stripped = c.original.lstrip()
    shift = len(c.original) - len(stripped)
    key = "\0".join([c.file, stripped, c.op, str(c.col - shift), c.mutated.strip()])
    digest = hashlib.sha1(key.encode(errors="surrogateescape")).hexdigest()[:8]
    stem = re.sub(r"[^A-Za-z0-9]+", "-", Path(c.file).stem).strip("-") or "file"
    return f"r-{stem}-{c.op}-{digest}"


def unified_diff(path, before, after):
    return "".join(difflib.unified_diff(before.splitlines(keepends=True),
                                        after.splitlines(keepends=True),
                                        f"a/{path}", f"b/{path}", n=2))


def assign_ids(candidates):
    """{candidate: stable id}; identical candidates (the same line twice in a file) numbered in
    file order: -2, -3."""
    ids, seen = {}, {}
    for c in sorted(candidates):
        mid = stable_id(c)
        seen[mid] = seen.get(mid, 0) + 1
        ids[c] = mid if seen[mid] == 1 else f"{mid}-{seen[mid]}"
    return ids


def mutant(c, text, mid, labels):
    """The mutation_test.py entry for candidate `c`, of the file whose text is `text`."""
    offset = line_offset(text, c.line)
    after = text[:offset] + c.mutated + text[offset + len(c.original):]
    what = {"drop": "statement deleted", "if": "condition fixed"}.get(c.op, c.op)
    return {"id": mid, "kind": c.kind, "labels": list(labels), "op": c.op,
            "why": f"random: {what} at {c.file}:{c.line}", "line": c.line, "list": "random",
            "files": c.file, "diff": unified_diff(c.file, text, after),
            "edits": [{"file": c.file, "find": c.original, "replace": c.mutated,
                       "occurrence": occurrence(text, c.original, offset)}]}


# --- which tests see a file ---------------------------------------------------------------------

def glob_regex(pattern):
    """`**` any path (`dir/**/x`: none too), `*` and `?` within a folder."""
    out, i = "", 0
    while i < len(pattern):
        if pattern.startswith("**/", i):
            out, i = out + "(?:.*/)?", i + 3
        elif pattern.startswith("**", i):
            out, i = out + ".*", i + 2
        elif pattern[i] == "*":
            out, i = out + "[^/]*", i + 1
        elif pattern[i] == "?":
            out, i = out + "[^/]", i + 1
        else:
            out, i = out + re.escape(pattern[i]), i + 1
    return re.compile(out + r"\Z")


def load_coverage(path):
    """(every label, [(pattern, labels)]) from tests/mutations/coverage.toml."""
    with open(path, "rb") as f:
        data = tomllib.load(f)
    return list(data["all"]), [(p, list(labels)) for p, labels in data["files"].items()]


def labels_for(path, rules, all_labels):
    """The labels of the most specific pattern matching `path` (most characters other than
    wildcards; the first written of equals); every label if none matches."""
    best, score = None, -1
    for pattern, labels in rules:
        literal = len(pattern) - pattern.count("*") - pattern.count("?")
        if literal > score and glob_regex(pattern).match(str(path)):
            best, score = labels, literal
    return list(all_labels) if best is None else best


def load_equivalent(path):
    """{id: reason} from tests/mutations/equivalent_random.toml."""
    if not Path(path).is_file():
        return {}
    with open(path, "rb") as f:
        data = tomllib.load(f)
    entries = data.get("equivalent", [])
    if not isinstance(entries, list):
        raise ValueError(f"{path}: write each entry as [[equivalent]]")
    out = {}
    for k, e in enumerate(entries):
        if not isinstance(e, dict) or not e.get("id") or not e.get("reason"):
            raise ValueError(f"{path}: entry {k + 1} needs an id and a reason")
        if e["id"] in out:
            raise ValueError(f"{path}: '{e['id']}' is listed twice")
        out[e["id"]] = e["reason"]
    return out


class Mutants:
    """The candidates of the lines changed since `since` in the seeded draw order, made into
    mutation_test.py entries on demand (a diff each)."""

    def __init__(self, root, since, seed, coverage_path, untracked=True):
        self.root, self.since, self.seed = Path(root), since, seed
        commit = verified_revision(root, since)
        self.candidates, self.changed, self._texts = collect(root, commit, untracked)
        self.base = commit[:7]
        self.ids = assign_ids(self.candidates)
        self.order = draw(self.candidates, seed)
        self.all_labels, self.rules = load_coverage(coverage_path)

    def mutant(self, c):
        return mutant(c, self._texts[c.file], self.ids[c],
                      labels_for(c.file, self.rules, self.all_labels))

    def __iter__(self):
        """Every mutant in the draw order: the first N are the sample, the rest replacements."""
        return (self.mutant(c) for c in self.order)

    def select(self, n, only="", label=""):
        """(mutants in order, how many to count): the draw's first n, or the ids of `only`
        (comma-separated; ValueError for one no candidate has); `label`: those it names."""
        source = iter(self)
        if only:
            wanted = {i for i in only.split(",") if i}
            unknown = wanted - set(self.ids.values())
            if unknown:
                raise ValueError(f"--only: unknown mutant ids {sorted(unknown)}")
            source = (self.mutant(c) for c in sorted(self.candidates) if self.ids[c] in wanted)
            n = len(wanted)
        if label:
            if label not in self.all_labels:
                raise ValueError(f"--label: no label '{label}' (one of {', '.join(self.all_labels)})")
            source = (m for m in source if label in m["labels"])
        return source, n

    def labels(self):
        """Every label that sees a changed file."""
        return sorted({label for path in self.changed
                       for label in labels_for(path, self.rules, self.all_labels)})

    def summary(self):
        lines = sum(len(v) for v in self.changed.values())
        return (f"random mutants since {self.since} ({self.base}), seed {self.seed}: "
                f"{len(self.candidates)} candidates on {lines} changed lines in "
                f"{len(self.changed)} files")

    def write_report(self, path, results, requested, rest):
        """The Markdown report at `path` and its JSON beside it; returns the kills."""
        info = {"since": self.since, "base": self.base, "seed": self.seed,
                "requested": requested, "candidates": len(self.candidates),
                "lines": sum(len(v) for v in self.changed.values()), "rest": rest}
        path = Path(path)
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(report_markdown(info, results))
        path.with_suffix(".json").write_text(json.dumps({**info, "mutants": results},
                                                        indent=1) + "\n")
        return sum(r["status"] == "killed" for r in results)


def first(source, n, equivalent):
    """The mutants of `source` up to the n-th not in `equivalent` (those with it)."""
    out, counted = [], 0
    for m in source:
        if counted == n:
            break
        out.append(m)
        counted += m["id"] not in equivalent
    return out


def listing(m, equivalent):
    note = f" (equivalent: {equivalent[m['id']]})" if m["id"] in equivalent else ""
    return (f"{m['id']:44} {m['kind']:10} {','.join(m['labels']):22} {m['files']}:{m['line']}"
            f"{note}\n    " + m["diff"].rstrip("\n").replace("\n", "\n    "))


# --- the report ---------------------------------------------------------------------------------

def report_markdown(info, results):
    """The Markdown report: the kill rate, each mutant's outcome, every survivor's diff."""
    counted = [r for r in results if r["status"] in ("killed", "survived")]
    killed = sum(r["status"] == "killed" for r in counted)
    rate = 100.0 * killed / len(counted) if counted else 0.0
    lines = ["# Random mutants", "",
             f"- since `{info['since']}` ({info['base']}), seed {info['seed']}, "
             f"{info['requested']} requested, drawn from {info['candidates']} candidates on "
             f"{info['lines']} changed lines",
             f"- **killed {killed} of {len(counted)} ({rate:.1f}%)**; "
             f"{sum(r['status'] == 'invalid' for r in results)} invalid (do not build), "
             f"{sum(r['status'] == 'equivalent' for r in results)} equivalent (not counted)",
             "", "| mutant | kind | where | outcome | s |", "| --- | --- | --- | --- | --- |"]
    for r in results:
        lines.append(f"| `{r['id']}` | {r['kind']} | {r['files']}:{r['line']} | {r['outcome']} "
                     f"| {r.get('seconds', 0):.0f} |")
    for title, status in (("Survivors", "survived"), ("Equivalent", "equivalent")):
        chosen = [r for r in results if r["status"] == status]
        if chosen:
            lines += ["", f"## {title}", ""]
        for r in chosen:
            lines += [f"### `{r['id']}` ({r['kind']}, labels {', '.join(r['labels'])})", "",
                      r["outcome"] if status == "equivalent" else r["why"], "", "```diff",
                      r["diff"].rstrip("\n"), "```", ""]
    return "\n".join(lines) + "\n"
