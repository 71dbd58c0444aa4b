"""tools/random_mutants.py, the generator of `make mutation-test RANDOM=N`, and the parts of
tools/mutation_test.py it plugs into: the operators (exact replacements), what is never mutated,
the changed-lines parsing, the seeded draw, the coverage map, ids, occurrences and the report.
Pure Python: no build, no GPU (ctest label "tools")."""
import json
import re
import random
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "tools"))

import mutation_test  # noqa: E402
import random_mutants as rm  # noqa: E402


def edits(text, path="src/x.cpp", wanted=None):
    """{(line, operator, mutated line)} of every candidate on the lines `wanted` (all)."""
    count = len(text.split("\n"))
    return {(c.line, c.op, c.mutated)
            for c in rm.file_candidates(path, text, wanted or set(range(1, count + 1)))}


# --- the operators, C++ --------------------------------------------------------------------------

def test_compare_if_and_integers():
    assert edits("int f() {\n    if (a < b) x = 1;\n}") == {
        (2, "if", "    if (true) x = 1;"), (2, "if", "    if (false) x = 1;"),
        (2, "compare", "    if (a <= b) x = 1;"),
        (2, "int", "    if (a < b) x = 2;"), (2, "int", "    if (a < b) x = 0;")}


@pytest.mark.parametrize("op, to", [("<", "<="), ("<=", "<"), (">", ">="), (">=", ">"),
                                    ("==", "!="), ("!=", "==")])
def test_each_comparison_to_its_neighbour(op, to):
    assert edits(f"{{\n    ok = a {op} b;\n}}") == {(2, "drop", ""),
                                                  (2, "compare", f"    ok = a {to} b;")}


def test_arithmetic_logic_not_and_drop():
    text = "void g() {\n    y = a + b * c;\n    ok = !done && n >= 0;\n}"
    assert edits(text) == {
        (2, "drop", ""), (2, "arith", "    y = a - b * c;"), (2, "arith", "    y = a + b / c;"),
        (3, "drop", ""), (3, "not", "    ok = done && n >= 0;"),
        (3, "logic", "    ok = !done || n >= 0;"), (3, "compare", "    ok = !done && n > 0;"),
        (3, "int", "    ok = !done && n >= 1;")}


def test_division_or_and_compound_assignments():
    text = "{\n    y = a / b || c;\n    i += 2;\n    j -= k;\n    m *= 3.0f;\n    q /= r;\n}"
    assert edits(text) == {
        (2, "drop", ""), (2, "arith", "    y = a * b || c;"), (2, "logic", "    y = a / b && c;"),
        (3, "drop", ""), (3, "arith", "    i -= 2;"), (3, "int", "    i += 3;"),
        (3, "int", "    i += 1;"), (4, "drop", ""), (4, "arith", "    j += k;"),
        (5, "drop", ""), (5, "arith", "    m /= 3.0f;"), (5, "float", "    m *= 1.5f;"),
        (6, "drop", ""), (6, "arith", "    q *= r;")}


def test_floats_halved_zero_to_one_and_unary_minus():
    text = "{\n    float f = 0.5f * x - 1.0 + 0.0;\n    return -d;\n}"
    assert edits(text) == {
        (2, "float", "    float f = 0.25f * x - 1.0 + 0.0;"),
        (2, "float", "    float f = 0.5f * x - 0.5 + 0.0;"),
        (2, "float", "    float f = 0.5f * x - 1.0 + 1.0;"),
        (2, "arith", "    float f = 0.5f / x - 1.0 + 0.0;"),
        (2, "arith", "    float f = 0.5f * x + 1.0 + 0.0;"),
        (2, "arith", "    float f = 0.5f * x - 1.0 - 0.0;"),
        (3, "negate", "    return d;")}


def test_exponent_literals_and_unsigned_zero():
    assert edits("{\n    t = 1e-4f;\n    u = 0u;\n}") == {
        (2, "drop", ""), (2, "float", "    t = 5e-05f;"),
        (3, "drop", ""), (3, "int", "    u = 1u;")}


def test_min_max_bool_and_symmetric_calls_kept():
    text = "{\n    v = std::min(a, b);\n    ok = true;\n    w = std::floor(x);\n}"
    assert edits(text) == {
        (2, "drop", ""), (2, "minmax", "    v = std::max(a, b);"),
        (3, "drop", ""), (3, "bool", "    ok = false;"),
        (4, "drop", ""), (4, "minmax", "    w = std::ceil(x);")}


def test_limits_max_is_not_swapped():
    assert edits("{\n    m = std::numeric_limits<float>::max();\n}") == {(2, "drop", "")}


def test_arguments_swapped_only_when_their_types_agree():
    text = "float x;\nfloat y;\nint n;\nvoid h() {\n    w = pow(x, y);\n    w = pow(x, n);\n}"
    assert edits(text, wanted={5, 6}) == {
        (5, "drop", ""), (5, "swap-args", "    w = pow(y, x);"), (6, "drop", "")}


def test_a_return_is_no_declaration_and_symmetric_calls_stay():
    text = ("uint32_t width;\nuint32_t height;\nfloat a;\nfloat b;\nuint32_t f() {\n"
            "    return width;\n}\nvoid g() {\n    h(width, height);\n    v = std::max(a, b);\n}")
    assert edits(text, wanted={9, 10}) == {
        (9, "drop", ""), (9, "swap-args", "    h(height, width);"),
        (10, "drop", ""), (10, "minmax", "    v = std::min(a, b);")}
    swap = next(c for c in rm.file_candidates("src/x.cpp", text, {9}) if c.op == "swap-args")
    assert swap.col == 6  # the first argument


def test_python_type_arguments_are_not_swapped():
    assert edits("y = 0\ny = cast(int, x)\ny = cast(x, str)\n", "tools/t.py", wanted={2, 3}) == {
        (2, "drop", "pass"), (3, "drop", "pass")}


def test_arguments_of_a_declaration_are_not_swapped():
    text = "float a;\nfloat b;\nvoid h() {\n    Foo foo(a, b);\n}"
    assert edits(text, wanted={4}) == set()


def test_argument_types_of_literals_enums_and_members():
    types = rm.declared_types("struct S { uint32_t width; uint32_t height; };\nfloat f;\n"
                              "const Foo& r = g();\nint f;\n")
    assert types["width"] == {"uint32_t"} and types["r"] == {"Foo"}
    assert types["f"] == {"float", "int"}
    assert rm.arg_type("s.sizes.width", types) == "uint32_t"
    assert rm.arg_type("f", types) is None  # two types: unknown
    assert rm.arg_type("Access::Read", types) == "Access"
    assert rm.arg_type("gpu::Access::Read", types) == "gpu::Access"
    assert [rm.arg_type(a, {}) for a in ("1.0f", "2u", "3", "-1", "0x10")] == [
        "float", "uint", "int", "int", "int"]
    assert rm.arg_type("unknown", types) is None


def test_statement_after_a_braceless_control_line_is_not_dropped():
    text = "{\n    for (i = 0; i < n; i++)\n        x = p->y;\n}"
    assert (3, "drop", "") not in edits(text)
    assert edits("{\n    a = 1;\n    x = p->y;\n}", wanted={3}) == {(3, "drop", "")}


def test_declarations_returns_and_calls_with_a_space_are_not_dropped():
    text = ("{\n    const int k = f(x);\n    return g(x);\n    break;\n    Checkerboard "
            "(*fp)(int) = nullptr;\n    delete p;\n}")
    assert {e for e in edits(text) if e[1] == "drop"} == set()


def test_preprocessor_lines_are_transparent():
    text = "{\n    a = 1;\n#ifdef X\n    b = 2;\n#endif\n    c = 3;\n}"
    assert {e for e in edits(text) if e[1] == "drop"} == {(2, "drop", ""), (4, "drop", ""),
                                                          (6, "drop", "")}


def test_continuation_lines_are_not_statements():
    text = "{\n    const int k =\n        f(x);\n    x = a *\n        -b;\n}"
    assert edits(text, wanted={3, 5}) == {(5, "negate", "        b;")}
    py = "x = 1 + \\\n    y(z)\nq = (a and\n     not b)\n"
    assert edits(py, "tools/t.py", wanted={2, 4}) == {(4, "not", "     b)")}


def test_a_lambda_inside_a_skipped_statement_is_skipped():
    text = ('{\n    throw Error(fmt::format("{}",\n    [&] {\n        return a + 1;\n    }()));\n'
            "    y = a +\n        min(b, c);\n}")
    assert edits(text, wanted={4, 7}) == {(7, "minmax", "        max(b, c);")}


def test_numbers_after_a_spaced_comparison_are_not_template_arguments():
    assert edits("{\n    ok = n < 4;\n}") == {
        (2, "drop", ""), (2, "compare", "    ok = n <= 4;"), (2, "int", "    ok = n < 5;"),
        (2, "int", "    ok = n < 3;")}


def test_keyword_call_statements_are_not_dropped():
    assert {e for e in edits("{\n    a = 1;\n    return(x);\n}") if e[1] == "drop"} == {
        (2, "drop", "")}


def test_compound_assignment_of_a_string_is_kept():
    assert edits('s = ""\ns += "x"\n', "tools/t.py", wanted={2}) == {(2, "drop", "pass")}


def test_if_conditions_that_declare_or_span_lines_are_kept():
    text = ("{\n    if (auto p = f(); p) g();\n    if (x = y) g();\n    if (a &&\n        b) g();\n"
            "    if constexpr (A) g();\n}")
    assert {e for e in edits(text) if e[1] == "if"} == set()


