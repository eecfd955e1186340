"""What a Python user discovers the module by: its type stub (every name and signature, checked
against the module), docstrings, __version__, the names read() takes, errors in Python's words,
and the library's warnings as Python warnings of the module's own category."""
import ast
import inspect
import pathlib
import re
import warnings

import numpy as np
import pytest
import ssgi
from conftest import CORNELL, ROOT

STUB = pathlib.Path(ssgi.__file__).with_suffix(".pyi")
SKIPPED = {"__doc__", "__module__", "__dict__", "__weakref__", "__hash__"}


def module_signature(doc):
    """pybind11's signature line of a docstring, as the stub writes it: 'self' unannotated,
    the package's own types without 'ssgi.'."""
    line = doc.split("\n")[0]
    line = re.sub(r"^\w*\(", "(", line)
    line = re.sub(r"^\((self|arg0): ssgi\.\w+", "(self", line)
    return line.replace("ssgi.", "")


def stub_signature(function):
    def parameter(arg, default):
        text = arg.arg
        if arg.annotation is not None:
            text += ": " + ast.unparse(arg.annotation)
        if default is not None:
            text += " = " + ast.unparse(default)
        return text
    a = function.args
    positional = a.posonlyargs + a.args
    defaults = [None] * (len(positional) - len(a.defaults)) + a.defaults
    parts = [parameter(p, d) for p, d in zip(positional, defaults)]
    if a.kwonlyargs:
        parts += ["*"] + [parameter(p, d) for p, d in zip(a.kwonlyargs, a.kw_defaults)]
    if a.kwarg:
        parts.append("**" + parameter(a.kwarg, None))
    return f"({', '.join(parts)}) -> {ast.unparse(function.returns)}"


def stub_members(node):
    """{name: [(kind, signature)]} of a stub's module or class body."""
    members = {}
    for item in node.body:
        if isinstance(item, ast.FunctionDef):
            decorators = [ast.unparse(d) for d in item.decorator_list]
            kind = ("property" if "property" in decorators else
                    "setter" if any(d.endswith(".setter") for d in decorators) else "function")
            members.setdefault(item.name, []).append((kind, stub_signature(item)))
        elif isinstance(item, ast.ClassDef):
            members[item.name] = [("class", item)]
        elif isinstance(item, ast.AnnAssign):
            members[item.target.id] = [("value", ast.unparse(item.annotation))]
    return members


def python_signature(function):
    """A function written in Python (the package's own .py files) as the stub writes it."""
    return str(inspect.signature(function)).replace("'", "")


def module_members(owner):
    members = {}
    in_python = isinstance(owner, type) and type(owner) is type  # not a pybind11 class
    for name, value in vars(owner).items():
        if name in SKIPPED or (owner is ssgi and name.startswith("_") and name != "__version__"):
            continue
        if in_python and name in ("__annotations__", "__dict__", "__weakref__"):
            continue
        if inspect.isfunction(value):
            members[name] = [("function", python_signature(value))]
        elif isinstance(value, staticmethod):  # Scene.from_dict
            function = value.__func__
            members[name] = [("function", python_signature(function) if
                              inspect.isfunction(function) else module_signature(function.__doc__))]
        elif isinstance(value, type):
            members[name] = [("class", value)]
        elif isinstance(value, property):
            members[name] = [("property", module_signature(value.fget.__doc__))]
            if value.fset is not None:
                members[name].append(("setter", module_signature(value.fset.__doc__)))
        elif callable(value):
            if name == "__init__" and not (value.__doc__ or "").startswith("__init__("):
                continue  # no constructor (Settings is made by Scene)
            members[name] = [("function", module_signature(value.__doc__))]
        else:
            members[name] = [("value", type(value).__name__)]
    if in_python:  # what a class written in Python declares of its instances
        for name, annotation in vars(owner).get("__annotations__", {}).items():
            members[name] = [("value", str(annotation))]
    return members


def test_the_stub_is_the_module():
    assert STUB.exists(), "the stub is shipped beside the module"
    assert (STUB.parent / "py.typed").exists()
    tree = ast.parse(STUB.read_text())
    stub, module = stub_members(tree), module_members(ssgi)
    assert set(stub) == set(module), "names of the module and of its stub"
    assert set(ssgi.__all__) == set(module) - {"__version__"}
    for name, entries in module.items():
        kind, value = entries[0]
        if kind != "class":
            assert stub[name] == entries, name
            continue
        node = stub[name][0][1]
        if issubclass(value, BaseException):
            assert [ast.unparse(b) for b in node.bases] == [b.__name__ for b in value.__bases__], \
                name
            continue
        expected, given = module_members(value), stub_members(node)
        assert set(given) == set(expected), f"members of {name}"
        for member, signatures in expected.items():
            assert given[member] == signatures, f"{name}.{member}"


def test_every_class_function_and_property_has_a_docstring():
    def described(doc, signature=True):
        text = doc.split("\n", 2)[2] if signature and doc and "\n" in doc else doc
        return bool(text and text.strip())
    assert described(ssgi.__doc__, False)
    for name in ssgi.__all__:
        value = getattr(ssgi, name)
        if not isinstance(value, type):
            assert described(value.__doc__, not inspect.isfunction(value)), name
            continue
        assert described(value.__doc__, False), name
        for member, attribute in module_members(value).items():
            if member not in vars(value) or member in ("__getstate__", "__setstate__"):
                continue  # an instance's attribute a Python class declares (Image.samples);
                # the pickling pair pybind11 makes, which it gives no docstring
            documented = vars(value)[member]
            if isinstance(documented, property):
                assert described(documented.__doc__, False), f"{name}.{member}"
            elif member not in ("__init__",) or name != "Settings":
                in_python = inspect.isfunction(documented)  # no signature line in its doc
                assert described(documented.__doc__, not in_python), f"{name}.{member}"
    assert "frames: Union[int, numpy.integer] = 1" in ssgi.Renderer.render.__doc__  # not handle


