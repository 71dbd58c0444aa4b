"""Where the shared code names one technique (tools/technique_coupling.py), on a scratch tree:
what counts as a place, what does not (comments, src/shadows, a field several modules set, a
declaration), and the check against the recorded figure."""
import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "tools"))
import technique_coupling  # noqa: E402

MODULE_H = """struct TechniqueModule {
    TechniqueInfo info; // name
    bool tracesField = false;
    bool modelsLightSize = false;
    double (*searchCap)(const ParameterValues&) = nullptr;
    std::vector<PassDecl> passes; // declarations: run whoever lists them
    std::optional<FieldDecl> field; // a declaration too: built for whoever declares it
};
"""


def tree(root, files, record=None):
    base = {
        "shaders/include/technique_list.h":
            "PENUMBRA_TECHNIQUE(0, Hard, hard, shadow_hard)\n"
            "PENUMBRA_TECHNIQUE(1, MsmSoft, msmSoft, shadow_sat)\n",
        "src/shadows/technique.h": MODULE_H,
        "src/shadows/hard.cpp": 'const TechniqueModule& hardModule() {\n'
                                '    static const TechniqueModule m{.info = {.name = "hard"},\n'
                                '        .tracesField = true, .modelsLightSize = true,\n'
                                '        .passes = {PassDecl{}}, .field = FieldDecl{}};\n}\n',
        "src/shadows/msm_soft.cpp": 'const TechniqueModule& msmSoftModule() {\n'
                                    '    static const TechniqueModule m{.info = {.name = '
                                    '"msm-soft"}, .modelsLightSize = true};\n}\n',
    }
    base.update(files)
    if record is not None:
        base["tests/technique_coupling.txt"] = f"# a comment\n{record}\n"
    for name, text in base.items():
        path = Path(root) / name
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text)
    technique_coupling.ROOT = Path(root)


def test_names_and_one_technique_fields_count_comments_and_shared_fields_do_not(tmp_path):
    tree(tmp_path, {
        "src/render/a.cpp": "\n".join([
            "if (o.technique == Technique::MsmSoft) {}",   # 1: the enum
            'params.number("msm-soft.maxRadius");',         # 2: its parameter key, by name
            "if (module.tracesField) {}",                   # 3: a field one module sets
            "if (module.modelsLightSize) {}",               # both set it: shared
            "// Technique::Hard in a comment",
            "/* module.tracesField",
            "   still a comment */ int x = 0;",
            'auto m = "hardly";',                           # not a name: a longer literal
            "const auto& h = hardModule();",                # 4: its module function
            "for (auto& pass : module.passes) {}",         # declarations one module lists
            "if (const auto& f = module.field) {}",         # an optional declaration
            "/* a comment first */ Technique::Hard;",       # 5: code after a closed comment
        ]),
        "src/shadows/b.cpp": "Technique::Hard; module.tracesField;",  # the modules' own folder
        "apps/c.h": 'std::string d = "hard";',              # 6: a name in apps/
    })
    assert technique_coupling.one_technique_fields() == ["tracesField"]
    found = technique_coupling.places()
    assert [(rel, line) for rel, line, _ in found] == [
        ("src/render/a.cpp", 1), ("src/render/a.cpp", 2), ("src/render/a.cpp", 3),
        ("src/render/a.cpp", 9), ("src/render/a.cpp", 12), ("apps/c.h", 1)]
    assert found[1][2] == ['"msm-soft"']


def test_the_check_holds_the_recorded_figure(tmp_path, capsys):
    tree(tmp_path, {"src/render/a.cpp": "Technique::Hard;\n"}, record=1)
    assert technique_coupling.main(["--check", "--quiet", "--root", str(tmp_path)]) == 0
    tree(tmp_path, {"src/render/a.cpp": "Technique::Hard;\nTechnique::MsmSoft;\n"}, record=1)
    assert technique_coupling.main(["--check", "--quiet", "--root", str(tmp_path)]) == 1
    assert "records 1: a change named a technique" in capsys.readouterr().err
    tree(tmp_path, {"src/render/a.cpp": "int x;\n"}, record=1)
    assert technique_coupling.main(["--check", "--quiet", "--root", str(tmp_path)]) == 1
    assert "lower the figure" in capsys.readouterr().err


def test_a_list_it_cannot_read_is_an_error_not_zero_coupling(tmp_path):
    # The three-column form of an older list: read as no technique, every count would be zero.
    tree(tmp_path, {"shaders/include/technique_list.h": "PENUMBRA_TECHNIQUE(0, Hard, hard)\n",
                    "src/render/a.cpp": "Technique::Hard;\n"})
    with pytest.raises(SystemExit, match="no PENUMBRA_TECHNIQUE line"):
        technique_coupling.places()


def test_the_root_option_is_the_tree_read_and_an_unreadable_record_is_an_error(tmp_path, capsys):
    tree(tmp_path, {"src/render/a.cpp": "Technique::Hard;\n"}, record=1)
    technique_coupling.ROOT = tmp_path / "elsewhere"  # --root, not the module's default, counts
    assert technique_coupling.main(["--check", "--quiet", "--root", str(tmp_path)]) == 0
    (tmp_path / "tests/technique_coupling.txt").unlink()
    assert technique_coupling.main(["--check", "--quiet", "--root", str(tmp_path)]) == 2
    assert capsys.readouterr().err.startswith("error: ")