def test_glsl_operators():
    text = "void main() {\n    c = max(c, 0.0);\n    uint n = 4u;\n    barrier();\n}"
    assert edits(text, "shaders/x.comp") == {
        (2, "drop", ""), (2, "minmax", "    c = min(c, 0.0);"),
        (2, "float", "    c = max(c, 1.0);"),
        (3, "int", "    uint n = 3u;"), (3, "int", "    uint n = 5u;"), (4, "drop", "")}


def test_glsl_layout_and_version_lines_are_kept():
    text = ("#version 460\nlayout(local_size_x = 8, binding = 2) in;\n"
            "layout(binding = 1) uniform U {")
    assert edits(text, "shaders/x.comp") == set()


# --- what is never mutated -----------------------------------------------------------------------

NEVER_CPP = r'''{
    char c = '+';
    auto r = R"(a + b < c)";
    auto u = u8"a - b";
    /* a + b
       c < d */
#include <vector>
#define X (a + 1) \
    + 2
    std::vector<int> v = f<float>(x);
    std::array<float, 4> a{};
    auto g = std::get<0>(t);
    out << x << "\n";
    Foo* p = &x;
    Foo&& q = std::move(y);
    static_assert(sizeof(X) == 4);
    assert(n < 3);
    std::fprintf(stderr, "%d\n", n + 1);
    std::printf("%d\n",
                n + 1);
    fmt::print("{}", n - 1);
    throw std::runtime_error("x" + std::to_string(n + 1));
template <typename T, int N = 3>
using Alias = Foo<T, 2>;
    ++i;
    --j;
    x = p->y;
}'''


def test_strings_comments_includes_templates_streams_and_logs_are_never_mutated():
    assert edits(NEVER_CPP) == {(25, "drop", ""), (26, "drop", ""), (27, "drop", "")}


def test_strings_and_comments_around_code():
    text = '{\n    s = "a < b + 1 && c";\n    x = y; // a < b + 1\n    z = s + "!";\n}'
    assert edits(text) == {(2, "drop", ""), (3, "drop", ""), (4, "drop", "")}


def test_digit_separators_are_code_not_char_literals():
    text = "{\n    if (n < 10'000) x = 2;\n}"
    assert (2, "int", "    if (n < 10'000) x = 3;") in edits(text)
    assert (2, "compare", "    if (n <= 10'000) x = 2;") in edits(text)


def test_blank_keeps_columns_and_lines():
    text = 'a = "x + y"; // c < d\n/* e\n f */ g = \'h\';'
    assert rm.blank(text, "cpp") == 'a = """"""";         \n    \n      g = """;'
    py = 'a = f"{b + 1}"  # c\nd = """e\nf""" + r\'\\\'\''
    assert rm.blank(py, "python") == 'a = """"""""""     \nd = """"\n"""" + """""'
    assert len(rm.blank(NEVER_CPP, "cpp")) == len(NEVER_CPP)


@pytest.mark.parametrize("text, lang, blanked", [
    ('r"a" + x', "python", '"""" + x'),              # a prefix at the very start
    ('my_r"x" + y', "python", 'my_r""" + y'),        # a prefix is a whole word
    ('a_u8"x" + y', "cpp", 'a_u8""" + y'),
    ('x = "abc', "cpp", 'x = """"'),                 # unterminated at the end
    ('s = "a\\"b" + c', "cpp", 's = """""" + c'),     # an escaped quote
    ("x = 'a\ny = b + c", "python", 'x = ""\ny = b + c'),  # a newline ends a short string
    ('"a" + b', "cpp", '""" + b'),                   # a string at the very start
    ("# c\nx", "python", "   \nx"),
    ("x; // c", "cpp", "x;     "),                   # a comment at the end, no newline
    ("x  # c", "python", "x     "),
    ("/*/ a + b */ c", "cpp", "             c"),     # `/*/` does not close
    ("/**/x + y", "cpp", "    x + y"),
    ("x /* a + b", "cpp", "x         "),             # unterminated
    ('a = "" + b', "python", 'a = "" + b'),          # empty, not a triple quote
    ("k = 0x1'0000 + 'c'", "cpp", "k = 0x1'0000 + \"\"\""),  # digit separators in hex
    ('s = "x(" + y + ")";\nz = a + b;', "cpp", 's = """" + y + """;\nz = a + b;'),  # not raw
    ('s = u8"x(" + y;\nz = a + b;', "cpp", 's = """""" + y;\nz = a + b;'),
    ('R"(a " + b)" + c', "cpp", '"""""""""""" + c'),  # a raw string holds a quote
    ('R"xy(a)" b)xy" + c', "cpp", '"""""""""""""" + c'),  # and a delimiter
    ('R"xy(a + b', "cpp", '""""""""""')])
def test_blank_edge_cases(text, lang, blanked):
    assert rm.blank(text, lang) == blanked


def test_tokens_take_the_longest_operator():
    assert [t.text for t in rm.tokens("a<<=b->c<=>d>>e", "cpp")] == [
        "a", "<<=", "b", "->", "c", "<=>", "d", ">>", "e"]
    assert [t.text for t in rm.tokens("a//b**c!=1.5e-3f", "python")] == [
        "a", "//", "b", "**", "c", "!=", "1.5e-3f"]


NEVER_PY = '''import os
from x import y
"""Doc a + b < c."""
total = 0


def f(a, b=1):
    # a + b
    print(f"{a + 1}")
    print("a",
          a + 1)
    raise ValueError(a + 1)
    assert a < b
    s = "a + b" + y
    args = f(*a, **b)
    log.info("%d", a - 1)
'''


def test_python_never_mutated():
    assert edits(NEVER_PY, "tools/t.py") == {(4, "int", "total = 1")}


# --- the operators, Python -----------------------------------------------------------------------

def test_python_operators():
    text = '''total = 0
x = 1
def f():
    if a < b and not c:
        total += n - 1
    x = y is None
    first = y is not None
    self.v = -w
    return True
    k = min(a, b)
    z = pow(a, b)
    flag = 0.5
    elif_ = a or b
'''
    assert edits(text, "tools/t.py", wanted=set(range(4, 14))) == {
        (4, "if", "    if True:"), (4, "if", "    if False:"),
        (4, "compare", "    if a <= b and not c:"), (4, "logic", "    if a < b or not c:"),
        (4, "not", "    if a < b and c:"),
        (5, "drop", "        pass"), (5, "arith", "        total -= n - 1"),
        (5, "arith", "        total += n + 1"), (5, "int", "        total += n - 0"),
        (5, "int", "        total += n - 2"),
        (6, "drop", "    pass"), (6, "compare", "    x = y is not None"),
        (7, "compare", "    first = y is None"),
        (8, "drop", "    pass"), (8, "negate", "    self.v = w"),
        (9, "bool", "    return False"),
        (10, "minmax", "    k = max(a, b)"),
        (11, "swap-args", "    z = pow(b, a)"),
        (12, "float", "    flag = 0.25"),
        (13, "logic", "    elif_ = a and b")}


def test_python_elif_call_statements_and_continuations():
    text = "x = 0\nif a:\n    go(x)\nelif b == 2:\n    x = [1,\n         2]\n"
    assert edits(text, "tools/t.py", wanted={3, 4, 5, 6}) == {
        (3, "drop", "    pass"), (4, "if", "elif True:"), (4, "if", "elif False:"),
        (4, "compare", "elif b != 2:"), (4, "int", "elif b == 3:"), (4, "int", "elif b == 1:"),
        (5, "int", "    x = [2,"), (5, "int", "    x = [0,"),
        (6, "int", "         3]"), (6, "int", "         1]")}


def test_a_constant_condition_is_left_to_the_bool_operator():
    assert edits("{\n    if (true) x = 1;\n}") == {
        (2, "bool", "    if (false) x = 1;"), (2, "int", "    if (true) x = 2;"),
        (2, "int", "    if (true) x = 0;")}
    assert edits("if True:\n    pass\n", "tools/t.py") == {(1, "bool", "if False:")}
    assert edits("h(a, a)\n", "tools/t.py") == {(1, "drop", "pass")}  # the same line


def test_python_ifs_that_bind_or_guard_main_are_kept():
    text = 'if (n := f()) > 0:\n    pass\nif __name__ == "__main__":\n    pass\n'
    assert {e for e in edits(text, "tools/t.py") if e[1] == "if"} == set()


def test_language_of_a_path():
    assert [rm.language(p) for p in (
        "src/a.cpp", "src/a.h", "include/p/a.h", "apps/v/a.cpp", "shaders/a.comp",
        "shaders/include/a.h", "shaders/include/a.glsl", "tools/a.py", "python/m.cpp",
        "tests/a.cpp", "docs/a.md", "bench/plans/a.toml", "src/CMakeLists.txt", "shaders/a.txt",
        "python/penumbra.pyi", "srcx/a.cpp")] == [
        "cpp", "cpp", "cpp", "cpp", "glsl", "glsl", "glsl", "python", "cpp",
        None, None, None, None, None, None, None]


# --- changed lines -------------------------------------------------------------------------------

DIFF = """diff --git a/src/a.cpp b/src/a.cpp
index 1..2 100644
--- a/src/a.cpp
+++ b/src/a.cpp
@@ -10 +10 @@ void f() {
-    x = 1;
+    x = 2;
@@ -20,0 +21,2 @@ void g() {
+    y = 1;
+    z = 2;
@@ -30,2 +32,0 @@ void h() {
-    gone();
-    gone();
@@ -40,3 +40,1 @@
-a
-b
+c
diff --git a/tools/new.py b/tools/new.py
new file mode 100644
--- /dev/null
+++ b/tools/new.py
@@ -0,0 +1,3 @@
+a = 1
+b = 2
+c = 3
diff --git a/src/old.cpp b/src/old.cpp
deleted file mode 100644
--- a/src/old.cpp
+++ /dev/null
@@ -1,2 +0,0 @@
-x
-y
"""


