"""The package's C declarations (brdffit/_lib.py, cffi ABI mode) against
include/brdffit.h, compiled: a difference would make the package read the
wrong bytes or call a function wrongly, silently, so every one fails here.

A C program is generated from the declarations themselves: it redeclares
every function and global variable of the cdef (with its const qualifiers,
as written; a redeclaration that differs from the header's is a compile
error), and prints the sizeof and every field's offset and size of every
struct, and the value of every constant, which are compared with what
cffi computed.
"""

import os
import re
import subprocess

import pycparser
from pycparser import c_ast, c_generator

from brdffit import _lib, _report
from brdffit._lib import ffi, lib

# Constants the package defines in Python (not parsable by cffi), with the
# C expression each must equal.
PY_CONSTANTS = {
    "CHANNEL_MEAN": ("%zu", "(size_t)BF_CHANNEL_MEAN"),
    "CONE_DEFAULT": ("%.17g", "(double)BF_CONE_DEFAULT"),
    "DEFAULT_N": ("%.17g", "(double)BF_DEFAULT_N"),
    "FREE_N_LO": ("%.17g", "(double)BF_FREE_N_LO"),
    "FREE_N_HI": ("%.17g", "(double)BF_FREE_N_HI"),
    "TIE_REL": ("%.17g", "(double)BF_TIE_REL"),
}


def _declarations():
    """The function and variable declarations of the cdef, as C text."""
    text = re.sub(r"/\*.*?\*/", "", _lib.CDEF + _lib.LIBC_CDEF +
                  _report.REPORT_CDEF, flags=re.S)
    text = re.sub(r"^\s*#.*$", "", text, flags=re.M)
    # size_t is built into cffi's parser, not pycparser's.
    ast = pycparser.CParser().parse("typedef unsigned long size_t;\n" + text)
    gen = c_generator.CGenerator()
    out = []
    for node in ast.ext:
        if not isinstance(node, c_ast.Decl) or node.name in (None, "size_t"):
            continue
        if isinstance(node.type, c_ast.FuncDecl) or "extern" in node.storage:
            out.append(gen.visit(node) + ";")
    return out


def _structs():
    """(typedef name, [field names]) of every struct the cdef defines."""
    out = []
    for name in ffi.list_types()[0]:
        if name == "gsl_error_handler_t":  # a function type, not an object
            continue
        t = ffi.typeof(name)
        if t.kind == "struct" and t.fields is not None:
            out.append((name, [f for f, _ in t.fields]))
    return out


def _constants():
    """Names of the integer constants (enums, #defines) the cdef knows."""
    return [n for n in dir(lib) if n.startswith("BF_")]


def _program():
    lines = ["#include <stddef.h>", "#include <stdio.h>",
             "#include <gsl/gsl_errno.h>", '#include "brdffit.h"']
    lines += _declarations()
    lines.append("int main(void)\n{")
    for name, fields in _structs():
        lines.append('    printf("sizeof %s %%zu\\n", sizeof(%s));'
                     % (name, name))
        for f in fields:
            lines.append('    printf("offsetof %s.%s %%zu %%zu\\n", '
                         'offsetof(%s, %s), sizeof(((%s *)0)->%s));'
                         % (name, f, name, f, name, f))
    for c in _constants():
        lines.append('    printf("const %s %%lld\\n", (long long)%s);'
                     % (c, c))
    for py, (fmt, expr) in PY_CONSTANTS.items():
        lines.append('    printf("py %s %s\\n", %s);' % (py, fmt, expr))
    lines.append('    printf("version %s\\n", BF_VERSION_STRING);')
    lines.append("    return 0;\n}")
    return "\n".join(lines) + "\n"


def _expected():
    out = []
    for name, fields in _structs():
        out.append("sizeof %s %d" % (name, ffi.sizeof(name)))
        for f, field in ffi.typeof(name).fields:
            out.append("offsetof %s.%s %d %d" % (name, f, field.offset,
                                                 ffi.sizeof(field.type)))
    for c in _constants():
        out.append("const %s %d" % (c, getattr(lib, c)))
    for py, (fmt, _) in PY_CONSTANTS.items():
        out.append("py %s %s" % (py, fmt.replace("%zu", "%d") %
                                 getattr(_lib, py)))
    import brdffit
    out.append("version %s" % brdffit.__version__)
    return out


def test_every_declaration_struct_and_constant_matches_the_header(
        tmp_path, include_dir):
    src = tmp_path / "layout.c"
    src.write_text(_program())
    exe = tmp_path / "layout"
    cc = os.environ.get("CC") or "cc"
    build = subprocess.run(
        [cc, "-std=c11", "-Wall", "-Wextra", "-Werror", "-D_XOPEN_SOURCE=700",
         "-I", include_dir, "-o", str(exe), str(src)],
        capture_output=True, text=True)
    assert build.returncode == 0, (
        "the cdef's declarations do not compile against brdffit.h:\n"
        + build.stderr)
    run = subprocess.run([str(exe)], capture_output=True, text=True,
                         check=True)
    got = run.stdout.splitlines()
    expected = _expected()
    diff = [(e, g) for e, g in zip(expected, got) if e != g]
    assert len(got) == len(expected) and not diff, (
        "cffi (expected) vs the compiled header (got):\n" +
        "\n".join("  %s  |  %s" % d for d in diff))


def test_the_check_covers_every_struct_and_function_the_package_uses():
    structs = {name for name, _ in _structs()}
    assert {"bf_error", "bf_geom", "bf_param", "bf_model_type",
            "bf_material_desc", "bf_selection", "bf_load_opts",
            "bf_fit_result", "bf_target", "bf_study_spec", "bf_study_row",
            "bf_analysis_opts", "bf_fit_stats", "bf_fits_line",
            "bf_ranking_line", "bf_report_options",
            "bf_report_inputs"} <= structs
    names = " ".join(_declarations())
    for fn in ("bf_model_eval", "bf_dataset_load", "bf_study_run",
               "bf_study_analyse", "bf_study_samples", "bf_report_write",
               "bf_fits_lines", "bf_ranking_lines", "bf_ranking_slots"):
        assert fn in names
