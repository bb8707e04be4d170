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


def test_records_keep_names_and_words_as_text_and_numbers_as_numbers():
    from brdffit.records import Records
    text = ("sample,name,channel,model,parameter,unit,value,lse,flags\n"
            "1,123,550,FC-E,m,1,0.25,3,\n"
            "2,0.5,600,FC-E,n,1,1.5,4,clamped\n")
    r = Records.from_csv(text)
    assert r.columns[:3] == ("sample", "name", "channel")
    # a material named "123", a wavelength channel "550", a unit "1" stay
    # text; the numeric columns convert
    assert [x["name"] for x in r] == ["123", "0.5"]
    assert [x["channel"] for x in r] == ["550", "600"]
    assert [x["unit"] for x in r] == ["1", "1"]
    assert [x["sample"] for x in r] == [1, 2]
    assert [x["value"] for x in r] == [0.25, 1.5]
    assert [x["lse"] for x in r] == [3, 4]
    assert [x["flags"] for x in r] == [None, "clamped"]