def test_parse_diff_hunks_with_counts_omitted_zero_and_many():
    assert rm.parse_diff(DIFF) == {"src/a.cpp": {10, 21, 22, 40}, "tools/new.py": {1, 2, 3}}


def test_parse_diff_ignores_lines_that_are_not_hunks():
    text = "--- a/src/a.cpp\n+++ b/src/a.cpp\n@@@ -1,2 -1,2 +1,3 @@@\n@@ -3 +3 @@\n+x\n"
    assert rm.parse_diff(text) == {"src/a.cpp": {3}}


def test_parse_diff_of_a_pure_deletion_is_empty():
    assert rm.parse_diff("--- a/src/a.cpp\n+++ b/src/a.cpp\n@@ -5,2 +4,0 @@\n-a\n-b\n") == {}


def git(repo, *args):
    return subprocess.run(["git", "-c", "user.name=t", "-c", "user.email=t@t", "-c",
                           "commit.gpgsign=false", *args],
                          cwd=repo, check=True, capture_output=True, text=True).stdout


BASE_CPP = "int f(int a, int b) {\n    int x = 0;\n    return x;\n}\n"
NEW_CPP = ("int f(int a, int b) {\n    int x = 0;\n    if (a < b) x = a + 1;\n    x = x * 2;\n"
           "    return x;\n}\n")


@pytest.fixture
def repo(tmp_path):
    """A git repository with one commit, then changes: a modified C++ file, a new Python file
    (untracked), an ignored file, a test and a doc (never mutated)."""
    git(tmp_path, "init", "-q")
    (tmp_path / "src").mkdir()
    (tmp_path / "src" / "a.cpp").write_text(BASE_CPP)
    (tmp_path / ".gitignore").write_text("build/\n")
    git(tmp_path, "add", ".")
    git(tmp_path, "commit", "-q", "-m", "base")
    (tmp_path / "src" / "a.cpp").write_text(NEW_CPP)
    (tmp_path / "tools").mkdir()
    (tmp_path / "tools" / "t.py").write_text("n = 0\nif n > 1:\n    n = n - 1\n")
    (tmp_path / "build").mkdir()
    (tmp_path / "build" / "b.cpp").write_text("int g() { return 1 + 2; }\n")
    (tmp_path / "tests").mkdir()
    (tmp_path / "tests" / "t.cpp").write_text("int h() { return 1 + 2; }\n")
    (tmp_path / "docs").mkdir()
    (tmp_path / "docs" / "d.py").write_text("x = 1 + 2\n")
    (tmp_path / "tests" / "mutations").mkdir()
    (tmp_path / "tests" / "mutations" / "coverage.toml").write_text(
        'all = ["unit", "cli", "tools"]\n[files]\n"src/**" = ["unit"]\n')
    return tmp_path


def test_changed_lines_of_the_working_tree_and_untracked_files(repo):
    assert rm.changed_lines(repo, "HEAD") == {"src/a.cpp": {3, 4}, "tools/t.py": {1, 2, 3}}
    assert rm.changed_lines(repo, "HEAD", untracked=False) == {"src/a.cpp": {3, 4}}


def test_a_revision_git_does_not_know_is_an_error(repo):
    with pytest.raises(subprocess.CalledProcessError):
        rm.changed_lines(repo, "no-such-revision")


def test_the_same_seed_draws_the_same_mutants(repo):
    path = repo / "tests" / "mutations" / "coverage.toml"
    first = [m["id"] for m in rm.Mutants(repo, "HEAD", 1, path)]
    assert first == [m["id"] for m in rm.Mutants(repo, "HEAD", 1, path)]
    assert len(first) == len(set(first)) == 20
    others = [[m["id"] for m in rm.Mutants(repo, "HEAD", seed, path)] for seed in (2, 3, 4)]
    assert all(sorted(o) == sorted(first) for o in others)
    assert any(o != first for o in others)


def test_mutants_know_their_labels_and_the_base(repo):
    path = repo / "tests" / "mutations" / "coverage.toml"
    mutants = rm.Mutants(repo, "HEAD", 1, path)
    assert mutants.base == git(repo, "rev-parse", "--short", "HEAD").strip()
    assert mutants.labels() == ["cli", "tools", "unit"]
    by_file = {m["files"]: m["labels"] for m in mutants}
    assert by_file == {"src/a.cpp": ["unit"], "tools/t.py": ["unit", "cli", "tools"]}
    assert "seed 1: 20 candidates on 5 changed lines in 2 files" in mutants.summary()


def test_mutants_are_made_from_the_text_they_were_drawn_from(repo):
    # The tree is edited while mutants run for hours: a line moved by a later edit must not
    # turn a drawn mutant into another line's (or a comment's) edit.
    path = repo / "tests" / "mutations" / "coverage.toml"
    before = [m["diff"] for m in rm.Mutants(repo, "HEAD", 1, path)]
    mutants = iter(rm.Mutants(repo, "HEAD", 1, path))
    first = next(mutants)
    (repo / "src" / "a.cpp").write_text("// a comment that moves every line\n" + NEW_CPP)
    assert [first["diff"]] + [m["diff"] for m in mutants] == before


def test_select_by_id_and_label(repo):
    mutants = rm.Mutants(repo, "HEAD", 1, repo / "tests" / "mutations" / "coverage.toml")
    ids = [m["id"] for m in mutants]
    source, n = mutants.select(5, only=f"{ids[3]},{ids[0]}")
    assert n == 2 and sorted(m["id"] for m in source) == sorted([ids[0], ids[3]])
    with pytest.raises(ValueError):
        mutants.select(5, only="r-nothing")
    source, n = mutants.select(4, label="tools")
    chosen = list(source)
    assert n == 4 and chosen and all(m["files"] == "tools/t.py" for m in chosen)
    source, n = mutants.select(4)
    assert n == 4 and [m["id"] for m in source] == ids


def test_draw_takes_every_line_once_before_any_line_twice():
    cands = [rm.Candidate("src/a.cpp", line, col, "int", f"m{col}", "o", "off-by-one")
             for line in range(1, 11) for col in range(line % 3 + 1)]
    for seed in range(5):
        order = rm.draw(cands, seed)
        assert sorted(order) == sorted(cands)
        assert sorted(c.line for c in order[:10]) == list(range(1, 11))
        assert order == rm.draw(list(reversed(cands)), seed)
    assert rm.draw(cands, 1) != rm.draw(cands, 2)
    assert rm.draw([], 1) == []


def test_draw_shuffles_each_lines_candidates():
    cands = [rm.Candidate("f", 1, col, "int", f"m{col}", "o", "off-by-one") for col in range(6)]
    orders = {tuple(c.col for c in rm.draw(cands, seed)) for seed in range(4)}
    assert len(orders) > 1 and all(sorted(o) == list(range(6)) for o in orders)


def test_draw_is_python_random_seeded():
    cands = [rm.Candidate("f", n, 0, "int", "m", "o", "off-by-one") for n in range(1, 6)]
    lines = list(range(1, 6))
    random.Random(9).shuffle(lines)
    assert [c.line for c in rm.draw(cands, 9)] == lines


# --- coverage map --------------------------------------------------------------------------------

RULES = [("src/**", ["a"]), ("src/ab", ["ab"]), ("src/sweep/**", ["sweep", "cli"]),
         ("src/sweep/plan.cpp", ["plan"]),
         ("shaders/**", ["gpu"]), ("shaders/include/*.h", ["shared"]), ("tools/x?.py", ["x"]),
         ("src/**/a.cpp", ["deep"])]


@pytest.mark.parametrize("path, labels", [
    ("src/core/io.cpp", ["a"]), ("src/sweep/tasks.cpp", ["sweep", "cli"]),
    ("src/sweep/plan.cpp", ["plan"]), ("src/sweep/deep/more.cpp", ["sweep", "cli"]),
    ("shaders/include/bias.h", ["shared"]), ("shaders/include/sub/bias.h", ["gpu"]),
    ("shaders/include/bias.glsl", ["gpu"]), ("tools/x1.py", ["x"]), ("src/a.cpp", ["deep"]),
    ("src/q/r/a.cpp", ["deep"]), ("tools/x12.py", ["all", "labels"]), ("src/ab", ["ab"]),
    ("apps/a.cpp", ["all", "labels"])])
def test_the_most_specific_pattern_wins(path, labels):
    assert rm.labels_for(path, RULES, ["all", "labels"]) == labels


def test_glob_regex():
    assert rm.glob_regex("src/*.cpp").match("src/a.cpp")
    assert not rm.glob_regex("src/*.cpp").match("src/acpp")
    assert not rm.glob_regex("src/*.cpp").match("src/a/b.cpp")
    assert rm.glob_regex("src/**.cpp").match("src/a/b.cpp")
    assert not rm.glob_regex("src/**.cpp").match("src/a/bcpp")
    assert rm.glob_regex("a/**/b").match("a/b") and rm.glob_regex("a/**/b").match("a/x/y/b")
    assert not rm.glob_regex("a/?").match("a/bc") and not rm.glob_regex("a.b").match("axb")
    assert rm.labels_for("x/y", [("**", ["everything"])], ["all"]) == ["everything"]


