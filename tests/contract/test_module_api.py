"""Every module states its public API in ``__all__`` (issue #17, the rosbags style): the names it
defines or deliberately re-exports for other modules, tests and users; a reader and mypy's
``no_implicit_reexport`` see what is meant to be used. The sources are parsed, not imported
(fast, and no rclpy needed). Not checked: setup.py, launch files, and package ``__init__.py``
files that hold nothing but a docstring."""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
SOURCE_ROOTS = [ROOT / "msgs", ROOT / "sim_bridge", *sorted(p for p in (ROOT / "src").iterdir() if p.is_dir())]


def _module_name(path: Path) -> str:
    """``door_contract.converters.pose`` of ``msgs/door_contract/converters/pose.py``."""
    root = next(r for r in SOURCE_ROOTS if r in path.parents)
    parts = path.relative_to(root).with_suffix("").parts
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def _docstring_only(tree: ast.Module) -> bool:
    return all(isinstance(node, ast.Expr) and isinstance(node.value, ast.Constant) for node in tree.body)


def _sources() -> dict[str, tuple[Path, ast.Module]]:
    sources = {}
    for root in SOURCE_ROOTS:
        for path in sorted(root.rglob("*.py")):
            if path.name == "setup.py" or "launch" in path.relative_to(root).parts or "__pycache__" in path.parts:
                continue
            sources[_module_name(path)] = (path, ast.parse(path.read_text(), str(path)))
    return sources


SOURCES = _sources()
MODULES = {name: source for name, source in SOURCES.items()
           if not (source[0].name == "__init__.py" and _docstring_only(source[1]))}


def _bound_names(body: list[ast.stmt]) -> set[str]:
    """The names a module's top level binds: definitions, assignments and imports (also inside a
    top-level ``if`` / ``try``, e.g. ``if TYPE_CHECKING:``)."""
    names: set[str] = set()
    for node in body:
        if isinstance(node, ast.FunctionDef | ast.AsyncFunctionDef | ast.ClassDef):
            names.add(node.name)
        elif isinstance(node, ast.Assign | ast.AnnAssign | ast.AugAssign):
            targets = node.targets if isinstance(node, ast.Assign) else [node.target]
            names.update(n.id for t in targets for n in ast.walk(t) if isinstance(n, ast.Name))
        elif isinstance(node, ast.Import):
            names.update(alias.asname or alias.name.split(".")[0] for alias in node.names)
        elif isinstance(node, ast.ImportFrom):
            names.update(alias.asname or alias.name for alias in node.names)
        elif isinstance(node, ast.If | ast.Try | ast.With):
            names |= _bound_names(node.body)
            names |= _bound_names(getattr(node, "orelse", []))
            for handler in getattr(node, "handlers", []):
                names |= _bound_names(handler.body)
            names |= _bound_names(getattr(node, "finalbody", []))
    return names


def _declared_all(tree: ast.Module) -> list[str] | None:
    """The strings of the module's ``__all__ = [...]``; None without one."""
    for node in tree.body:
        if isinstance(node, ast.Assign) and any(isinstance(t, ast.Name) and t.id == "__all__" for t in node.targets):
            assert isinstance(node.value, ast.List | ast.Tuple), "__all__ is not a list literal"
            values = [element.value for element in node.value.elts if isinstance(element, ast.Constant)]
            assert len(values) == len(node.value.elts) and all(isinstance(v, str) for v in values), \
                "__all__ holds something else than string literals"
            return values
    return None


def test_the_walk_finds_the_modules():
    assert len(MODULES) > 200 and "door_contract.payloads" in MODULES and "door_contract" not in MODULES


@pytest.mark.parametrize("module", sorted(MODULES))
def test_module_states_its_public_api(module):
    path, tree = MODULES[module]
    declared = _declared_all(tree)
    assert declared is not None, f"{path.relative_to(ROOT)} has no __all__"
    assert declared, f"{module}.__all__ is empty"
    assert len(set(declared)) == len(declared), f"{module}.__all__ lists a name twice"
    private = [name for name in declared if name.startswith("_")]
    assert not private, f"{module}.__all__ lists private names {private}"
    missing = sorted(set(declared) - _bound_names(tree.body))
    assert not missing, f"{module}.__all__ lists names the module neither defines nor imports: {missing}"


def _imports_from_our_modules() -> list[tuple[str, str, str]]:
    """(importing file, module, name) of every ``from <our module> import <name>`` in the
    sources, their launch and setup files and the tests; submodules and private names left out."""
    files = sorted({*ROOT.joinpath("tests").rglob("*.py"), *(p for r in SOURCE_ROOTS for p in r.rglob("*.py"))})
    found = []
    for path in files:
        if "__pycache__" in path.parts:
            continue
        for node in ast.walk(ast.parse(path.read_text(), str(path))):
            if isinstance(node, ast.ImportFrom) and node.level == 0 and node.module in MODULES:
                found += [(str(path.relative_to(ROOT)), node.module, alias.name) for alias in node.names
                          if not alias.name.startswith("_") and f"{node.module}.{alias.name}" not in SOURCES]
    return found


def test_what_other_modules_import_is_listed():
    """A public name imported from one of our modules is in that module's ``__all__`` (tests may
    import private helpers: those are not public API and not checked)."""
    unlisted = [f"{importer}: from {module} import {name}" for importer, module, name in _imports_from_our_modules()
                if name not in (_declared_all(MODULES[module][1]) or [])]
    assert not unlisted, "imported but not in the module's __all__:\n" + "\n".join(unlisted)
