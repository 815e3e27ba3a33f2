"""Every enum of the module is bound from its C++ table (python/src/enum_binding.hpp): each member's docstring is its
table row, '"name": meaning', with the name that files, the CLI and JSON use. An enum bound by hand, or a member
without a row, has no such docstring and fails here (tests/unit/test_enum_tables.cpp checks the tables in C++)."""
import re

import needlekit as nk
import needlekit._needlekit as module

ROW = re.compile(r'^"([^"]+)": (.+)$')


def enums():
    return {name: value for name, value in vars(module).items()
            if isinstance(value, type) and hasattr(value, "__members__")}


def rows(enum):
    """{member name: (value, table name, meaning)} from the docstrings bind_enum gives the members."""
    out = {}
    for member, (value, doc) in getattr(enum, "__entries").items():
        match = ROW.match(doc or "")
        assert match, f"{enum.__name__}.{member} has no table row in its docstring: {doc!r}"
        out[member] = (int(value), match.group(1), match.group(2))
    return out


def test_the_module_has_its_enums():
    assert len(enums()) >= 37


def test_every_member_of_every_enum_comes_from_a_table_row():
    for enum in enums().values():
        table = rows(enum)
        assert list(table) == list(enum.__members__), enum.__name__
        names = [name for _, name, _ in table.values()]
        assert len(set(names)) == len(names), enum.__name__


def test_the_rows_say_what_the_library_says():
    for member, (_, name, _) in rows(nk.Dimension).items():
        assert nk.dimension_name(getattr(nk.Dimension, member)) == name
    for member, (_, name, _) in rows(nk.PerformanceStatus).items():
        assert nk.performance_status_name(getattr(nk.PerformanceStatus, member)) == name
    assert rows(nk.Shape)["Bevel"][1] == "bevel"
    assert rows(nk.ArraySymmetry)["None_"][1] == "none"
    assert rows(nk.ExitCode)["Interrupted"][0] == 130