def test_equal_patterns_the_first_written_wins():
    assert rm.labels_for("src/a.cpp", [("src/*", ["one"]), ("src/?.cpp", ["two"])], []) == ["two"]
    assert rm.labels_for("src/a.cpp", [("src/*.cpp", ["one"]), ("src/?.cpp", ["two"])],
                         []) == ["one"]


def cmake_labels():
    text = (ROOT / "tests" / "CMakeLists.txt").read_text()
    import re
    labels = set(re.findall(r"LABELS \"?([\w;]+)", text))
    labels = {part for group in labels for part in group.split(";")}
    areas = re.findall(r"^    ([a-z]+) \"[^\"]*\"\)?$", text, re.M)
    return labels | set(areas) | {"unsorted"}


def test_the_coverage_map_names_only_labels_that_exist():
    all_labels, rules = rm.load_coverage(ROOT / "tests" / "mutations" / "coverage.toml")
    assert set(all_labels) == cmake_labels()
    for pattern, labels in rules:
        assert labels and set(labels) <= set(all_labels), pattern
        if "*" not in pattern and "?" not in pattern:
            assert (ROOT / pattern).is_file(), f"{pattern}: no such file"


def test_the_coverage_map_sends_the_tools_to_their_tests():
    all_labels, rules = rm.load_coverage(ROOT / "tests" / "mutations" / "coverage.toml")
    assert rm.labels_for("tools/random_mutants.py", rules, all_labels) == ["tools"]
    assert rm.labels_for("src/sweep/new.cpp", rules, all_labels) == ["sweep", "cli"]
    assert rm.labels_for("tools/fuzz_cli.py", rules, all_labels) == all_labels


def test_every_hand_written_mutation_names_labels_that_tests_carry():
    # A label no test carries runs nothing: the mutant would survive unseen.
    all_labels, _ = rm.load_coverage(ROOT / "tests" / "mutations" / "coverage.toml")
    mutations = mutation_test.load_mutations(ROOT / "tests" / "mutations")
    assert len(mutations) > 500
    mutation_test.check_labels(mutations, all_labels)
    bad = [dict(mutations[0], labels=["frame"])]
    with pytest.raises(mutation_test.ListError, match="no test carries the label.s. frame"):
        mutation_test.check_labels(bad, all_labels)


def test_every_parameter_table_is_seen_by_the_range_tests():
    # Parameters.EveryRangeIsInclusiveAtBothEndsAndNoWider (label params) reads every module's
    # table: a default moved past its range fails there, and only there.
    all_labels, rules = rm.load_coverage(ROOT / "tests" / "mutations" / "coverage.toml")
    tables = [p for p in sorted((ROOT / "src").rglob("*.cpp")) if ".defaultValue" in p.read_text()]
    assert len(tables) >= 10
    for path in tables:
        rel = path.relative_to(ROOT).as_posix()
        assert "params" in rm.labels_for(rel, rules, all_labels), rel


# --- mutants in mutation_test.py's shape ---------------------------------------------------------

TWICE = "{\n        x = y + 1;\n    x = y + 1;\n    x = y + 1;\n}\n"


def test_occurrence_lets_locate_find_exactly_that_line(tmp_path):
    # "    x = y + 1;" occurs inside line 2 too (deeper indentation): line 4 is its third.
    cands = [c for c in rm.file_candidates("src/x.cpp", TWICE, {4}) if c.op == "arith"]
    assert len(cands) == 1
    offset = rm.line_offset(TWICE, 4)
    assert offset == TWICE.index("    x = y + 1;\n}")
    m = rm.mutant(cands[0], TWICE, "r-x", ["unit"])
    edit = m["edits"][0]
    assert edit == {"file": "src/x.cpp", "find": "    x = y + 1;", "replace": "    x = y - 1;",
                    "occurrence": 3}
    assert mutation_test.locate(m, edit, TWICE) == offset
    (tmp_path / "src").mkdir()
    (tmp_path / "src" / "x.cpp").write_text(TWICE)
    originals = mutation_test.apply(m, tmp_path)
    assert (tmp_path / "src" / "x.cpp").read_text() == TWICE.replace(
        "    x = y + 1;\n}", "    x = y - 1;\n}")
    assert list(originals.values()) == [TWICE]


def test_apply_keeps_the_original_of_a_file_edited_twice(tmp_path):
    (tmp_path / "a.cpp").write_text("x = 1; y = 2;")
    m = {"id": "m", "edits": [{"file": "a.cpp", "find": "x = 1", "replace": "x = 3"},
                              {"file": "a.cpp", "find": "y = 2", "replace": "y = 4"}]}
    originals = mutation_test.apply(m, tmp_path)
    assert (tmp_path / "a.cpp").read_text() == "x = 3; y = 4;"
    assert originals == {tmp_path / "a.cpp": "x = 1; y = 2;"}


def test_occurrence_of_each_copy():
    text = "a;\nba;\na;\n"  # "a;" at 0, inside "ba;" at 4, and at 7
    assert [rm.occurrence(text, "a;", at) for at in (0, 4, 7)] == [1, 2, 3]
    assert rm.occurrence(text, "a;", 1) is None
    assert rm.occurrence("aaa", "aa", 1) is None  # locate() could not reach an overlap
    assert [rm.line_offset(text, n) for n in (1, 2, 3, 4)] == [0, 3, 7, 10]


def test_a_mutant_has_mutation_test_shape_and_a_diff():
    c = next(c for c in rm.file_candidates("src/x.cpp", TWICE, {3}) if c.op == "int")
    m = rm.mutant(c, TWICE, "r-x-int-1", ["unit", "math"])
    long = "a;\nb;\nc;\nd;\n    e = 1;\nf;\ng;\nh;\ni;\n"
    d = next(c for c in rm.file_candidates("src/y.cpp", long, {5}) if c.op == "drop")
    assert rm.mutant(d, long, "r-y", [])["diff"] == (
        "--- a/src/y.cpp\n+++ b/src/y.cpp\n@@ -3,5 +3,5 @@\n c;\n d;\n-    e = 1;\n+\n f;\n g;\n")
    assert m["kind"] in mutation_test.KINDS and m["kind"] == "off-by-one"
    assert (m["id"], m["labels"], m["line"], m["files"]) == ("r-x-int-1", ["unit", "math"], 3,
                                                             "src/x.cpp")
    assert m["why"] == "random: int at src/x.cpp:3"
    assert m["diff"] == ("--- a/src/x.cpp\n+++ b/src/x.cpp\n@@ -1,5 +1,5 @@\n {\n"
                         "         x = y + 1;\n-    x = y + 1;\n+    x = y + 0;\n"
                         "     x = y + 1;\n }\n")


def test_every_operator_has_its_kind_and_mutation_test_knows_it():
    assert set(rm.KIND.values()) <= mutation_test.KINDS
    texts = [("src/x.cpp", "{\n    y = a + b * c - -d / e;\n    ok = !done && n >= 0 || x;\n"
              "    if (a < b) v = std::min(a, 2.5f);\n    i -= 2;\n    ok = true;\n}"),
             ("tools/t.py", "x = 0\nif a and not b:\n    x = y is None or -z * 1.5\n")]
    seen = set()
    for path, text in texts:
        for c in rm.file_candidates(path, text, set(range(1, 10))):
            seen.add(c.op)
            if c.op == "arith":
                op = max((o for o in rm.ARITH if c.original.startswith(o, c.col)), key=len)
                assert c.kind == rm.ARITH[op][1] and c.kind == ("sign" if op[0] in "+-" else
                                                                "swap"), c
            else:
                assert c.kind == rm.KIND[c.op], c
    assert seen == (set(rm.KIND) | {"arith"}) - {"swap-args"}


def test_ids_are_stable_across_lines_indentation_and_seeds():
    a = rm.file_candidates("src/x.cpp", "{\n    x = y + 1;\n}", {2})
    b = rm.file_candidates("src/x.cpp", "{\n\n  z = 2;\n        x = y + 1;\n}", {4})
    assert [rm.stable_id(c) for c in a] == [rm.stable_id(c) for c in b]
    ids = [rm.stable_id(c) for c in a]
    assert ids == ["r-x-drop-6023ebba", "r-x-arith-edde1881", "r-x-int-4a4f9cd3",
                   "r-x-int-8e5a00e0"]
    assert all(i.startswith("r-x-") for i in ids)
    other = rm.file_candidates("src/y.cpp", "{\n    x = y + 1;\n}", {2})
    assert rm.stable_id(a[0]) != rm.stable_id(other[0])


def test_the_same_line_twice_gets_numbered_ids():
    cands = rm.file_candidates("src/x.cpp", TWICE, {3, 4})
    ids = rm.assign_ids(cands)
    assert len(set(ids.values())) == len(cands)
    for c in cands:
        assert ids[c] == rm.stable_id(c) + ("-2" if c.line == 4 else "")


# --- equivalents, listing, report ----------------------------------------------------------------

def test_equivalent_mutants_are_set_aside_not_counted(tmp_path):
    path = tmp_path / "eq.toml"
    path.write_text('[[equivalent]]\nid = "r-b"\nreason = "the same"\n')
    equivalent = rm.load_equivalent(path)
    assert equivalent == {"r-b": "the same"}
    assert rm.load_equivalent(tmp_path / "none.toml") == {}
    assert rm.load_equivalent(ROOT / "tests" / "mutations" / "equivalent_random.toml") is not None
    source = ({"id": i} for i in ("r-a", "r-b", "r-c", "r-d"))
    assert [m["id"] for m in rm.first(source, 2, equivalent)] == ["r-a", "r-b", "r-c"]
    assert [m["id"] for m in rm.first(iter([{"id": "r-a"}]), 0, {})] == []


