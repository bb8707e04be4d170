"""The package's version: the library's (include/brdffit.h BF_VERSION_STRING;
python/tests/test_models.py checks that they agree)."""
VERSION = "0.1.0"
