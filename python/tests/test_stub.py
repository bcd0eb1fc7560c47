"""python/relume.pyi against the module: the compress options the stub lists (class
CompressOptions and the keywords of compress and compress_file) are exactly relume.CompressOptions'
attributes, with the same defaults, which are the C++ library's (relume/compress.hpp); the moved
light's color= and spread= have the module's defaults (DirectionalLight's) wherever they are
taken. A default changed in C++ and not in the stub fails here."""
import ast
import re

import pytest

import relume
from conftest import source_dir

# Keywords of compress / compress_file that are not compress options.
NOT_OPTIONS = {"field", "dirs", "mask", "intensities", "report", "progress", "input", "output"}


def stub_tree():
    return ast.parse((source_dir() / "python" / "relume.pyi").read_text())


def stub_class_defaults(tree, name):
    for node in tree.body:
        if isinstance(node, ast.ClassDef) and node.name == name:
            return {item.target.id: ast.literal_eval(item.value) for item in node.body
                    if isinstance(item, ast.AnnAssign) and item.value is not None}
    pytest.fail(f"the stub has no class {name}")


def stub_keyword_defaults(tree, name):
    """The keyword-only defaults of function `name` ("Class.method" for a method)."""
    *owner, function = name.split(".")
    body = tree.body
    if owner:
        body = next((node.body for node in body
                     if isinstance(node, ast.ClassDef) and node.name == owner[0]), [])
    for node in body:
        if isinstance(node, ast.FunctionDef) and node.name == function:
            arguments = node.args
            return {argument.arg: ast.literal_eval(default)
                    for argument, default in zip(arguments.kwonlyargs, arguments.kw_defaults)
                    if argument.arg not in NOT_OPTIONS}
    pytest.fail(f"the stub has no function {name}")


def module_defaults():
    defaults = relume.CompressOptions()
    names = [name for name in dir(defaults) if not name.startswith("_")]
    return {name: getattr(defaults, name) for name in names}


@pytest.mark.parametrize("where", ["class CompressOptions", "compress", "compress_file"])
def test_the_stub_lists_every_compress_option_with_the_library_default(where):
    tree = stub_tree()
    listed = (stub_class_defaults(tree, "CompressOptions") if where.startswith("class")
              else stub_keyword_defaults(tree, where))
    actual = module_defaults()
    assert set(listed) == set(actual), (
        f"{where}: only in the stub {sorted(set(listed) - set(actual))}, "
        f"only in the module {sorted(set(actual) - set(listed))}")
    for name, value in actual.items():
        assert listed[name] == value, f"{where}: {name}"


def test_the_defaults_are_the_commands():
    """The command's --help shows the library's defaults for the options it prints them for."""
    from conftest import run_relume
    help_text = run_relume("compress", "--help").stdout
    defaults = relume.CompressOptions()
    for option, value in [("--clusters", defaults.clusters), ("--terms", defaults.terms),
                          ("--iterations", defaults.iterations),
                          ("--candidates", defaults.candidates), ("--residual", defaults.residual)]:
        line = next(line for line in help_text.splitlines() if line.strip().startswith(option))
        assert f"={value} " in line, line


def test_options_take_keywords_and_refuse_unknown_ones():
    options = relume.CompressOptions(clusters=8, residual=3, memory_limit="1G")
    assert (options.clusters, options.residual, options.memory_limit) == (8, 3, 1 << 30)
    with pytest.raises(relume.Error, match="unknown compress option 'cluster'"):
        relume.CompressOptions(cluster=8)


@pytest.mark.parametrize("where", ["light_vector", "Field.relight", "Compressed.relight"])
def test_the_stub_gives_the_moved_light_the_module_defaults(where):
    function = relume
    for part in where.split("."):
        function = getattr(function, part)
    # pybind11's signature line: name(argument: type = repr(default), ...) -> type
    signature = function.__doc__.splitlines()[0]
    module = {name: ast.literal_eval(
                  re.search(rf"\b{name}: \w+ = (\([^)]*\)|[-+0-9.e]+)", signature).group(1))
              for name in ("color", "spread")}
    stub = stub_keyword_defaults(stub_tree(), where)
    assert {name: stub[name] for name in module} == module, signature