def test_listing_shows_the_mutant_and_its_diff():
    m = {"id": "r-x", "kind": "sign", "labels": ["unit", "math"], "files": "src/x.cpp",
         "line": 3, "diff": "--- a\n+++ b\n"}
    assert rm.listing(m, {}) == (f"{'r-x':44} {'sign':10} {'unit,math':22} src/x.cpp:3\n"
                                 "    --- a\n    +++ b")
    assert rm.listing(m, {"r-x": "why"}).split("\n")[0].endswith("src/x.cpp:3 (equivalent: why)")


def result(mid, status, outcome="", seconds=1.0):
    return {"id": mid, "kind": "sign", "files": "src/x.cpp", "line": 3, "status": status,
            "outcome": outcome or status, "labels": ["unit"], "why": f"why {mid}",
            "diff": f"-{mid} before\n+{mid} after\n", "seconds": seconds}


def test_the_report_gives_the_rate_every_outcome_and_the_survivors_diffs(tmp_path, repo):
    results = [result("r-k1", "killed", "killed by T.A"), result("r-k2", "killed"),
               result("r-s", "survived", "SURVIVED (every test)"), result("r-i", "invalid"),
               result("r-e", "equivalent", "same maths")]
    mutants = rm.Mutants(repo, "HEAD", 3, repo / "tests" / "mutations" / "coverage.toml")
    report = tmp_path / "out" / "deeper" / "r.md"
    assert mutants.write_report(str(report), results, 3, True) == 2
    assert mutants.write_report(report, results, 3, True) == 2  # over the last one
    text = report.read_text()
    assert "**killed 2 of 3 (66.7%)**; 1 invalid (do not build), 1 equivalent (not counted)" in text
    assert f"since `HEAD` ({mutants.base}), seed 3, 3 requested, drawn from 20 candidates on " \
           "5 changed lines" in text
    for r in results:
        assert f"| `{r['id']}` | sign | src/x.cpp:3 | {r['outcome']} | 1 |" in text
    assert "```diff\n-r-s before\n+r-s after\n```" in text
    assert "## Equivalent" in text and "-r-e before" in text and "same maths" in text
    assert "-r-k1 before" not in text and "-r-i before" not in text
    assert report.with_suffix(".json").read_text().startswith('{\n "since": "HEAD",\n')
    data = json.loads(report.with_suffix(".json").read_text())
    assert data["seed"] == 3 and data["rest"] is True and len(data["mutants"]) == 5


def test_an_empty_report():
    text = rm.report_markdown({"since": "HEAD", "base": "abc", "seed": 1, "requested": 0,
                               "candidates": 0, "lines": 0}, [])
    assert "**killed 0 of 0 (0.0%)**" in text and "## Survivors" not in text


# --- the runner's side ---------------------------------------------------------------------------

def test_run_tests_selects_excludes_or_takes_everything(monkeypatch, tmp_path):
    calls = []
    monkeypatch.setattr(mutation_test, "run", lambda cmd, log, timeout=None: calls.append(
        (cmd, timeout)) or 0)
    mutation_test.run_tests(["a", "b"], 3, tmp_path / "l", 7)
    mutation_test.run_tests(["a"], 3, tmp_path / "l", 7, exclude=True)
    mutation_test.run_tests(None, 3, tmp_path / "l", 7)
    assert [c[0][3:6] for c in calls[:2]] == [["-L", "^(a|b)$", "-j"], ["-LE", "^(a)$", "-j"]]
    assert calls[2][0][3:5] == ["-j", "3"] and "-L" not in calls[2][0]
    assert all(c[1] == 28 for c in calls)


def test_a_test_run_by_an_interpreter_needs_the_whole_build(monkeypatch):
    build = mutation_test.BUILD
    tests = {"tests": [
        {"command": [str(build / "tests" / "penumbra_unit_tests")],
         "properties": [{"name": "LABELS", "value": ["unit", "math"]}]},
        {"command": [str(build / "tests" / "penumbra_cli_tests")],
         "properties": [{"name": "LABELS", "value": ["cli"]}]},
        {"command": ["/usr/bin/python3", "-m", "pytest"],
         "properties": [{"name": "LABELS", "value": ["tools", "unit"]}]}]}

    class Done:
        stdout = json.dumps(tests)
    calls = []
    monkeypatch.setattr(mutation_test.subprocess, "run", lambda *a, **k: calls.append((a, k))
                        or Done())
    targets = mutation_test.targets_by_label()
    assert calls == [((["ctest", "--test-dir", str(build), "--show-only=json-v1"],),
                      {"check": True, "capture_output": True, "text": True})]
    assert targets["math"] == {"penumbra_unit_tests"}
    assert targets["cli"] == {"penumbra_cli_tests", "penumbra"}
    assert targets["tools"] == {None}
    assert mutation_test.needed_targets(["math", "cli"], targets) == [
        "penumbra", "penumbra_cli_tests", "penumbra_unit_tests"]
    assert mutation_test.needed_targets(["math", "tools"], targets) == []
    assert mutation_test.needed_targets(["nothing"], targets) == []


def in_repo(monkeypatch, repo, argv):
    """mutation_test.py on `repo` with `argv`; nothing may build, sync or run ctest."""
    def forbidden(*args, **kwargs):
        raise AssertionError("no build, no scratch tree, no ctest here")
    monkeypatch.setattr(mutation_test, "ROOT", repo)
    monkeypatch.setattr(mutation_test, "MUTATIONS", repo / "tests" / "mutations")
    monkeypatch.setattr(mutation_test, "LOGS", repo / "build" / "mutation" / "logs")
    for name in ("run", "sync_scratch", "prepare", "build", "targets_by_label", "try_mutant"):
        monkeypatch.setattr(mutation_test, name, forbidden)
    monkeypatch.setattr(sys, "argv", ["mutation_test.py", *argv])


def drawn(repo, seed):
    return [m["id"] for m in rm.Mutants(repo, "HEAD", seed, repo / "tests" / "mutations" /
                                        "coverage.toml")]


def test_random_list_end_to_end(monkeypatch, repo, capsys):
    argv = ["--random", "4", "--since", "HEAD", "--seed", "5", "--list"]
    in_repo(monkeypatch, repo, argv)
    (repo / "tests" / "mutations" / "equivalent_random.toml").write_text("")
    assert mutation_test.main() == 0
    out = capsys.readouterr().out.split("\n")
    assert out[0].startswith("mutation-test: random mutants since HEAD (")
    assert out[0].endswith("seed 5: 20 candidates on 5 changed lines in 2 files")
    heads = [line for line in out if line.startswith("r-")]
    expected = drawn(repo, 5)[:4]
    assert [h.split()[0] for h in heads] == expected
    assert sum(line.startswith("    @@ ") for line in out) == 4
    first = expected[0]
    (repo / "tests" / "mutations" / "equivalent_random.toml").write_text(
        f'[[equivalent]]\nid = "{first}"\nreason = "no change"\n')
    assert mutation_test.main() == 0
    heads = [line for line in capsys.readouterr().out.split("\n") if line.startswith("r-")]
    assert len(heads) == 5 and heads[0].endswith("(equivalent: no change)")
    monkeypatch.setattr(sys, "argv", ["mutation_test.py", *argv, "--only", "r-nothing"])
    assert mutation_test.main() == 2
    monkeypatch.setattr(sys, "argv", ["mutation_test.py", *argv[:-1]])  # no --list: a run
    with pytest.raises(AssertionError, match="no build"):
        mutation_test.main()


def test_the_default_seed_is_one(monkeypatch, repo, capsys):
    in_repo(monkeypatch, repo, ["--random", "2", "--since", "HEAD", "--list"])
    assert mutation_test.main() == 0
    assert ", seed 1: " in capsys.readouterr().out.split("\n")[0]


def test_an_unknown_revision_stops_the_run(monkeypatch, repo, capsys):
    in_repo(monkeypatch, repo, ["--random", "3", "--since", "no-such-rev", "--list"])
    assert mutation_test.main() == 2
    assert capsys.readouterr().err.startswith("error: random mutants since no-such-rev: ")


def test_a_random_run_replaces_invalid_mutants_and_reports(monkeypatch, repo, capsys):
    report = repo / "build" / "r.md"
    in_repo(monkeypatch, repo, ["--random", "3", "--since", "HEAD", "--seed", "5",
                                "--report", str(report)])
    order = drawn(repo, 5)
    (repo / "tests" / "mutations" / "equivalent_random.toml").write_text(
        f'[[equivalent]]\nid = "{order[1]}"\nreason = "no change"\n')
    outcomes = iter([("invalid", "INVALID (does not build)"), ("killed", "killed by T.a"),
                     ("survived", "SURVIVED (every test)"), ("killed", "killed by T.b")])
    calls = []
    monkeypatch.setattr(mutation_test, "prepare", lambda args, labels: calls.append(labels) or True)
    monkeypatch.setattr(mutation_test, "targets_by_label", lambda: {"unit": {"u"}})
    monkeypatch.setattr(mutation_test, "build", lambda jobs, log: calls.append(log.name) or True)
    monkeypatch.setattr(mutation_test, "try_mutant", lambda m, args, executables, rest, labels:
                        calls.append((m["id"], executables, rest, tuple(labels)))
                        or next(outcomes))
    assert mutation_test.main() == 0
    everything = ("unit", "cli", "tools")
    assert calls == [None] + [(order[i], {"unit": {"u"}}, True, everything)
                              for i in (0, 2, 3, 4)] + ["restore-build.log"]
    out = capsys.readouterr().out.split("\n")
    progress = [line for line in out if line.startswith("[")]
    assert [line.split()[0:2] for line in progress] == [
        ["[", "-/3]"], ["[", "1/3]"], ["[", "2/3]"], ["[", "3/3]"]]
    assert [line.split()[2] for line in progress] == [order[i] for i in (0, 2, 3, 4)]
    assert all(", ETA 0m" in line for line in progress)
    assert out[-2] == "mutation-test: killed 2 of 3 (66.7%)"
    assert [line for line in out if line.startswith("  survivor: ")] == [
        f"  survivor: {order[3]} ({where(repo, order[3])})"]
    assert "1 invalid (do not build), 1 equivalent, not counted" in "\n".join(out)
    assert "**killed 2 of 3 (66.7%)**" in report.read_text()
    data = json.loads(report.with_suffix(".json").read_text())
    assert [m["status"] for m in data["mutants"]] == [
        "invalid", "equivalent", "killed", "survived", "killed"]
    assert all(0 <= m.get("seconds", 0) < 60 for m in data["mutants"])


