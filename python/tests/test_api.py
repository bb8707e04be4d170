"""The public API: everything in brdffit.__all__ exists and is documented,
and so is every public method and property of its classes (help(brdffit)
is the reference)."""

import inspect

import brdffit


def _public_members(cls):
    for name, member in vars(cls).items():
        if name.startswith("_") or not (inspect.isfunction(member) or
                                        isinstance(member, (property,
                                                            classmethod))):
            continue
        yield name, member


def test_every_public_name_and_method_has_a_docstring():
    assert brdffit.__doc__
    missing = []
    for name in brdffit.__all__:
        obj = getattr(brdffit, name)
        if isinstance(obj, str):  # library_path
            continue
        if not inspect.getdoc(obj):
            missing.append(name)
        if inspect.isclass(obj):
            for mname, member in _public_members(obj):
                f = member.__func__ if isinstance(member, classmethod) \
                    else member
                if not inspect.getdoc(f):
                    missing.append("%s.%s" % (name, mname))
    assert not missing, "undocumented: " + ", ".join(missing)


def test_the_exceptions_derive_from_the_builtin_a_caller_expects():
    assert issubclass(brdffit.ParseError, ValueError)
    assert issubclass(brdffit.InvalidArgumentError, ValueError)
    assert issubclass(brdffit.DomainError, ValueError)
    assert issubclass(brdffit.LoadError, OSError)
    assert issubclass(brdffit.NotFoundError, LookupError)
    assert issubclass(brdffit.OutOfMemoryError, MemoryError)
    assert issubclass(brdffit.ConvergenceError, RuntimeError)
    assert issubclass(brdffit.DomainWarning, RuntimeWarning)
    for cls in (brdffit.ParseError, brdffit.LoadError, brdffit.NotFoundError):
        assert issubclass(cls, brdffit.BrdffitError)