def test_version_is_the_projects():
    project = re.search(r"project\(ssgi VERSION ([0-9.]+)", (ROOT / "CMakeLists.txt").read_text())
    assert ssgi.__version__ == project.group(1)


def test_read_names_what_it_accepts():
    renderer = ssgi.Renderer(ssgi.Scene(CORNELL), (16, 16))
    with pytest.raises(ValueError, match="no frame rendered yet; call render"):
        renderer.images() and renderer.read("hdr")
    renderer.render()
    names = renderer.images()
    assert {"hdr", "ldr", "gbuffer.normal", "gbuffer.position", "ao.history"} <= set(names)
    for name in names:  # RGBA floats, or an image of integers as its integers, height x width
        image = renderer.read(name)
        assert image.ndim == 3 or (image.ndim == 2 and image.dtype.kind == "u"), name
    with pytest.raises(ValueError) as error:
        renderer.read("bogus")
    assert "no image named 'bogus'" in str(error.value) and "gbuffer.normal" in str(error.value)
    assert "ao" not in names  # GTAO's raw output is overwritten within the frame ...
    with pytest.raises(ValueError, match=r"'ao' shares its memory .* keep=\['ao'\]"):
        renderer.read("ao")
    kept = ssgi.Renderer(ssgi.Scene(CORNELL), (16, 16), keep=["ao"])  # ... unless kept
    kept.render()
    assert "ao" in kept.images() and kept.read("ao").shape == (16, 16, 4)


def test_the_camera_reads_as_set_camera_takes_it():
    renderer = ssgi.Renderer(ssgi.Scene(CORNELL), (16, 16))
    camera = renderer.camera
    renderer.set_camera(position=(0, 1, 2), target=(0, 1, 0), up=(1, 0, 0), fov=30)
    assert not np.allclose(renderer.camera["up"], camera["up"])
    renderer.set_camera(**{k: camera[k] for k in ("position", "target", "up", "fov")})
    for key in camera:
        assert np.allclose(renderer.camera[key], camera[key], atol=1e-6), key


def test_errors_in_pythons_words(tmp_path):
    scene = ssgi.Scene(CORNELL)
    with pytest.raises(TypeError, match="scene: expected an ssgi.Scene, got None"):
        ssgi.Renderer(None)
    with pytest.raises(TypeError, match="scene: expected an ssgi.Scene, got None"):
        ssgi.reference(None)
    with pytest.raises(ValueError, match=r"keep: no image named 'bogus' in this frame; the "
                                          r"images it can keep: .*\bao\b.*gbuffer.normal"):
        ssgi.Renderer(scene, (16, 16), keep=["bogus"])
    with pytest.raises(TypeError, match=r"keep: expected a list of image names, got a str"):
        ssgi.Renderer(scene, (16, 16), keep="ao")
    image = np.zeros((2, 2, 3), np.float32)
    with pytest.raises(TypeError, match=r"linear: expected True or False, got 'no' \(str\)"):
        ssgi.compare(image, image, linear="no")
    with pytest.raises(ValueError, match=r"cache_dir: the path '.*\\x00.*' holds a NUL"):
        ssgi.reference(scene, size=(2, 2), spp=1, cache_dir=str(tmp_path) + "/a\0b")
    with pytest.raises(TypeError, match=r"Scene\(\): incompatible|path: expected a path"):
        ssgi.Scene(b"scenes/cornell-box.json")


def test_warnings_are_python_warnings_of_the_modules_own_category(tmp_path, capfd):
    half = np.full((4, 4, 4), 0.5, np.float32)  # alpha 0.5: compare warns, as the program does
    ssgi.write_image(tmp_path / "half.png", half)
    assert issubclass(ssgi.SsgiWarning, UserWarning)
    with pytest.warns(ssgi.SsgiWarning, match=r"half.png: 16 pixels are not opaque"):
        ssgi.compare(tmp_path / "half.png", tmp_path / "half.png")
    with warnings.catch_warnings(record=True) as said:
        warnings.simplefilter("ignore", ssgi.SsgiWarning)
        ssgi.compare(tmp_path / "half.png", tmp_path / "half.png")
    assert said == []
    with warnings.catch_warnings(record=True) as said:
        warnings.simplefilter("default")  # once per place, as Python says its own
        for _ in range(3):
            ssgi.compare(tmp_path / "half.png", tmp_path / "half.png")
    assert len(said) == 1 and said[0].category is ssgi.SsgiWarning
    assert said[0].filename == __file__  # blamed on the caller's line
    assert "warning" not in capfd.readouterr().err  # nothing printed from C++


PYTHON_BLOCKS = re.findall(r"```python\n(.*?)```", (ROOT / "docs" / "python.md").read_text(),
                           re.S)


@pytest.mark.parametrize("block", PYTHON_BLOCKS, ids=[f"block{i}" for i in
                                                     range(len(PYTHON_BLOCKS))])
def test_every_python_block_of_the_docs_runs_from_another_folder(block, tmp_path):
    import os
    import subprocess
    import sys
    run = subprocess.run([sys.executable, "-c", block], cwd=tmp_path, capture_output=True,
                         text=True, env=dict(os.environ, SSGI_VALIDATION="1"))
    assert run.returncode == 0, run.stdout + run.stderr
    assert "validation" not in run.stderr.lower(), run.stderr


def test_the_docs_have_their_blocks():
    assert len(PYTHON_BLOCKS) >= 5  # a first image, a sweep, a dict, a golden test, a notebook