def where(repo, mid):
    mutants = rm.Mutants(repo, "HEAD", 1, repo / "tests" / "mutations" / "coverage.toml")
    return next(f"{m['files']}:{m['line']}" for m in mutants if m["id"] == mid)


def test_a_random_run_takes_what_the_draw_has_with_the_default_options(monkeypatch, repo, capsys):
    in_repo(monkeypatch, repo, ["--random", "50", "--since", "HEAD",
                                "--report", str(repo / "build" / "r.md")])
    seen = []
    monkeypatch.setattr(mutation_test, "prepare", lambda args, labels: True)
    monkeypatch.setattr(mutation_test, "targets_by_label", lambda: {})
    monkeypatch.setattr(mutation_test, "build", lambda *a, **k: True)
    monkeypatch.setattr(mutation_test, "try_mutant", lambda m, args, executables, rest, labels:
                        seen.append((args.jobs, args.timeout, args.seed, rest))
                        or ("killed", "killed by T.a"))
    assert mutation_test.main() == 0
    assert seen == [(mutation_test.os.cpu_count(), 600, 1, True)] * 20
    assert capsys.readouterr().out.split("\n")[-2] == "mutation-test: killed 20 of 20 (100.0%)"
    monkeypatch.setattr(mutation_test, "prepare", lambda args, labels: False)
    assert mutation_test.main() == 2


def test_a_random_run_without_the_rest_and_with_nothing_but_invalid(monkeypatch, repo, capsys):
    in_repo(monkeypatch, repo, ["--random", "2", "--since", "HEAD", "--no-rest",
                                "--report", str(repo / "build" / "r.md")])
    calls = []
    monkeypatch.setattr(mutation_test, "prepare", lambda args, labels: calls.append(labels) or True)
    monkeypatch.setattr(mutation_test, "targets_by_label", lambda: {})
    monkeypatch.setattr(mutation_test, "build", lambda *a, **k: True)
    monkeypatch.setattr(mutation_test, "try_mutant", lambda m, args, executables, rest, labels:
                        calls.append(rest) or ("invalid", "INVALID (does not build)"))
    assert mutation_test.main() == 0
    assert calls == [["cli", "tools", "unit"], False, False, False]  # then it gives up
    assert capsys.readouterr().out.split("\n")[-2] == "mutation-test: killed 0 of 0 (0.0%)"


def test_try_mutant_builds_runs_the_labels_then_the_rest(monkeypatch, tmp_path):
    target = tmp_path / "x.cpp"
    target.write_text("mutated")
    runs, builds, failing = [], [], set()
    monkeypatch.setattr(mutation_test, "apply", lambda m, root: {target: "original"}
                        if root == mutation_test.SCRATCH and "id" in m else None)
    monkeypatch.setattr(mutation_test, "LOGS", tmp_path)
    monkeypatch.setattr(mutation_test, "build", lambda jobs, log, targets=(): builds.append(
        list(targets)) or (jobs == 2 and log.name == "r-x.build.log" and "build" not in failing))
    monkeypatch.setattr(mutation_test, "run_tests", lambda labels, jobs, log, timeout,
                        exclude=False: runs.append((labels, exclude)) or int(exclude in failing))
    monkeypatch.setattr(mutation_test, "first_failure", lambda log: "T.x")

    class Args:
        jobs, timeout = 2, 5
    m = {"id": "r-x", "labels": ["math"]}
    executables = {"math": {"unit_tests"}}
    assert mutation_test.try_mutant(m, Args, executables, True, ["math", "cli"]) == (
        "survived", "SURVIVED (every test)")
    assert runs == [(["math"], False), (["math"], True)] and builds == [["unit_tests"], []]
    assert target.read_text() == "original"
    failing.add(True)
    assert mutation_test.try_mutant(m, Args, executables, True, ["math", "cli"]) == (
        "killed", "killed by T.x (outside its labels)")
    failing.add(False)
    assert mutation_test.try_mutant(m, Args, executables, True, ["math", "cli"]) == (
        "killed", "killed by T.x")
    failing.clear()
    runs.clear()
    assert mutation_test.try_mutant(m, Args, executables, False, ["math", "cli"]) == (
        "survived", "SURVIVED")
    assert mutation_test.try_mutant(m, Args, executables, True, ["math"]) == (
        "survived", "SURVIVED")
    assert mutation_test.try_mutant(m, Args, executables) == ("survived", "SURVIVED")
    assert runs == [(["math"], False)] * 3
    failing.add("build")
    assert mutation_test.try_mutant(m, Args, executables) == (
        "invalid", "INVALID (does not build)")
    target.write_text("mutated")
    with pytest.raises(ZeroDivisionError):
        monkeypatch.setattr(mutation_test, "build", lambda *a, **k: 1 / 0)
        mutation_test.try_mutant(m, Args, executables)
    assert target.read_text() == "original"  # restored whatever happens


# --- the hand-written lists' runner, which random mode shares ---------------------------------

def write_list(directory, text):
    directory.mkdir(parents=True, exist_ok=True)
    (directory / "a.toml").write_text(text)
    coverage = ROOT / "tests" / "mutations" / "coverage.toml"  # the labels the lists may name
    (directory / "coverage.toml").write_text(coverage.read_text())
    return directory


ENTRY = '''[[mutation]]
id = "{id}"
file = "src/x.cpp"
find = "a + b"
replace = "a - b"
labels = ["unit"]
kind = "{kind}"
why = "w"
'''


def test_load_mutations_checks_every_entry(tmp_path):
    good = ENTRY.format(id="m1", kind="sign") + '''
[[mutation]]
id = "m2"
labels = ["unit", "math"]
kind = "swap"
why = "w"
[[mutation.edits]]
file = "a.h"
find = "x"
replace = "y"
occurrence = 2
[[mutation.edits]]
file = "b.h"
find = "p"
replace = "q"
[[mutation.edits]]
file = "a.h"
find = "u"
replace = "v"
'''
    d = write_list(tmp_path / "ok", good)
    (d / "coverage.toml").write_text('all = ["unit"]\n[files]\n"src/**" = ["unit"]\n')
    m1, m2 = mutation_test.load_mutations(d)
    assert m1["edits"] == [{"file": "src/x.cpp", "find": "a + b", "replace": "a - b"}]
    assert (m1["files"], m1["list"], m2["files"]) == ("src/x.cpp", "a.toml", "a.h, b.h")
    assert m2["edits"][0]["occurrence"] == 2
    bad = {"missing": ENTRY.format(id="m", kind="sign").replace('why = "w"\n', ""),
           "duplicate": ENTRY.format(id="m", kind="sign") * 2,
           "kind": ENTRY.format(id="m", kind="nonsense"),
           "same": ENTRY.format(id="m", kind="sign").replace('"a - b"', '"a + b"'),
           "edit": ENTRY.format(id="m", kind="sign").replace('replace = "a - b"\n', "")}
    messages = {}
    for name, text in bad.items():
        with pytest.raises(mutation_test.ListError) as e:
            mutation_test.load_mutations(write_list(tmp_path / name, text))
        messages[name] = str(e.value)
    assert messages == {"missing": "a.toml: m: missing 'why'",
                        "duplicate": "a.toml: m: duplicate id",
                        "kind": "a.toml: m: kind 'nonsense' is not one of ['compare', 'constant', "
                                "'drop', 'logic', 'off-by-one', 'sign', 'swap']",
                        "same": "a.toml: m: find and replace are the same",
                        "edit": "a.toml: m: an edit is missing 'replace'"}


def test_the_real_lists_load_and_the_data_files_beside_them_hold_no_entries():
    mutations = mutation_test.load_mutations(ROOT / "tests" / "mutations")
    assert len(mutations) > 500 and all(m["list"] not in ("coverage.toml",
                                                           "equivalent_random.toml")
                                        for m in mutations)


def test_locate_needs_one_match_or_an_occurrence():
    m, text = {"id": "m"}, "a + b; a + b; a + b;"
    assert mutation_test.locate(m, {"find": "b;", "file": "f"}, "x b; y") == 2
    with pytest.raises(mutation_test.ListError, match="'find' occurs 3 times in f"):
        mutation_test.locate(m, {"find": "a + b", "file": "f"}, text)
    with pytest.raises(mutation_test.ListError, match="'find' occurs 0 times"):
        mutation_test.locate(m, {"find": "zz", "file": "f"}, text)
    assert [mutation_test.locate(m, {"find": "a + b", "file": "f", "occurrence": n}, text)
            for n in (1, 2, 3)] == [0, 7, 14]
    for n in (0, 4):
        with pytest.raises(mutation_test.ListError, match=f"occurrence {n} of 3 in f"):
            mutation_test.locate(m, {"find": "a + b", "file": "f", "occurrence": n}, text)


def test_first_failure_names_the_first_failing_test(tmp_path):
    log = tmp_path / "log"
    log.write_text("1/3 Test #1: Ok.Test ....   Passed\n"
                   "2/3 Test #2: Filter.Breaks ....***Failed  1.0 sec\n"
                   "3/3 Test #3: Later.Fails ....***Timeout 9.0 sec\n")
    assert mutation_test.first_failure(log) == "Filter.Breaks"
    log.write_text("1/1 Test #7: Slow.One ...***Timeout 9.0 sec\n")
    assert mutation_test.first_failure(log) == "Slow.One"
    log.write_text("1/1 Test #4: Crash.Test ...Subprocess aborted***Exception: SegFault  0.1 sec\n")
    assert mutation_test.first_failure(log) == "Crash.Test"
    log.write_text("nothing failed\n")
    assert mutation_test.first_failure(log) == "?"


def test_build_configures_once_then_builds_the_targets(monkeypatch, tmp_path):
    calls, results = [], iter([0, 0, 0, 1])
    monkeypatch.setattr(mutation_test, "BUILD", tmp_path)
    monkeypatch.setattr(mutation_test, "run", lambda cmd, log: calls.append(cmd) or next(results))
    assert mutation_test.build(3, tmp_path / "l", ["a", "b"])
    assert calls == [["cmake", "--preset", "release"],
                     ["cmake", "--build", "--preset", "release", "-j", "3", "--target", "a",
                      "--target", "b"]]
    (tmp_path / "CMakeCache.txt").write_text("")
    calls.clear()
    assert mutation_test.build(2, tmp_path / "l")
    assert calls == [["cmake", "--build", "--preset", "release", "-j", "2"]]
    assert not mutation_test.build(2, tmp_path / "l")
    (tmp_path / "CMakeCache.txt").unlink()
    monkeypatch.setattr(mutation_test, "run", lambda cmd, log: calls.append(cmd) or 1)
    calls.clear()
    assert not mutation_test.build(2, tmp_path / "l") and len(calls) == 1


def test_sync_scratch_copies_what_changed_and_removes_what_went(monkeypatch, tmp_path):
    root, scratch = tmp_path / "root", tmp_path / "scratch"
    for rel, text in (("a.txt", "a"), ("d/b.sh", "b"), ("same.txt", "s"), ("e/f/g.txt", "g")):
        (root / rel).parent.mkdir(parents=True, exist_ok=True)
        (root / rel).write_text(text)
    (root / "d" / "b.sh").chmod(0o755)
    (scratch / "build").mkdir(parents=True)
    (scratch / "build" / "keep.o").write_text("o")
    (scratch / "gone.txt").write_text("g")
    (scratch / "same.txt").write_text("s")
    monkeypatch.setattr(mutation_test, "ROOT", root)
    monkeypatch.setattr(mutation_test, "SCRATCH", scratch)
    listed = [Path("a.txt"), Path("d/b.sh"), Path("same.txt"), Path("missing.txt"),
              Path("e/f/g.txt")]
    monkeypatch.setattr(mutation_test, "tracked_files", lambda: listed)
    assert mutation_test.sync_scratch() == 3
    assert (scratch / "e" / "f" / "g.txt").read_text() == "g"
    assert (scratch / "a.txt").read_text() == "a" and (scratch / "d" / "b.sh").read_text() == "b"
    assert (scratch / "d" / "b.sh").stat().st_mode & 0o111
    assert not (scratch / "gone.txt").exists() and (scratch / "build" / "keep.o").exists()
    assert mutation_test.sync_scratch() == 0


def test_tracked_files_are_gits_tracked_and_untracked_not_ignored(monkeypatch, repo):
    monkeypatch.setattr(mutation_test, "ROOT", repo)
    files = set(mutation_test.tracked_files())
    assert {Path("src/a.cpp"), Path("tools/t.py"), Path(".gitignore")} <= files
    assert Path("build/b.cpp") not in files


def test_tracked_files_outside_a_repository_is_an_error(monkeypatch, tmp_path):
    monkeypatch.setattr(mutation_test, "ROOT", tmp_path)
    with pytest.raises(subprocess.CalledProcessError):
        mutation_test.tracked_files()


def test_eta_and_durations():
    assert mutation_test.eta(120.0, 4, 10) == 180.0
    assert mutation_test.eta(50.0, 0, 3) == 150.0
    assert mutation_test.eta(30.0, 3, 3) == 0.0
    assert [mutation_test.fmt_seconds(s) for s in (0, 59.9, 61, 3725)] == [
        "0m00s", "0m59s", "1m01s", "62m05s"]


def test_run_logs_the_output_and_times_out(tmp_path):
    log = tmp_path / "log"
    assert mutation_test.run(["sh", "-c", "echo out; echo err >&2; exit 3"], log, cwd=tmp_path) == 3
    assert log.read_text() == "out\nerr\n"
    assert mutation_test.run(["sh", "-c", "pwd"], log, cwd=tmp_path) == 0
    assert log.read_text().strip() == str(tmp_path)
    assert mutation_test.run(["sleep", "5"], log, timeout=0.2, cwd=tmp_path) == 124


def test_prepare_syncs_builds_and_needs_a_passing_baseline(monkeypatch, tmp_path, capsys):
    class Args:
        jobs, timeout = 3, 7
    root = tmp_path / "root"
    monkeypatch.setattr(mutation_test, "ROOT", root)
    monkeypatch.setattr(mutation_test, "SCRATCH", root / "build" / "mutation" / "tree")
    monkeypatch.setattr(mutation_test, "LOGS", root / "build" / "mutation" / "logs")
    monkeypatch.setattr(mutation_test, "sync_scratch", lambda: 4)
    builds, tests, results = [], [], {"build": True, "tests": 0}
    monkeypatch.setattr(mutation_test, "build", lambda jobs, log: builds.append((jobs, log.name))
                        or results["build"])
    monkeypatch.setattr(mutation_test, "run_tests", lambda labels, jobs, log, timeout: tests.append(
        (labels, jobs, log.name, timeout)) or results["tests"])
    assert mutation_test.prepare(Args, ["a", "b"]) is True
    assert (root / "build" / "mutation" / "logs").is_dir()
    assert (root / "build" / "mutation" / "tree").is_dir()
    assert mutation_test.prepare(Args, None) is True
    assert builds == [(3, "baseline-build.log")] * 2
    assert tests == [(["a", "b"], 3, "baseline-tests.log", 7), (None, 3, "baseline-tests.log", 7)]
    assert capsys.readouterr().out.split("\n") == [
        "mutation-test: scratch tree build/mutation/tree: 4 files copied",
        "mutation-test: building the unmutated tree ...",
        "mutation-test: baseline: labels a, b must pass unmutated ...",
        "mutation-test: scratch tree build/mutation/tree: 4 files copied",
        "mutation-test: building the unmutated tree ...",
        "mutation-test: baseline: every test must pass unmutated ...", ""]
    results["tests"] = 8
    assert mutation_test.prepare(Args, ["a"]) is False
    assert "error: tests fail on the unmutated tree" in capsys.readouterr().err
    results["build"], tests[:] = False, []
    assert mutation_test.prepare(Args, ["a"]) is False and tests == []
    assert "error: the unmutated tree does not build" in capsys.readouterr().err


def test_hand_written_mode_runs_each_list_entry(monkeypatch, tmp_path, capsys):
    (tmp_path / "src").mkdir()
    (tmp_path / "src" / "x.cpp").write_text("int f() { return a + b; }\n")
    lists = write_list(tmp_path / "tests" / "mutations",
                       ENTRY.format(id="m1", kind="sign") + ENTRY.format(id="m2", kind="sign")
                       + ENTRY.format(id="m3", kind="sign") + ENTRY.format(id="m4", kind="sign")
                       + 'equivalent = "no change"\n')
    in_repo(monkeypatch, tmp_path, ["--list"])
    monkeypatch.setattr(mutation_test, "MUTATIONS", lists)
    assert mutation_test.main() == 0
    out = capsys.readouterr().out.split("\n")
    assert out[0] == f"{'m1':44} {'sign':10} {'unit':22} src/x.cpp"
    assert out[3] == f"{'m4':44} {'sign':10} {'unit':22} src/x.cpp (equivalent)"
    monkeypatch.setattr(sys, "argv", ["mutation_test.py", "--list", "--only", "m2,m3"])
    assert mutation_test.main() == 0
    assert [line.split()[0] for line in capsys.readouterr().out.split("\n") if line] == [
        "m2", "m3"]
    monkeypatch.setattr(sys, "argv", ["mutation_test.py", "--list", "--label", "math"])
    assert mutation_test.main() == 0 and capsys.readouterr().out == ""
    monkeypatch.setattr(sys, "argv", ["mutation_test.py", "--only", "m9"])
    assert mutation_test.main() == 2
    assert "unknown mutation ids ['m9']" in capsys.readouterr().err

    outcomes = iter([("killed", "killed by T.a"), ("invalid", "INVALID (does not build)"),
                     ("survived", "SURVIVED")])
    calls = []
    monkeypatch.setattr(mutation_test, "prepare", lambda args, labels: calls.append(labels) or True)
    monkeypatch.setattr(mutation_test, "targets_by_label", lambda: {})
    monkeypatch.setattr(mutation_test, "build", lambda *a, **k: calls.append("restore") or True)
    monkeypatch.setattr(mutation_test, "try_mutant", lambda m, args, executables:
                        calls.append(m["id"]) or next(outcomes))
    monkeypatch.setattr(sys, "argv", ["mutation_test.py"])
    assert mutation_test.main() == 1  # an invalid entry is an error in the list
    assert calls == [["unit"], "m1", "m2", "m3", "restore"]
    out = capsys.readouterr().out.split("\n")
    assert out[0].startswith("mutation-test: baseline passed after 0m00s; 3 mutations")
    assert [line.split()[:3] for line in out[1:4]] == [
        ["[", "1/3]", "m1"], ["[", "2/3]", "m2"], ["[", "3/3]", "m3"]]
    assert out[1].split("m1", 1)[1].strip().startswith("killed by T.a (")
    assert out[-6:] == [out[-6], "  equivalent, not run: m4: no change",
                        "  invalid (fix the list): m2 (src/x.cpp)", "  survivor: m3 (src/x.cpp): w",
                        "mutation-test: killed 1 of 2 (50.0%)", ""]
    assert out[-6].startswith("mutation-test: 0m00s in all; logs in build/mutation/logs")
    outcomes = iter([("killed", "k")] * 3)
    assert mutation_test.main() == 0
    assert capsys.readouterr().out.split("\n")[-2] == "mutation-test: killed 3 of 3 (100.0%)"
    prepare_fails = []
    monkeypatch.setattr(mutation_test, "prepare", lambda args, labels: prepare_fails.append(1))
    assert mutation_test.main() == 2 and prepare_fails == [1]
    monkeypatch.setattr(mutation_test, "prepare", lambda args, labels: True)
    monkeypatch.setattr(sys, "argv", ["mutation_test.py", "--only", "m4"])  # only an equivalent
    assert mutation_test.main() == 0
    assert capsys.readouterr().out.split("\n")[-2] == "mutation-test: killed 0 of 0 (0.0%)"
    (tmp_path / "src" / "x.cpp").write_text("int f() { return a * b; }\n")  # the list is stale
    assert mutation_test.main() == 2
    assert capsys.readouterr().err.startswith("error: tests/mutations: m1: 'find' occurs 0 times")


# --- refusals before anything is built --------------------------------------------------------

@pytest.mark.parametrize("argv,message", [
    (["--random", "0", "--since", "HEAD", "--list"], "error: --random: 0 mutants; at least 1"),
    (["--random", "-3", "--since", "HEAD"], "error: --random: -3 mutants; at least 1"),
    (["--since", "HEAD", "--list"], "error: --since goes with --random"),
    (["--seed", "4"], "error: --seed goes with --random"),
    (["--min-rate", "85"], "error: --min-rate goes with --random"),
    (["--no-rest"], "error: --no-rest goes with --random"),
    (["--random", "3", "--since=--output=x", "--list"], "error: random mutants since "
                                                           "--output=x: '--output=x' is not a"),
    (["--random", "3", "--since", "HEAD~1..HEAD", "--list"], "is not a revision"),
    (["--random", "3", "--since", "HEAD", "--label", "nolabel", "--list"],
     "error: --label: no label 'nolabel'"),
    (["--random", "3", "--since", "HEAD", "--only", "r-x,", "--list"],
     "error: --only: unknown mutant ids ['r-x']"),
])
def test_bad_options_are_one_error_line(monkeypatch, repo, capsys, argv, message):
    in_repo(monkeypatch, repo, argv)
    assert mutation_test.main() == 2
    err = capsys.readouterr().err
    assert message in err and err.count("\n") == 1, err


def test_no_changed_line_is_an_error_and_fewer_than_asked_a_warning(monkeypatch, repo, capsys):
    git(repo, "add", "-A")
    git(repo, "commit", "-q", "-m", "all")
    in_repo(monkeypatch, repo, ["--random", "3", "--since", "HEAD", "--list"])
    assert mutation_test.main() == 2
    assert "error: no line changed since HEAD can be mutated" in capsys.readouterr().err
    in_repo(monkeypatch, repo, ["--random", "500", "--since", "HEAD~1", "--list"])
    assert mutation_test.main() == 0
    out = capsys.readouterr().out
    assert "warning: 20 candidates, fewer than the 500 asked for" in out, out


def test_an_option_as_revision_reaches_no_git_command(tmp_path, repo):
    target = tmp_path / "written.txt"
    with pytest.raises(ValueError):
        rm.Mutants(repo, f"--output={target}", 1, repo / "tests" / "mutations" / "coverage.toml")
    assert not target.exists()


def test_non_utf8_and_non_ascii_files_are_mutated_and_written_back_unchanged(repo):
    name = repo / "src" / "café.cpp"
    raw = b"// caf\xe9\nint f(int a) {\n    return a + 1;\n}\n"
    name.write_bytes(raw)
    mutants = [m for m in rm.Mutants(repo, "HEAD", 1, repo / "tests" / "mutations" /
                                     "coverage.toml") if m["files"] == "src/café.cpp"]
    assert mutants, "the file's lines are candidates"
    originals = mutation_test.apply(mutants[0], repo)
    for target, text in originals.items():
        target.write_text(text, errors="surrogateescape")
    assert name.read_bytes() == raw


@pytest.mark.parametrize("text,message", [
    ('[equivalent]\nid = "r-a"\nreason = "x"\n', "[[equivalent]]"),
    ('[[equivalent]]\nid = "r-a"\n', "entry 1 needs an id and a reason"),
    ('[[equivalent]]\nreason = "x"\n', "entry 1 needs an id and a reason"),
    ('[[equivalent]]\nid = "r-a"\nreason = "x"\n[[equivalent]]\nid = "r-a"\nreason = "y"\n',
     "'r-a' is listed twice"),
])
def test_a_malformed_equivalent_list_is_refused(tmp_path, text, message):
    path = tmp_path / "equivalent_random.toml"
    path.write_text(text)
    with pytest.raises(ValueError, match=re.escape(message)):
        rm.load_equivalent(path)


def test_min_rate_fails_a_run_below_the_standard(monkeypatch, repo, capsys):
    for rate, code in ((60, 0), (70, 1)):
        in_repo(monkeypatch, repo, ["--random", "3", "--since", "HEAD", "--min-rate", str(rate),
                                    "--report", str(repo / "build" / "r.md")])
        outcomes = iter([("killed", "k"), ("killed", "k"), ("survived", "S")] * 2)
        monkeypatch.setattr(mutation_test, "prepare", lambda args, labels: True)
        monkeypatch.setattr(mutation_test, "targets_by_label", lambda: {})
        monkeypatch.setattr(mutation_test, "build", lambda jobs, log: True)
        monkeypatch.setattr(mutation_test, "try_mutant", lambda *a: next(outcomes))
        assert mutation_test.main() == code, rate
        assert ("below the standard" in capsys.readouterr().err) == bool(code)


def test_an_unwritable_report_stops_the_run_before_the_build(monkeypatch, repo, capsys):
    (repo / "build" / "file").write_text("")
    in_repo(monkeypatch, repo, ["--random", "3", "--since", "HEAD",
                                "--report", str(repo / "build" / "file" / "r.md")])
    assert mutation_test.main() == 2
    assert capsys.readouterr().err.startswith("error: --report: ")


@pytest.mark.parametrize("code,declares", [
    ("StagedOutputDir(StagedOutputDir&& other) noexcept;", True),
    ("ReadbackLayout(uint32_t width, uint32_t height);", True),
    ("Foo(const Foo&) = delete;", True),
    ("Foo& operator=(Foo&&) = default;", True),
    ("virtual void run() = 0;", True),
    ("void record(VkCommandBuffer cmd, const Prepared& p);", True),
    ("static Scene load(const std::string& path);", True),
    ("track(next);", False),
    ("vkCmdDispatch(c.cmd, groups(w), groups(h), 1);", False),
    ("mesh.add(v);", False),
    ("i += step(a, b);", False),
    ("next = advanced;", False),
    ("print(uint32_t(x));", False),
])
def test_declarations_are_never_deleted(code, declares):
    assert rm.declares_function(code) == declares
    text = "struct S {\n    int a;\n    " + code + "\n};\n"
    drops = [c for c in rm.file_candidates("src/s.h", text, {3}) if c.op == "drop"]
    assert bool(drops) != declares, drops


def test_a_mutated_line_in_another_encoding_and_a_spaced_name_get_plain_ids(repo):
    (repo / "src" / "two words.cpp").write_bytes(b'int f(int a) {\n    return a + 1; // caf\xe9\n}\n')
    mutants = [m for m in rm.Mutants(repo, "HEAD", 1, repo / "tests" / "mutations" /
                                     "coverage.toml") if m["files"] == "src/two words.cpp"]
    assert mutants
    assert all(re.fullmatch(r"r-two-words-[\w-]+-[0-9a-f]{8}(-\d+)?", m["id"]) for m in mutants), \
        [m["id"] for m in mutants]


def test_a_list_cut_short_by_its_reader_ends_quietly(repo):
    done = subprocess.run(
        f"{sys.executable} {ROOT / 'tools' / 'mutation_test.py'} --list | head -1",
        shell=True, capture_output=True, text=True, cwd=ROOT)
    assert "Traceback" not in done.stderr and "BrokenPipe" not in done.stderr, done.stderr
